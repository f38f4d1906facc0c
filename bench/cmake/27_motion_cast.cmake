# SPDX-License-Identifier: MIT
# Motion cast accuracy/speed over tolerances and rotation angles, with FCL (screw motion, zero
# translation, conservative advancement) and Bullet f64's btContinuousConvexCollision in one program.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_MB_FCL QUIET fcl)
    pkg_check_modules(KAIROS_MB_BULLET64 QUIET bullet-float64)
endif()
find_library(KAIROS_MB_BULLET64_COLLISION BulletCollision-float64)
find_library(KAIROS_MB_BULLET64_MATH LinearMath-float64)
if(KAIROS_MB_FCL_FOUND AND KAIROS_MB_BULLET64_FOUND AND KAIROS_MB_BULLET64_COLLISION AND KAIROS_MB_BULLET64_MATH)
    add_executable(bench_motion_cast ${CMAKE_CURRENT_SOURCE_DIR}/bench_motion_cast.cpp)
    target_include_directories(bench_motion_cast PRIVATE ${PROJECT_SOURCE_DIR}/tests/support ${CMAKE_CURRENT_SOURCE_DIR})
    # Peers' headers as system headers; FCL's pkg-config -std=c++11 is left out on purpose.
    target_include_directories(bench_motion_cast SYSTEM PRIVATE ${KAIROS_MB_FCL_INCLUDE_DIRS} ${KAIROS_MB_BULLET64_INCLUDE_DIRS})
    target_compile_definitions(bench_motion_cast PRIVATE BT_USE_DOUBLE_PRECISION)
    target_link_libraries(bench_motion_cast PRIVATE kairos_core benchmark::benchmark ${KAIROS_MB_FCL_LINK_LIBRARIES}
                                                    ${KAIROS_MB_BULLET64_COLLISION} ${KAIROS_MB_BULLET64_MATH})
    kairos_warnings(bench_motion_cast)
else()
    message(STATUS "bench_motion_cast skipped: needs FCL and Bullet's double build (pkg-config fcl, bullet-float64)")
endif()
