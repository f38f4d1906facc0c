# GJK core tests: closed forms, random polytopes against the long double oracle, hard cases.
kairos_gtest(test_gjk SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_gjk.cpp LIBS kairos_core)
# The same queries through the shared library's C ABI.
kairos_gtest(test_gjk_capi SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/test_gjk_capi.cpp LIBS kairos)
