// SPDX-License-Identifier: MIT
// The translational cast of two boxes without rounding in closed form: the separating axis test
// over the step (docs/algorithms.md §3, "Box pairs"). Internal; shape_cast (cast.cpp) tries it
// first and keeps the GJK ray cast for what it declines.
#pragma once

#include "math/math.hpp"

namespace kairos::cast_detail {

struct BoxCast {
    enum class Verdict { Declined, Miss, Hit };
    Verdict verdict = Verdict::Declined;
    double toi = 1;  // the first contact's lambda, in (0, 1]
    Vec3 normal{};   // unit, from A toward B, A's frame
    Vec3 point{};    // the contact point at toi, A's frame with A kept at its start pose
};

// Box A (half extents ha) at the origin of its frame, box B (half extents hb) with axes the
// columns of rot and centre t in that frame, moving by r over the step. Exact up to rounding
// (the time never later than the contact's), or Declined where the GJK cast's conventions or
// its care are needed: touching or overlapping at the start (within 1e-9 of the pair's size), a
// graze or an end of the step within that of contact, edges of the two boxes between 1e-14 and
// 1e-3 radians of parallel, a motion below that of the size, or anything not finite.
BoxCast box_box_cast(Vec3 ha, Vec3 hb, const Mat3& rot, Vec3 t, Vec3 r);

}  // namespace kairos::cast_detail
