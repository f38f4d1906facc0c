// SPDX-License-Identifier: MIT
// The guard around every exported function: each kind of C++ exception becomes a status and a
// message, and nothing escapes. Built from the C boundary's sources, since out-of-memory and
// internal errors cannot be provoked on purpose through the public functions.
#include <gtest/gtest.h>

#include <cmath>
#include <new>
#include <random>
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

// unit_quat skips the normalisation's divisions by testing the squared length itself: the
// skipped cases must be exactly those whose square root rounds to 1 (where q / n is q), over
// the doubles around 1 and over quaternions whose squared length lands there.
TEST(Boundary, UnitQuatSkipsTheDivisionsExactlyWhereTheyChangeNothing) {
    double nn = 1;
    for (int k = 0; k < 300; ++k) nn = std::nextafter(nn, 0.0);
    int roots_of_one = 0;
    for (int k = 0; k < 600; ++k, nn = std::nextafter(nn, 2.0)) {
        const kairos_quat q{0, 0, 0, std::sqrt(nn)};
        const kairos::Quat u = kairos::capi::unit_quat(q, nn);
        const double n = std::sqrt(nn);
        roots_of_one += n == 1;
        EXPECT_EQ(u.w, q.w / n) << std::hexfloat << "nn " << nn;
    }
    EXPECT_EQ(roots_of_one, 2);  // 1 and 1 + 2^-52
    std::mt19937_64 rng(20261202);
    std::normal_distribution<double> g;
    int skipped = 0;
    for (int k = 0; k < 20000; ++k) {
        kairos_quat q{g(rng), g(rng), g(rng), g(rng)};
        const double len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
        q = {q.x / len, q.y / len, q.z / len, q.w / len};
        const double sq = kairos::capi::squared_length(q), n = std::sqrt(sq);
        skipped += n == 1;
        const kairos::Quat u = kairos::capi::unit_quat(q, sq);
        ASSERT_TRUE(u.x == q.x / n && u.y == q.y / n && u.z == q.z / n && u.w == q.w / n)
            << "seed 20261202, case " << k;
    }
    // Both paths are taken: a caller's unit quaternions land on either side.
    EXPECT_GT(skipped, 2000);
    EXPECT_LT(skipped, 18000);
}
