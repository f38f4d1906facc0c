// SPDX-License-Identifier: MIT
// GJK ray cast and translational shape cast: the first time of impact of a ray on a convex shape,
// and of two convex shapes moving by constant translations over one step.
//
// Source: van den Bergen, "Ray casting against general convex objects with application to
// continuous collision detection" (2004) and his GJK talks (docs/algorithms.md §3). Each support plane
// of C that separates the ray point x from C is a clipping plane: lambda advances to where the ray
// crosses it, which is a lower bound of the hit. The iteration stops when ||v||^2 <= eps^2 max ||y||^2
// (v = x - c, c the point of the current simplex closest to x, y = x - p for the simplex's points).
#pragma once

#include <cstdint>

#include "gjk/gjk.hpp"
#include "math/math.hpp"
#include "shapes/shape.hpp"

namespace kairos {

// Result of a cast. Points and normals are in the world frame.
struct CastResult {
    bool hit = false;
    double toi = 1;           // lambda in [0, 1] of the first contact; 1 when there is no hit
    Vec3 point;               // contact point at toi (unspecified when no hit)
    Vec3 normal;              // unit; ray cast: outward from the shape; shape cast: from A toward B
    uint32_t iterations = 0;  // support evaluations
    Termination termination = Termination::None;
};

// First hit of the ray origin + lambda * translation, lambda in [0, 1], on `s` at `pose`.
// tolerance: the relative accuracy eps in (0, 1): the iteration stops when the ray point is within
// eps times the size of the shape seen from the ray point. A ray that starts inside hits at 0 with
// normal -translation (unit), or, for a zero translation, the direction from the shape's local
// origin toward the ray origin, or world +z.
CastResult ray_cast(const Shape& s, const Transform& pose, Vec3 origin, Vec3 translation, double tolerance,
                    uint32_t max_iterations);

// a at pose_a moves by translation_a and b at pose_b by translation_b over the step: a ray from the
// origin along r = translation_b - translation_a onto A - B at the start poses, in A's local frame.
// toi = lambda; the normal is the latest clipping plane's, from A toward B; the contact point (world
// frame, at toi) comes from the final simplex's barycentric coordinates.
// Shapes that overlap (or touch within the tolerance) at the start: hit, toi 0, and the normal is
// -r (unit): the contact opposes the relative motion, as it does for every later hit (normal . r < 0),
// so a solver that removes the approach velocity along the normal stops the motion into the overlap.
// With r = 0 it is the direction from A's local origin toward B's, or world +z when they coincide.
// Overlapping by more than touching, the normal and point are the signed distance's (the minimum
// translation's axis and the deepest points' midpoint) unless overlap_normal is false: a caller
// that uses only the verdict and toi (the motion cast's checks) does not pay for the expansion.
CastResult shape_cast(const Shape& a, const Transform& pose_a, Vec3 translation_a, const Shape& b,
                      const Transform& pose_b, Vec3 translation_b, double tolerance, uint32_t max_iterations,
                      bool overlap_normal = true);

}  // namespace kairos
