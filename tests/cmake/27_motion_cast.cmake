# SPDX-License-Identifier: MIT
# Motion cast (rotation by disk bounds with bisection): random rotating pairs of every kind against
# the conservative-advancement reference, closed forms, hard cases. MotionCastLong.* is the long
# run (10^5 casts), disabled unless asked for.
kairos_gtest(test_motion_cast SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/motion/test_motion_cast.cpp LIBS kairos_core)
# The motion cast through the C boundary (shared library).
kairos_gtest(test_capi_motion SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_motion.cpp LIBS kairos)
# Peers, each in its own executable: FCL's conservative advancement with screw motion and zero
# translation (every call in a forked child), and Bullet's btContinuousConvexCollision in its
# double build (never linked with the float build).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_MOTION_FCL QUIET fcl)
    pkg_check_modules(KAIROS_MOTION_BULLET64 QUIET bullet-float64)
endif()
find_library(KAIROS_MOTION_BULLET64_COLLISION BulletCollision-float64)
find_library(KAIROS_MOTION_BULLET64_MATH LinearMath-float64)
if(KAIROS_MOTION_FCL_FOUND)
    kairos_gtest(test_motion_cast_fcl SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/motion/test_motion_cast_fcl.cpp
                 LIBS kairos_core ${KAIROS_MOTION_FCL_LINK_LIBRARIES})
    # FCL's pkg-config -std=c++11 is left out on purpose (only include directories are taken).
    target_include_directories(test_motion_cast_fcl SYSTEM PRIVATE ${KAIROS_MOTION_FCL_INCLUDE_DIRS})
else()
    message(STATUS "test_motion_cast_fcl skipped: needs FCL (pkg-config fcl)")
endif()
if(KAIROS_MOTION_BULLET64_FOUND AND KAIROS_MOTION_BULLET64_COLLISION AND KAIROS_MOTION_BULLET64_MATH)
    kairos_gtest(test_motion_cast_bullet SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/motion/test_motion_cast_bullet.cpp
                 LIBS kairos_core ${KAIROS_MOTION_BULLET64_COLLISION} ${KAIROS_MOTION_BULLET64_MATH})
    target_include_directories(test_motion_cast_bullet SYSTEM PRIVATE ${KAIROS_MOTION_BULLET64_INCLUDE_DIRS})
    target_compile_definitions(test_motion_cast_bullet PRIVATE BT_USE_DOUBLE_PRECISION)
else()
    message(STATUS "test_motion_cast_bullet skipped: needs Bullet's double build (pkg-config bullet-float64)")
endif()
