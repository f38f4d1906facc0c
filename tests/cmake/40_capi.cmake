# The C boundary through the shared library: bad input for every exported function.
kairos_gtest(test_capi SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_input.cpp LIBS kairos)
