# SPDX-License-Identifier: MIT
# The broad phase core: space-time sweep and prune against brute force and the encapsulating sweep.
kairos_gtest(test_broadphase SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/broadphase/test_broadphase.cpp LIBS kairos_core)
