// SPDX-License-Identifier: MIT
// Signed distance: the distance when apart, minus the penetration depth when overlapping.
//
// Source: van den Bergen, "Proximity Queries and Penetration Depth Computation on 3D Game Objects"
// (GDC 2001) and "Collision Detection in Interactive 3D Environments" (2004), §4.3.6: the expanding
// polytope algorithm (EPA). The depth of overlapping convex A and B is the distance from the
// origin to the boundary of C = A - B; EPA grows a polytope inside C from a tetrahedron of support
// points, each step adding C's support point along the normal of the polytope's face nearest the
// origin. Rounded shapes are their cores plus the radii (docs/algorithms.md §2): the depth is the
// cores' depth plus the radii, or the radii less the cores' distance when the cores are apart.
#pragma once

#include <cstdint>

#include "gjk/gjk.hpp"

namespace kairos {

// Signed distance of a at pose_a and b at pose_b (world frame, the shapes' length unit).
// Apart: gjk_distance's result. Overlapping: distance = -depth (< 0), axis the unit direction
// from A toward B along which translating B by depth leaves the shapes touching, point_a and
// point_b the deepest points (on A's and B's surfaces), point_b - point_a = distance * axis to
// rounding, intersecting = true. Touching (within rounding): distance 0.
//
// The depth lies between two bounds the iteration keeps: below, the offset of the polytope's
// nearest face (the polytope lies inside C); above, the smallest support value of C seen along a
// unit direction. termination: RELATIVE_ERROR when they are within `tolerance` of the depth
// (relative); REPEATED_SUPPORT when the support point lies on the nearest face within rounding
// (polytopes: exact); NEAR_CONTACT when C is flat (a segment crossing a segment, a triangle in a
// triangle's plane: depth 0 of the cores); NO_PROGRESS when rounding leaves no valid expansion;
// MAX_ITERATIONS (at most min(max(max_iterations, 16), 128) support calls; the cores' GJK, for
// rounded shapes, gets at least 16 too). The last two return
// the nearest face found, whose depth is a lower bound, or, when the polytope never held the
// origin, the smallest support value of C seen along a direction (an upper bound); for
// cylinders, cones and capsules whose axes are parallel within about 5e-6 rad, the closed form's
// lower bound when it is the larger (gjk/parallel_axes.hpp, coaxial_depth).
DistanceResult signed_distance(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                               double tolerance, uint32_t max_iterations);

}  // namespace kairos
