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
// graze or an end of the step within that of contact, a motion below that of the size, edges of
// the two boxes nearly parallel (between tolerance / 100 and 10 eps / tolerance times the reach
// over the size, radians: there the bound of their axis is not known within the tolerance), or
// anything not finite. tolerance: shape_cast's relative accuracy; edges within tolerance / 100 rad
// of parallel count as parallel (their axis would move the time by less than that share of the
// size), and nothing else depends on it.
BoxCast box_box_cast(Vec3 ha, Vec3 hb, const Mat3& rot, Vec3 t, Vec3 r, double tolerance);

}  // namespace kairos::cast_detail
