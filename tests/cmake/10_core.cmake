# SPDX-License-Identifier: MIT
# Core shapes: support mappings of every kind, convex hull construction, bounds, thread safety.
kairos_gtest(test_shapes
    SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/shapes/test_shapes.cpp ${CMAKE_CURRENT_SOURCE_DIR}/shapes/test_hull.cpp
    LIBS kairos_core)

# The math layer's helpers against the standard library.
kairos_gtest(test_math
    SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/math/test_math.cpp
    LIBS kairos_core)
