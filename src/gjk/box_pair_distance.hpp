// SPDX-License-Identifier: MIT
// Two box cores apart: their distance from the separating axis test, certified by witness points.
// Internal to gjk.cpp.
#pragma once

#include "gjk/closed_form_distance.hpp"
#include "gjk/support_kernels.hpp"
#include "math/transform.hpp"

namespace kairos::gjk_detail {

// The distance of two box cores (plain or rounded boxes), exact to rounding. The axis of the 15
// (three faces each, nine edge pairs) that separates the boxes most gives a lower bound of the
// distance; the features it names give a point of each box, whose distance is an upper bound.
// When that pair's distance is within the rounding of the coordinates (64 eps of the pair's reach)
// of the axes' bound, or of the separation along the pair's own direction (a vertex by an edge),
// it is the distance, with those points as witnesses. In A's frame, as the GJK loop's answer;
// center_offset receives B's origin in A's frame. False (and the loop decides) otherwise: not two
// boxes, overlapping or within rounding of touching, no bound confirms the pair (parallel edges
// nearest, a gap near the rounding), or coordinates outside 1e-140 .. 1e140.
bool box_pair_distance(const kernels::CoreOf& ca, const Transform& pose_a, const kernels::CoreOf& cb,
                       const Transform& pose_b, LocalDistance& out, Vec3& center_offset);

}  // namespace kairos::gjk_detail
