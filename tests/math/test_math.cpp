// SPDX-License-Identifier: MIT
// The math layer's helpers against the standard library they stand in for: max_of / min_of give
// std::fmax / std::fmin's results on every pair of special values (NaN ignored unless both are
// NaN), so the bounds, scales and normalisations that use them keep the library's semantics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "math/math.hpp"

namespace kairos {
namespace {

// Equal as fmax results are: both NaN, or the same value (the sign of a zero is unspecified).
bool same_result(double got, double want) { return (std::isnan(got) && std::isnan(want)) || got == want; }

TEST(MathHelpers, MaxOfAndMinOfAgreeWithTheLibraryOnSpecialValues) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double den = std::numeric_limits<double>::denorm_min();
    const std::vector<double> values = {nan, -inf, -1e300, -1.5, -den, -0.0, 0.0, den, 1e-300, 2.0, 1e300, inf};
    int nan_pairs = 0;
    for (const double a : values) {
        for (const double b : values) {
            EXPECT_TRUE(same_result(max_of(a, b), std::fmax(a, b))) << a << " " << b;
            EXPECT_TRUE(same_result(min_of(a, b), std::fmin(a, b))) << a << " " << b;
            nan_pairs += std::isnan(a) != std::isnan(b);
        }
    }
    EXPECT_EQ(nan_pairs, 2 * (static_cast<int>(values.size()) - 1));  // one NaN in each such pair
}

TEST(MathHelpers, MaxAbsAndBoundsIgnoreASingleNaNAsTheLibraryDoes) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(max_abs({nan, -3, 2}), 3.0);
    EXPECT_EQ(max_abs({-1, nan, 0.5}), 1.0);
    EXPECT_EQ(max_abs({0.25, -0.5, nan}), 0.5);
    EXPECT_TRUE(std::isnan(max_abs({nan, nan, nan})));
    const Vec3 lo = cwise_min({nan, 1, -2}, {3, nan, -4});
    const Vec3 hi = cwise_max({nan, 1, -2}, {3, nan, -4});
    EXPECT_EQ(lo, (Vec3{3, 1, -4}));
    EXPECT_EQ(hi, (Vec3{3, 1, -2}));
}

TEST(MathHelpers, NormalizedOrGivesUnitVectorsAcrossScalesAndTheFallbackForZero) {
    for (const double scale : {1e-310, 1e-200, 1e-5, 1.0, 1e5, 1e200, 1e307}) {
        const Vec3 u = normalized_or(Vec3{3, -4, 12} * scale, {0, 0, 1});
        EXPECT_NEAR(u.x, 3.0 / 13, 4e-16) << scale;
        EXPECT_NEAR(u.y, -4.0 / 13, 4e-16) << scale;
        EXPECT_NEAR(u.z, 12.0 / 13, 4e-16) << scale;
    }
    EXPECT_EQ(normalized_or({0, 0, 0}, {0, 1, 0}), (Vec3{0, 1, 0}));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Vec3 n = normalized_or({nan, nan, nan}, {1, 0, 0});
    EXPECT_EQ(n, (Vec3{1, 0, 0}));
}

// radial_unit stands in for normalized_or({x, y, 0}, {}) in the cylinder and cone supports, so
// every GJK answer on them stays as it was: the same bits, not merely close ones.
TEST(MathHelpers, RadialUnitIsNormalizedOrOfThePlanarPartBitForBit) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double den = std::numeric_limits<double>::denorm_min();
    std::vector<double> values = {nan, -inf, -1e308, -1e300, -3.0, -1.0, -1e-300, -den, -0.0, 0.0,
                                  den,  1e-310, 1e-300, 0.1,  1.0,  7.0,  1e200, 1e308, inf};
    const uint64_t seed = 20261127;
    uint64_t state = seed;
    for (int i = 0; i < 2000; ++i) {  // random magnitudes over the whole exponent range
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const double mant = static_cast<double>(state >> 11) * 0x1p-53 * 2 - 1;
        const int exp = static_cast<int>((state >> 3) % 2098) - 1074;
        values.push_back(std::ldexp(mant, exp));
    }
    auto bits_equal = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, 8) == 0; };
    int unit = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        for (size_t j = 0; j < values.size(); j += (i < 19 ? 1 : 97)) {
            const double x = values[i], y = values[j];
            const Vec3 want = normalized_or({x, y, 0}, {0, 0, 0});
            const Planar got = radial_unit(x, y);
            ASSERT_TRUE(bits_equal(got.x, want.x) && bits_equal(got.y, want.y))
                << "seed " << seed << ": (" << x << ", " << y << ") gives (" << got.x << ", " << got.y
                << "), normalized_or (" << want.x << ", " << want.y << ")";
            unit += std::fabs(std::hypot(got.x, got.y) - 1) < 1e-15;
        }
    }
    // Most pairs are finite and not both zero: the comparison ran on real unit vectors.
    EXPECT_GT(unit, 30000);
}

}  // namespace
}  // namespace kairos
