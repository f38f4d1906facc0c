// SPDX-License-Identifier: MIT
// Cores among cylinders, cones and segments (capsules') whose axes are parallel: A - B is then a
// body of revolution about the axis through the offset between theirs, and its section through
// that axis is the sum of theirs (a body of revolution's section through its axis is also its
// projection on that plane, and projections add). The nearest point of such a body to a point lies
// in the axial half-plane through that point, so the cores' distance and depth are those of two
// polygons in the plane through both axes. Internal to gjk.cpp and penetration.cpp.
// Both closed forms take a pair only when its axes are parallel within the poses' rounding, or
// (the depth) when turning B by their angle moves a support value by less than the tolerance allows.
#pragma once

#include "gjk/closed_form_distance.hpp"
#include "gjk/polytope.hpp"
#include "gjk/support_kernels.hpp"
#include "math/transform.hpp"

namespace kairos::gjk_detail {

// A cylinder, cone or segment core, with at least one of the two a cylinder or a cone (two
// segments have a closed form of their own).
bool axial_pair(const kernels::CoreOf& ca, const kernels::CoreOf& cb);

// A core's axial section's corners in order around it (x across the axis, z along it; symmetric in
// x): a cylinder's rectangle, a cone's triangle (apex at +h), a segment's ends. Returns the count.
int axial_section(const kernels::CoreOf& c, double (&x)[4], double (&z)[4]);

// The cores' distance when their axes are parallel within the poses' rounding (64 ulps of their
// coordinates and reaches), from the closest points of their sections in the plane through both
// axes: exact, one support call (the separation along the axis, a lower bound from the shapes' own
// supports, which must confirm it to the tolerance, relative as GJK's stop). In A's frame, as the
// GJK loop's answer; center_offset receives B's origin in A's frame. False (and the loop decides)
// when the pair is not axial_pair, the axes are not parallel, the cores overlap or touch within
// rounding, or the separation does not confirm the distance.
bool parallel_axes_distance(const kernels::CoreOf& ca, const Transform& pose_a, const kernels::CoreOf& cb,
                            const Transform& pose_b, double tolerance, LocalDistance& out, Vec3& center_offset);

// What coaxial_depth found. Accepted: `depth` is the depth to the tolerance. Near (asked for by
// offer_near, axes parallel within kNearlyParallel but not within the tolerance): `depth` is an
// upper bound at most `error` (twice the turn's bound) above the depth, so its depth less `error`
// is a lower bound; the caller's expansion may do better, or stop short (coaxial sides' circle,
// turned). None: no answer (not an axial pair, axes not parallel enough, no overlap).
struct CoaxialAnswer {
    enum class Kind { None, Accepted, Near };
    Kind kind = Kind::None;
    epa_detail::CoreDepth depth;  // Accepted and Near only
    double error = 0;             // Near only
};

// The depth of two overlapping such cores, exact: the least of the candidate translations along the
// sections' edge normals, each measured with the shapes' own supports (so never below the depth).
// In A's frame, as the expansion's answer. Accepted when the axes are parallel within the poses'
// rounding or within the tolerance of the depth (relative, as the expansion's stop): the answer is
// then within twice the turn's bound of the depth, and B's deepest point (from the untilted
// section) off B by at most that bound. The expansion can only approach the circle along which
// coaxial sides meet (two coincident cylinders took its 254 support calls to come within 6e-4 of the
// depth, in about 0.5 ms).
CoaxialAnswer coaxial_depth(const kernels::CoreOf& ca, const Transform& pose_a, const kernels::CoreOf& cb,
                            const Transform& pose_b, double tolerance, bool offer_near);

// The axes' turn bound, as a share of the reaches' sum, within which coaxial_depth offers its
// answer to a caller that asks (offer_near): turns up to about 5e-6 rad. Its error, at most 1e-5
// of the reaches, is then well below where the expansion stops short on a turned coaxial circle
// (4e-4 to 9e-4 of the size); beyond, the expansion goes on to its 252 support calls.
inline constexpr double kNearlyParallel = 1e-5;

}  // namespace kairos::gjk_detail
