// SPDX-License-Identifier: MIT
// Motion cast: the first contact of two convex shapes that translate and rotate over one step, by
// disk bounds on the rotation and GJK shape casts of the fattened shapes (docs/algorithms.md §4).
//
// Source: van den Bergen's talks on continuous collision detection (docs/algorithms.md §4): over an
// interval a body turning by angle a about an axis through its local origin stays inside its pose
// at the interval's start plus a disk of radius 2 rho sin(a / 2) perpendicular to the axis (rho
// the extreme radius about the axis). Casting the fattened shapes gives a lower bound of the time
// of impact and a miss proves that there is no contact in the interval.
#pragma once

#include <cstdint>

#include "casts/cast.hpp"
#include "motion/motion.hpp"
#include "shapes/shape.hpp"

namespace kairos {

// Work done by one motion cast, for tests and benchmarks.
struct MotionCastStats {
    uint32_t casts = 0;       // shape casts of the fattened shapes (or the one exact shape cast)
    uint32_t distances = 0;   // distance queries of the true shapes
    uint32_t bisections = 0;  // windows halved because the fattened shapes touched at their start
    uint32_t steps = 0;       // passes of the outer loop
};

// a follows ma and b follows mb over the step t in [0, 1] (Motion: the local origin moves
// linearly, the orientation turns at constant angular velocity about a fixed world axis).
//
// Pure translations (neither motion rotates) take the exact shape_cast. Otherwise time advances
// from t0 = 0 by proven steps: conservative advancement from a distance query at t0 while it moves
// t0, and disk bounds where it cannot (near contact, when GJK's axis or distance is not good
// enough to certify a step): each body, at its pose in the window [t0, t1] and fattened by the
// disk its rotation sweeps (built in its local frame, where the rotation axis is constant), is
// cast with its translation over the window; t0 advances to each clip, a window whose fattened
// shapes already touch at t0 is halved (first half first), and a window the cast misses is
// proven free of contact. (The talks' disk bounds with bisection alone, and a hybrid that cast
// wherever the window reached 3x past the advancement, took more support evaluations: about 30
// per fattened cast on the disks' flat, coplanar support points. Their rows stay in
// bench/results/motion.csv as kairos_disk and kairos_hybrid; they were removed in 0.2.)
//
// Result (world frame): hit when the true shapes come within delta = tolerance * min(rA, rB) of
// each other (rA, rB the bounding radii of the shapes about their local origins; the other one
// when one is 0, so two points must touch within rounding): toi is the
// first time found with distance <= delta, never later than the true first contact (up to
// rounding), and the normal (unit, from A toward B) and point (midpoint of the closest points)
// come from a distance query there. Shapes that overlap at t = 0: hit at 0, normal opposing the
// relative velocity of the contact point (as shape_cast's -r), or from A's origin toward B's.
// No hit: every window was proven free (termination Separated).
// Guards: at most kMaxMotionSteps outer passes and windows no shorter than the time resolution;
// when one fires the answer is still conservative: a hit at the last t0 (no contact before it),
// with termination MaxIterations or NoProgress, even though the shapes may be apart there. Near
// misses grazed for long (a spinning box passing 1e-6 from a sphere: 3,650 steps) end on
// MaxIterations; curved surfaces closer than double precision resolves (GJK and the cast disagree
// below about 1e-8 of the size) end on NoProgress with the shapes that close.
// tolerance in (0, 1) (clamped to [1e-15, 0.5]); max_iterations guards each GJK query; the
// result's iterations sum the support evaluations of all of them.
CastResult motion_cast(const Shape& a, const Motion& ma, const Shape& b, const Motion& mb, double tolerance,
                       uint32_t max_iterations, MotionCastStats* out_stats = nullptr);

// Guard on the outer loop (windows, clips and bisections together).
inline constexpr uint32_t kMaxMotionSteps = 4096;

}  // namespace kairos
