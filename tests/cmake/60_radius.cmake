# SPDX-License-Identifier: MIT
# Extreme radius about an axis (the rotation bound's size).
kairos_gtest(test_radius SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/shapes/test_radius.cpp LIBS kairos_core)
