# SPDX-License-Identifier: MIT
# kairos_fcl: the adapter's conversions against closed forms, and the checker on FCL's known wrong
# answers (fcl#508, the GST_INDEP hull pair) and on cases where FCL is right. Needs FCL (fcl/).
if(TARGET kairos_fcl_campaign)
    kairos_gtest(test_fcl_adapter SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/fcl/test_fcl_adapter.cpp
        LIBS kairos_fcl_campaign)
else()
    message(STATUS "test_fcl_adapter skipped: kairos_fcl is not built (FCL not found, or KAIROS_BUILD_FCL_CHECK off)")
endif()
