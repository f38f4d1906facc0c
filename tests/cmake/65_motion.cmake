# SPDX-License-Identifier: MIT
# Motion over a step and the rotation disk bound.
kairos_gtest(test_motion SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/motion/test_motion.cpp LIBS kairos_core)
