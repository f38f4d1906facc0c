# SPDX-License-Identifier: MIT
# The world's step: on the core against brute force and pairwise casts, and through the C API.
kairos_gtest(test_world SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/world/test_world.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/world/test_world_placed.cpp LIBS kairos_core)
kairos_gtest(test_workers SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/world/test_workers.cpp LIBS kairos_core)
kairos_gtest(test_world_queries SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/world/test_world_queries.cpp LIBS kairos_core)
kairos_gtest(test_world_capi SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_world_capi.cpp LIBS kairos)
