# SPDX-License-Identifier: MIT
# GJK distance and intersection against FCL (GST_INDEP), Bullet f64 and libccd, in one program.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_BENCH_FCL QUIET fcl)
    pkg_check_modules(KAIROS_BENCH_CCD QUIET ccd)
    pkg_check_modules(KAIROS_BENCH_BULLET64 QUIET bullet-float64)
endif()
find_library(KAIROS_BENCH_BULLET64_COLLISION BulletCollision-float64)
find_library(KAIROS_BENCH_BULLET64_MATH LinearMath-float64)
if(KAIROS_BENCH_FCL_FOUND AND KAIROS_BENCH_CCD_FOUND AND KAIROS_BENCH_BULLET64_FOUND AND KAIROS_BENCH_BULLET64_COLLISION)
    add_executable(bench_gjk ${CMAKE_CURRENT_SOURCE_DIR}/bench_gjk.cpp)
    target_include_directories(bench_gjk PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
    # Peers' headers as system headers; FCL's pkg-config -std=c++11 is left out on purpose.
    target_include_directories(bench_gjk SYSTEM PRIVATE ${KAIROS_BENCH_FCL_INCLUDE_DIRS} ${KAIROS_BENCH_CCD_INCLUDE_DIRS}
                                                        ${KAIROS_BENCH_BULLET64_INCLUDE_DIRS})
    target_compile_definitions(bench_gjk PRIVATE BT_USE_DOUBLE_PRECISION)
    target_link_libraries(bench_gjk PRIVATE kairos::kairos kairos_core benchmark::benchmark ${KAIROS_BENCH_FCL_LINK_LIBRARIES}
                                            ${KAIROS_BENCH_CCD_LINK_LIBRARIES} ${KAIROS_BENCH_BULLET64_COLLISION}
                                            ${KAIROS_BENCH_BULLET64_MATH})
    kairos_warnings(bench_gjk)
else()
    message(STATUS "bench_gjk skipped: needs FCL, libccd and Bullet's double build (pkg-config fcl, ccd, bullet-float64)")
endif()
