// SPDX-License-Identifier: MIT
// The guard around every exported function: each kind of C++ exception becomes a status and a
// message, and nothing escapes. Built from the C boundary's sources, since out-of-memory and
// internal errors cannot be provoked on purpose through the public functions.
#include <gtest/gtest.h>

#include <new>
#include <stdexcept>
#include <string>

#include "boundary.hpp"

using kairos::capi::guarded;

TEST(Guard, MapsEveryExceptionToAStatus) {
    EXPECT_EQ(guarded("f_ok", [] {}), KAIROS_OK);

    EXPECT_EQ(guarded("f_oom", [] { throw std::bad_alloc(); }), KAIROS_ERROR_OUT_OF_MEMORY);
    EXPECT_EQ(std::string(kairos_last_error()), "f_oom: out of memory");

    EXPECT_EQ(guarded("f_std", [] { throw std::logic_error("broken invariant"); }), KAIROS_ERROR_INTERNAL);
    EXPECT_EQ(std::string(kairos_last_error()), "f_std: internal error: broken invariant");

    EXPECT_EQ(guarded("f_other", [] { throw 42; }), KAIROS_ERROR_INTERNAL);
    EXPECT_EQ(std::string(kairos_last_error()), "f_other: internal error: unknown exception");

    EXPECT_EQ(guarded("f_bad", [] { kairos::capi::fail(KAIROS_ERROR_STALE_ID, "f_bad", "id %d is stale", 7); }),
              KAIROS_ERROR_STALE_ID);
    EXPECT_EQ(std::string(kairos_last_error()), "f_bad: id 7 is stale");
}

TEST(Guard, LongMessagesAreTruncatedNotOverflowed) {
    const std::string huge(5000, 'x');
    EXPECT_EQ(
        guarded("f_long", [&] { kairos::capi::fail(KAIROS_ERROR_INVALID_ARGUMENT, "f_long", "%s", huge.c_str()); }),
        KAIROS_ERROR_INVALID_ARGUMENT);
    const std::string m = kairos_last_error();
    EXPECT_EQ(m.rfind("f_long: xxx", 0), 0u);
    EXPECT_LT(m.size(), 1024u);
}
