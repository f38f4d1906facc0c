// SPDX-License-Identifier: MIT
// Doubles rounded outward to float, for the spans that filter candidates cheaply before the exact
// test. Internal to broadphase/ (namespace broadphase_detail).
#pragma once

#include <cmath>
#include <limits>

namespace kairos::broadphase_detail {

// Float bounds of a double: a float <= x and a float >= x, within a few float ulps (infinite
// beyond the float range). x is lowered by more than half a float ulp (relative 2^-22, plus 2^-140
// for subnormals) and rounded to nearest, which can then not land above x. No branches: these run
// four times per moving object and step, on rounding directions that are random.
inline float float_below(double x) {
    double y = x - (std::fabs(x) * 0x1p-22 + 0x1p-140);
    y = y < -3.4028234663852886e38 ? -std::numeric_limits<double>::infinity() : y;
    y = y > 3.4028234663852886e38 ? 3.4028234663852886e38 : y;
    return static_cast<float>(y);
}
inline float float_above(double x) { return -float_below(-x); }

}  // namespace kairos::broadphase_detail
