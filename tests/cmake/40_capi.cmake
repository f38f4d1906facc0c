# SPDX-License-Identifier: MIT
# The C boundary through the shared library: bad input for every exported function.
kairos_gtest(test_capi SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_input.cpp LIBS kairos)
# Flat shapes in every query against closed forms, and the contract regressions of issue 11.
kairos_gtest(test_capi_flat SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_flat.cpp LIBS kairos)
kairos_gtest(test_capi_contract SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_contract.cpp LIBS kairos)
# GJK at the rounding limit (issue 12): the reported cases in both orders and a sweep over every
# pair of shape kinds at constructed gaps, every answer checked against its own certificate.
kairos_gtest(test_capi_edges SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_edges.cpp LIBS kairos)
# The batches against their single calls, on the calling thread, a world's threads and a task hook.
kairos_gtest(test_capi_batch SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_batch.cpp LIBS kairos)
