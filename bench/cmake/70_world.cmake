# SPDX-License-Identifier: MIT
# Broad phases: Kairos's space-time sweeps against FCL's DynamicAABBTree and Bullet f64's
# bt32BitAxisSweep3 and btDbvtBroadphase, in one program (scripts/world-chart.sh draws the chart).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_WORLD_FCL QUIET fcl)
    pkg_check_modules(KAIROS_WORLD_BULLET64 QUIET bullet-float64)
endif()
find_library(KAIROS_WORLD_BULLET64_COLLISION BulletCollision-float64)
find_library(KAIROS_WORLD_BULLET64_MATH LinearMath-float64)
if(KAIROS_WORLD_FCL_FOUND AND KAIROS_WORLD_BULLET64_FOUND AND KAIROS_WORLD_BULLET64_COLLISION AND KAIROS_WORLD_BULLET64_MATH)
    add_executable(bench_world ${CMAKE_CURRENT_SOURCE_DIR}/bench_world.cpp)
    # Peers' headers as system headers; FCL's pkg-config -std=c++11 is left out on purpose.
    target_include_directories(bench_world SYSTEM PRIVATE ${KAIROS_WORLD_FCL_INCLUDE_DIRS} ${KAIROS_WORLD_BULLET64_INCLUDE_DIRS})
    target_include_directories(bench_world PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
    target_compile_definitions(bench_world PRIVATE BT_USE_DOUBLE_PRECISION)
    target_link_libraries(bench_world PRIVATE kairos_core benchmark::benchmark ${KAIROS_WORLD_FCL_LINK_LIBRARIES}
                                              ${KAIROS_WORLD_BULLET64_COLLISION} ${KAIROS_WORLD_BULLET64_MATH})
    kairos_warnings(bench_world)
else()
    message(STATUS "bench_world skipped: needs FCL and Bullet's double build (pkg-config fcl, bullet-float64)")
endif()

# World queries against brute force, and the step's scaling with worker threads (no peers).
add_executable(bench_world_queries ${CMAKE_CURRENT_SOURCE_DIR}/bench_world_queries.cpp)
target_include_directories(bench_world_queries PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
target_link_libraries(bench_world_queries PRIVATE kairos_core benchmark::benchmark)
kairos_warnings(bench_world_queries)

# The batches against single calls through the shared library (bench/python/bench_batch.py
# measures the same scene from Python).
add_executable(bench_batch ${CMAKE_CURRENT_SOURCE_DIR}/bench_batch.cpp)
target_link_libraries(bench_batch PRIVATE kairos benchmark::benchmark)
kairos_warnings(bench_batch)
