# SPDX-License-Identifier: MIT
# Stability catalogue: families of hard cases through Kairos (public C API) and every peer query
# (libccd, FCL, Bullet f64), failure rates per method and family. A plain program (no Google
# Benchmark): it counts failures against exact truths, it does not time anything.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_ST_FCL QUIET fcl)
    pkg_check_modules(KAIROS_ST_CCD QUIET ccd)
    pkg_check_modules(KAIROS_ST_BULLET64 QUIET bullet-float64)
endif()
find_library(KAIROS_ST_BULLET64_COLLISION BulletCollision-float64)
find_library(KAIROS_ST_BULLET64_MATH LinearMath-float64)
if(KAIROS_ST_FCL_FOUND AND KAIROS_ST_CCD_FOUND AND KAIROS_ST_BULLET64_FOUND AND KAIROS_ST_BULLET64_COLLISION
   AND KAIROS_ST_BULLET64_MATH)
    add_executable(bench_stability ${CMAKE_CURRENT_SOURCE_DIR}/stability.cpp)
    # tests/ for the long-double oracles only; Kairos itself is used through kairos.h.
    target_include_directories(bench_stability PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
    # Peers' headers as system headers; FCL's pkg-config -std=c++11 is left out on purpose.
    target_include_directories(bench_stability SYSTEM PRIVATE ${KAIROS_ST_FCL_INCLUDE_DIRS} ${KAIROS_ST_CCD_INCLUDE_DIRS}
                                                              ${KAIROS_ST_BULLET64_INCLUDE_DIRS})
    target_compile_definitions(bench_stability PRIVATE BT_USE_DOUBLE_PRECISION)
    target_link_libraries(bench_stability PRIVATE kairos ${KAIROS_ST_FCL_LINK_LIBRARIES} ${KAIROS_ST_CCD_LINK_LIBRARIES}
                                                  ${KAIROS_ST_BULLET64_COLLISION} ${KAIROS_ST_BULLET64_MATH})
    kairos_warnings(bench_stability)
else()
    message(STATUS "bench_stability skipped: needs FCL, libccd and Bullet's double build (pkg-config fcl, ccd, bullet-float64)")
endif()
