# SPDX-License-Identifier: MIT
# Ray cast and shape cast: random casts of every pair of kinds against the long double oracles,
# closed forms, hard cases. CastLong.* is the long run (10^6 casts), disabled unless asked for.
kairos_gtest(test_cast SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast_rounded.cpp ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast_graze.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast_degenerate.cpp ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_cast_rounded_loose.cpp
             ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_box_cast.cpp ${CMAKE_CURRENT_SOURCE_DIR}/casts/test_capsule_cast.cpp
             LIBS kairos_core)
# The two casts through the C boundary (shared library).
kairos_gtest(test_capi_cast SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_capi_cast.cpp LIBS kairos)
