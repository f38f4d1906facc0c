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

// A ray s + lambda r (the box's frame) against the box of half extents h grown by a ball of
// radius rho >= 0 (a plain box when 0, or below the rounding of the entry): for a point or a ball
// cast against a box, rounded or not.
// The ray enters the box grown by rho on every axis (a slab test); an entry with at most one
// coordinate past the box is on a face and exact; otherwise the capsule of the edge whose region
// it is in decides, or in a corner's region the earliest of the three at the corner (cylinders as
// circles in the planes across the edges, caps as balls: closed_form::ball_entry). normal:
// outward of the grown box at the hit; point: the hit on its surface. Declined where the GJK cast's conventions are
// needed: a start within 1e-9 of the size of the grown box or inside it, a motion below that,
// sizes or offsets beyond 1e-100 .. 1e100, anything not finite.
BoxCast ray_rounded_box(Vec3 h, double rho, Vec3 s, Vec3 r);

// A ray s + lambda r (the segment's frame) against the capsule of the segment from (0, 0, -h) to
// (0, 0, h) grown by rho: the box (0, 0, h) rounded by rho (ray_rounded_box, whose edges and
// corners there are the capsule's side and caps), with its declines, and one more: a radius below
// the rounding of the entry, where the grown box's faces stand for the capsule (ray_rounded_box's
// plain box), is declined too: a segment has no face whose normal a contact could take.
BoxCast ray_capsule(double h, double rho, Vec3 s, Vec3 r);

// Two capsules moving by translations: A's segment from (0, 0, -ha) to (0, 0, ha) at the origin of
// its frame, B's of half length hb along the third column of rot (B's axes in A's frame), centred
// at t, B moving by r relative to A; radii ra and rb. B's centre as a ray against the parallelogram
// of A's segment less B's grown by both radii: the least entry into the prism over its face and
// the four edges' capsules (ray_capsule). normal and point: at the contact, A's frame, A at its
// start pose. Segments within tolerance / 100 rad of parallel (sine of their angle) count as
// parallel: the parallelogram is taken as its long axis grown by its half width, which moves the
// time earlier by at most that width over the approach. Declined where any piece declines (a start
// in or within 1e-9 of the size of the grown parallelogram, a radius below the entry's rounding),
// for segments between that and 1e-4 rad of parallel, and for anything not finite.
BoxCast capsule_pair_cast(double ha, double hb, const Mat3& rot, Vec3 t, Vec3 r, double ra, double rb,
                          double tolerance);

}  // namespace kairos::cast_detail
