// SPDX-License-Identifier: MIT
// The GJK loops' answer in A's frame (LocalDistance), and the pairs that take a closed form
// instead of the loop: points and segments among themselves, a point and a box, cylinder or cone.
// Internal to gjk.cpp.
#pragma once

#include <cstdint>

#include "gjk/closed_forms.hpp"
#include "gjk/core_distance.hpp"
#include "gjk/support_kernels.hpp"
#include "gjk/termination.hpp"
#include "math/math.hpp"

namespace kairos::gjk_detail {

using kernels::Core;
using kernels::CoreOf;
using kernels::segment_half_length;

// In A's frame, at the caller's scale (the loop's own scale undone).
struct LocalDistance {
    double core;  // ||v|| of the final estimate (cores)
    Vec3 v, point_a, point_b;
    Vec3 unit;      // -v / ||v||, or zero when v is zero
    Vec3 proven{};  // shapes without radii: the axis to report, or zero for unit (gjk_detail::proven_axis)
    bool intersecting;
    uint32_t iterations;
    Termination termination;
    // The last simplex was a triangle whose coordinates did not reproduce v, and the sub-simplex
    // taken instead lies farther than the tolerance allows (see distance_query).
    bool lengthened = false;
    // A support call proved a positive lower bound of the distance (v.w > 0 along some direction):
    // the shapes' depth, should they overlap, is within rounding.
    bool bounded = false;
};

// Pairs with a closed form: cores that are points or segments (spheres, capsules, points,
// segments), or a point core and a box, cylinder or cone. No loop, one "iteration", exact to rounding.
inline bool line_core(const CoreOf& c) { return c.core == Core::Point || c.core == Core::Segment; }
inline bool closed_form_pair(const CoreOf& ca, const CoreOf& cb) {
    return (line_core(ca) && line_core(cb)) || point_and_solid(ca, cb);
}

// The cores' closest points in A's frame (the loop's LocalDistance, at the caller's scale);
// center_offset receives B's origin in A's frame.
inline LocalDistance line_core_distance(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb,
                                        const Transform& pose_b, Vec3& center_offset) {
    // Only B's centre and axis in A's frame are needed, not the whole relative rotation.
    const Vec3 t = pose_a.to_local_direction(pose_b.translation - pose_a.translation);
    center_offset = t;
    const double ha = ca.core == Core::Segment ? segment_half_length(*ca.shape) : 0;
    const double hb = cb.core == Core::Segment ? segment_half_length(*cb.shape) : 0;
    const Vec3 d = pose_a.to_local_direction(pose_b.rotation.col(2));
    const closed_form::SegmentPair cp = closed_form::closest_points(ha, t, d, hb);
    const Vec3 gap = cp.q - cp.p;  // from A's core toward B's
    LocalDistance l{};
    l.core = closed_form::safe_length(gap);
    l.v = -gap;
    l.point_a = cp.p;
    l.point_b = cp.q;
    const double margin = ca.radius + cb.radius;
    if (l.core > 0) {
        const closed_form::Axis axis = closed_form::separating_axis(ha, t, d, hb, closed_form::unit_of(gap));
        l.unit = axis.n;
        // Apart only when the axis proves it: the cores' shadows on it, grown by the radii, do not
        // meet. Closer than that is touching within rounding, as GJK's own rule reads it.
        l.intersecting = !(l.core > margin && axis.sep > margin);
    } else {
        l.intersecting = true;
    }
    l.iterations = 1;
    l.termination = l.intersecting ? Termination::FullSimplex : Termination::RelativeError;
    return l;
}

// A point core and a box, cylinder or cone, in the solid's frame: its nearest point to the point
// (closed_form::solid_nearest); the axis t - p separates whenever it is not zero. When B is the
// solid the answer is brought back to A's frame, where A's core is the origin.
inline LocalDistance point_solid_distance(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb,
                                          const Transform& pose_b, Vec3& center_offset) {
    const bool a_is_solid = ca.core != Core::Point;
    const Transform& solid_pose = a_is_solid ? pose_a : pose_b;
    const Transform& point_pose = a_is_solid ? pose_b : pose_a;
    const Vec3 t = solid_pose.to_local_direction(point_pose.translation - solid_pose.translation);
    Vec3 unit;  // the solid's frame, from it toward the point
    const Vec3 p = closed_form::solid_nearest(a_is_solid ? *ca.shape : *cb.shape, t, unit);
    LocalDistance l{};
    l.core = closed_form::safe_length(t - p);
    l.intersecting = !(l.core > ca.radius + cb.radius);
    l.iterations = 1;
    l.termination = l.intersecting ? Termination::FullSimplex : Termination::RelativeError;
    if (a_is_solid) {
        center_offset = t;
        l.point_a = p;
        l.point_b = t;
        l.unit = unit;
    } else {
        center_offset = pose_a.to_local_direction(pose_b.translation - pose_a.translation);
        l.point_a = {};
        l.point_b = pose_a.to_local_direction(pose_b.apply(p) - pose_a.translation);
        l.unit = -pose_a.to_local_direction(pose_b.rotation * unit);
    }
    l.v = -l.core * l.unit;
    return l;
}

inline LocalDistance closed_form_distance(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb,
                                          const Transform& pose_b, Vec3& center_offset) {
    return line_core(ca) && line_core(cb) ? line_core_distance(ca, pose_a, cb, pose_b, center_offset)
                                          : point_solid_distance(ca, pose_a, cb, pose_b, center_offset);
}

}  // namespace kairos::gjk_detail
