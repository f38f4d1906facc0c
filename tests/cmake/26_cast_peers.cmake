# SPDX-License-Identifier: MIT
# Cast peers, each in its own executable: Bullet's double build (never linked with the float
# build) and FCL's conservative advancement (every call in a forked child).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_CAST_BULLET64 QUIET bullet-float64)
    pkg_check_modules(KAIROS_CAST_FCL QUIET fcl)
endif()
find_library(KAIROS_CAST_BULLET64_COLLISION BulletCollision-float64)
find_library(KAIROS_CAST_BULLET64_MATH LinearMath-float64)
if(KAIROS_CAST_BULLET64_FOUND AND KAIROS_CAST_BULLET64_COLLISION AND KAIROS_CAST_BULLET64_MATH)
    kairos_gtest(test_cast_bullet SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast_bullet.cpp
                 LIBS kairos_core ${KAIROS_CAST_BULLET64_COLLISION} ${KAIROS_CAST_BULLET64_MATH})
    target_include_directories(test_cast_bullet SYSTEM PRIVATE ${KAIROS_CAST_BULLET64_INCLUDE_DIRS})
    target_compile_definitions(test_cast_bullet PRIVATE BT_USE_DOUBLE_PRECISION)
else()
    message(STATUS "test_cast_bullet skipped: needs Bullet's double build (pkg-config bullet-float64)")
endif()
if(KAIROS_CAST_FCL_FOUND)
    kairos_gtest(test_cast_fcl SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast_fcl.cpp
                 LIBS kairos_core ${KAIROS_CAST_FCL_LINK_LIBRARIES})
    # FCL's pkg-config -std=c++11 is left out on purpose (only include directories are taken).
    target_include_directories(test_cast_fcl SYSTEM PRIVATE ${KAIROS_CAST_FCL_INCLUDE_DIRS})
else()
    message(STATUS "test_cast_fcl skipped: needs FCL (pkg-config fcl)")
endif()
