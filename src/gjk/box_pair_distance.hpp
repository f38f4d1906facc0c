// SPDX-License-Identifier: MIT
// Two box cores apart: their distance from the separating axis test, certified by witness points.
// Internal to gjk.cpp.
#pragma once

#include "gjk/closed_form_distance.hpp"
#include "gjk/support_kernels.hpp"
#include "math/transform.hpp"

namespace kairos::gjk_detail {

// The distance of two box cores (plain or rounded boxes), exact to rounding, when the closest
// features are a vertex over a face or two crossing edges. The axis of the 15 (three faces each,
// nine edge pairs) that separates the boxes most gives a lower bound of the distance; the features
// it names give a point of each box, whose distance is an upper bound. When the two agree within
// the rounding of the coordinates (64 eps of the pair's reach), that is the distance, with those
// points as witnesses. In A's frame, as the GJK loop's answer; center_offset receives B's origin
// in A's frame. False (and the loop decides) otherwise: not two boxes, overlapping or within
// rounding of touching, a closest pair of other features (a vertex by an edge, parallel edges, a
// face's feature past the other face's rim), or coordinates outside 1e-100 .. 1e150 of the size.
bool box_pair_distance(const kernels::CoreOf& ca, const Transform& pose_a, const kernels::CoreOf& cb,
                       const Transform& pose_b, LocalDistance& out, Vec3& center_offset);

}  // namespace kairos::gjk_detail
