// SPDX-License-Identifier: MIT
// Extreme radius of a shape about an axis: the farthest any of its points lies from a line
// through its local origin. It sizes the disk that bounds a rotating shape (docs/algorithms.md §4).
#pragma once

#include "shapes/shape.hpp"

namespace kairos {

// An upper bound on max_{x in s} |x - (x.u) u|, the distance of the farthest point of `s` from
// the axis through the local origin along unit `axis` (local frame). Exact for primitives,
// convex hulls and hulls of two exact parts; for transformed shapes and Minkowski sums a
// guaranteed upper bound at most 0.2 % above the truth (sampled support, docs/algorithms.md §4).
double extreme_radius(const Shape& s, Vec3 axis);

// Number of sampled directions of the composite bound; the bound is max_k h(u_k) / cos(pi/K).
inline constexpr int kRadiusSamples = 64;

}  // namespace kairos
