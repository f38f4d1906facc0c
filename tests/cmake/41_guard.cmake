# SPDX-License-Identifier: MIT
# The C boundary's guard, built from capi/ sources so exceptions can be thrown into it on purpose.
file(GLOB KAIROS_GUARD_CAPI_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/capi/*.cpp)
kairos_gtest(test_guard SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/capi/test_guard.cpp ${KAIROS_GUARD_CAPI_SOURCES} LIBS kairos_core)
target_include_directories(test_guard PRIVATE ${PROJECT_SOURCE_DIR}/capi ${PROJECT_SOURCE_DIR}/include ${KAIROS_GENERATED_INCLUDE})
