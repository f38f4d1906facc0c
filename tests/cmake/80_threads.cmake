# SPDX-License-Identifier: MIT
# Shapes shared across threads and one world per thread, through the shared library; the `tsan`
# preset builds and runs only this (label test_threads) under ThreadSanitizer.
kairos_gtest(test_threads SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_threads.cpp LIBS kairos)
