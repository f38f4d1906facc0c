# SPDX-License-Identifier: MIT
# GJK core tests: closed forms, random polytopes against the long double oracle, hard cases.
kairos_gtest(test_gjk SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_gjk.cpp ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_gjk_seed.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_support_kernels.cpp ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_near_ranking.cpp
             LIBS kairos_core)
kairos_gtest(test_closed_forms SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_closed_forms.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_box_pair_distance.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_rigid_placement.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_rigid_placement_edges.cpp LIBS kairos_core)
# The same queries through the shared library's C ABI.
kairos_gtest(test_gjk_capi SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_gjk_capi.cpp LIBS kairos)

# Peer cross-checks. FCL and libccd in one executable; Bullet's double build in another (its
# symbols clash with the float build's, so it never shares a binary with anything linking that).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
    pkg_check_modules(KAIROS_FCL QUIET fcl)
    pkg_check_modules(KAIROS_CCD QUIET ccd)
    pkg_check_modules(KAIROS_BULLET64 QUIET bullet-float64)
endif()
if(KAIROS_FCL_FOUND AND KAIROS_CCD_FOUND)
    kairos_gtest(test_gjk_peers SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_gjk_peers.cpp LIBS kairos_core)
    # pkg-config's fcl flags carry -std=c++11: take only its include directories and libraries.
    target_include_directories(test_gjk_peers SYSTEM PRIVATE ${KAIROS_FCL_INCLUDE_DIRS} ${KAIROS_CCD_INCLUDE_DIRS})
    target_link_libraries(test_gjk_peers PRIVATE ${KAIROS_FCL_LINK_LIBRARIES} ${KAIROS_CCD_LINK_LIBRARIES})
else()
    message(STATUS "test_gjk_peers skipped: FCL or libccd not found (pkg-config fcl, ccd)")
endif()
if(KAIROS_BULLET64_FOUND)
    kairos_gtest(test_gjk_bullet SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_gjk_bullet.cpp LIBS kairos_core)
    target_include_directories(test_gjk_bullet SYSTEM PRIVATE ${KAIROS_BULLET64_INCLUDE_DIRS})
    target_compile_definitions(test_gjk_bullet PRIVATE BT_USE_DOUBLE_PRECISION)
    find_library(KAIROS_BULLET64_COLLISION BulletCollision-float64)
    find_library(KAIROS_BULLET64_MATH LinearMath-float64)
    target_link_libraries(test_gjk_bullet PRIVATE ${KAIROS_BULLET64_COLLISION} ${KAIROS_BULLET64_MATH})
else()
    message(STATUS "test_gjk_bullet skipped: bullet-float64 not found")
endif()

# Near contact on curved surfaces against a closed-form gap.
kairos_gtest(test_gjk_curved SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_gjk_curved_contact.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_gjk_slides.cpp LIBS kairos_core)

# Signed distance (EPA) against closed forms, the polytope oracle and the touching invariant.
kairos_gtest(test_penetration SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_penetration.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_tilted_contacts.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/gjk/test_coaxial_depth.cpp LIBS kairos_core)
