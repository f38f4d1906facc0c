// SPDX-License-Identifier: MIT
// Signed distance: the cores' distance by GJK, their depth by the expanding polytope algorithm
// (gjk/expander.hpp) when they overlap, closed forms where they exist, radii added. See
// penetration.hpp for the contract and the source.
#include "gjk/penetration.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>

#include "gjk/closed_forms.hpp"
#include "gjk/core_distance.hpp"
#include "gjk/expander.hpp"
#include "gjk/parallel_axes.hpp"
#include "gjk/support_kernels.hpp"

namespace kairos {
namespace {

using namespace kernels;
using namespace epa_detail;

// A point core inside a box, cylinder or cone core: the depth to the solid's nearest boundary,
// exact. Points and axis in A's frame, as the expansion gives them. Boxes: the nearest face (the
// expansion on a slab 1e9 times wider than thick, a ball's centre inside it, tilted its axis by
// 3e-6: found by fuzzing). Cylinders and cones: the nearest boundary point lies in the axial
// half-plane through the point (turning a boundary point about the axis into it brings it no
// farther), on the flat end or along the side's normal there (the side's foot lies within the side:
// the axial section's angles at the rim and the apex are at most right). On the axis the side's
// nearest points form a circle, which the expansion can only approach: two coaxial shapes took its
// 254 support calls to come within 3e-4 of the depth, and each order gave another answer. The
// point lies at `at` in its own core's frame (a segment's end): turned into the solid's frame apart
// from the poses' offset, so that it is not rounded at the offset's size.
CoreDepth point_in_solid_depth(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b,
                               Vec3 at = {}) {
    const bool a_is_solid = ca.core != Core::Point;
    const Shape& solid = a_is_solid ? *ca.shape : *cb.shape;
    const Transform& solid_pose = a_is_solid ? pose_a : pose_b;
    const Transform& point_pose = a_is_solid ? pose_b : pose_a;
    const Vec3 t = solid_pose.to_local_direction(point_pose.translation - solid_pose.translation) +
                   solid_pose.to_local_direction(point_pose.rotation * at);
    double room;
    Vec3 out_dir{}, face = t;  // solid's frame: the way the point leaves, and where
    if (solid.kind() == ShapeKind::Box) {
        const Vec3 h = static_cast<const BoxShape&>(solid).half_extents;
        int axis = 0;
        room = h.x - std::fabs(t.x);
        for (int i = 1; i < 3; ++i) {
            const double r = h[i] - std::fabs(t[i]);
            if (r < room) room = r, axis = i;
        }
        const double side = t[axis] < 0 ? -1.0 : 1.0;
        out_dir[axis] = side;
        face[axis] = side * h[axis];
    } else {
        const closed_form::Revolution v = closed_form::revolution_of(solid);
        const bool cone = v.cone;
        const double r = v.radius, hh = v.half_height;
        const closed_form::Section section = closed_form::section_of(t);
        const double rho = section.rho;
        const Vec3 u = rho > 0 ? Vec3{section.radial.x, section.radial.y, 0} : Vec3{1, 0, 0};  // on the axis: any
        // The end: the cylinder's nearer one, the cone's base at z = -h. The side: a cone's slant
        // has the normal (2h u + r e_z) / l in the half-plane and passes through the rim (r, -h).
        const double end_sign = cone || t.z < 0 ? -1.0 : 1.0;
        const double end_room = hh - end_sign * t.z;
        double side_room;
        Vec3 side_dir;
        if (cone) {
            const closed_form::Slant slant = closed_form::slant_of(r, hh);
            side_dir = Vec3{slant.across * u.x, slant.across * u.y, slant.up};
            side_room = slant.room(rho, t.z, hh);
        } else {
            side_dir = u;
            side_room = r - rho;
        }
        if (end_room <= side_room) {
            room = end_room;
            out_dir.z = end_sign;
            face.z = end_sign * hh;
        } else {
            room = side_room;
            out_dir = side_dir;
            face = t + side_room * side_dir;
        }
    }
    CoreDepth d;
    d.depth = room;  // < 0 outside; the caller clamps
    d.iterations = 1;
    d.termination = Termination::RelativeError;
    if (a_is_solid) {  // B, the point, leaves along out_dir
        d.n = out_dir;
        d.point_a = face;
        d.point_b = t;
    } else {  // B, the solid, moves the other way
        d.n = -pose_a.to_local_direction(pose_b.rotation * out_dir);
        d.point_a = at;
        d.point_b = pose_a.to_local_direction(pose_b.apply(face) - pose_a.translation);
    }
    return d;
}

// A segment core (a capsule's, a segment) and a box, cylinder or cone core, either order. A point
// p of the segment inside the solid by D(p) along its exact axis n (point_in_solid_depth) bounds
// the segment's depth D: at least D(p) (p needs that push out along any axis), at most
// U(p) = D(p) + max over the segment's x of (x - p) . n (A's segment; (p - x) . n for B's), the
// segment's push out along n. Of the centre, U = D0 + h |n . e| (h the half length, e the
// direction): a segment across its axis or short (capsules of length 0 or 1e-12: balls) has U
// within the tolerance of D0; the expansion on such a ball inside a needle cone stopped on
// rounding with its axis up to 1.5e-3 rad off the normal, or converged on sliver faces 1.5e-6 of
// the depth too deep. Of an end, U = D(p) when the segment leaves the solid along its axis from
// it: a capsule's tip poking into a box or through a cylinder's side. The centre and both ends are
// tried; `upper` holds the least U with its axis and deepest points (the segment's point that
// needs the most push, the tried point itself within the tolerance of a tie, and the solid's point
// U from it along the axis), `lower` the largest D(p), 0 when no point tried is inside or the pair
// is not such a pair. Within the tolerance of each other, U is the depth, in three calls;
// otherwise U bounds the expansion's answer, should it pass U by more than the tolerance.
struct SegmentInSolid {
    CoreDepth upper;
    double lower = 0;
};
SegmentInSolid segment_in_solid(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b,
                                double tolerance) {
    SegmentInSolid s;
    const bool a_segment = ca.core == Core::Segment && solid_core(cb);
    if (!a_segment && !(solid_core(ca) && cb.core == Core::Segment)) return s;
    CoreOf point_a = ca, point_b = cb;
    (a_segment ? point_a : point_b).core = Core::Point;  // a point of the segment: its pose's origin
    const double half = segment_half_length(*(a_segment ? ca : cb).shape);
    // The segment's half extent in A's frame. B leaves A along n: A's point farthest along it needs
    // the most push, or B's least far; `sign` turns B's into A's case.
    const Vec3 e = half * (a_segment ? Vec3{0, 0, 1} : pose_a.to_local_direction(pose_b.rotation * Vec3{0, 0, 1}));
    const double sign = a_segment ? 1 : -1;
    s.upper.depth = INFINITY;
    uint32_t calls = 0;
    for (int t = 0; t <= (half > 0 ? 2 : 0); ++t) {
        const double at = t == 0 ? 0.0 : (t == 1 ? 1.0 : -1.0);  // the point at `at` e
        const CoreDepth d = point_in_solid_depth(point_a, pose_a, point_b, pose_b, Vec3{0, 0, at * half});
        ++calls;
        if (!(d.depth > 0)) continue;
        s.lower = std::fmax(s.lower, d.depth);
        // The segment's ends, at u e for u = -1, 1, push out (u - at) e . n past this point (B's: minus that).
        const double along = sign * dot(d.n, e), push_plus = (1 - at) * along, push_minus = (-1 - at) * along;
        const double extra = std::fmax(0.0, std::fmax(push_plus, push_minus));
        const double u = d.depth + extra;
        if (!(u < s.upper.depth) || !std::isfinite(u)) continue;
        const Vec3 shift = extra <= tolerance * u ? Vec3{} : (push_plus >= push_minus ? 1 - at : -1 - at) * e;
        s.upper = d;
        s.upper.depth = u;
        if (a_segment) {
            s.upper.point_a = d.point_a + shift;
            s.upper.point_b = s.upper.point_a - u * d.n;
        } else {
            s.upper.point_b = d.point_b + shift;
            s.upper.point_a = s.upper.point_b + u * d.n;
        }
    }
    if (!(s.lower > 0) || !std::isfinite(s.upper.depth)) return SegmentInSolid{};
    s.upper.iterations = calls;
    return s;
}

// The cores' separation along the unit axis n (A's frame, from A toward B): B's support value
// along -n less A's along n, a lower bound of their gap when positive; a_point gets A's support
// point along n.
double separation_along(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b, Vec3 n,
                        Vec3& a_point) {
    return with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double) {
        Vec3 pb;
        return -dot(n, pair(n, a_point, pb));
    });
}

}  // namespace

CoreDepth overlap_behind_rounding_stop(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb,
                                       const Transform& pose_b, Vec3 axis, double tolerance) {
    Vec3 a_point;
    const double along = separation_along(ca, pose_a, cb, pose_b, axis, a_point);
    const Vec3 offset = pose_a.to_local_direction(pose_b.translation - pose_a.translation);
    const double rounding = 0x1p-46 * (max_abs(offset) + max_abs(a_point));
    if (!(along < -rounding)) return {};
    CoreDepth d = with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double) {
        return Expander<std::decay_t<decltype(pair)>>(pair, pair.t, 128).run(tolerance);
    });
    if (!(d.depth > rounding) || d.flat) d.depth = 0;
    return d;
}

DistanceResult signed_distance(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                               double tolerance, uint32_t max_iterations) {
    if (rigidly_placed(a) || rigidly_placed(b)) {
        const PlacedShape ua = unwrap_rigid(a, pose_a), ub = unwrap_rigid(b, pose_b);
        return signed_distance(*ua.shape, ua.pose, *ub.shape, ub.pose, tolerance, max_iterations);
    }
    const CoreOf ca = classify(a), cb = classify(b);
    const double margin = ca.radius + cb.radius;
    // GJK's tetrahedron around the origin, the expansion's start: of the shapes themselves when
    // they have no radius, else of core_distance's run.
    HeldTetrahedron held;
    DistanceResult r = gjk_distance(a, pose_a, b, pose_b, tolerance, max_iterations, margin > 0 ? nullptr : &held);
    if (!r.intersecting) return r;
    CoreDistance c;
    if (margin > 0) {
        // As the expansion, at least 16 support calls: a guard-stopped GJK's gap is no gap.
        c = core_distance(ca, pose_a, cb, pose_b, tolerance, max_iterations < 16 ? 16 : max_iterations, &held);
    } else {  // the cores are the shapes: gjk_distance has answered already (they overlap)
        c.overlap = true;
        c.center_offset = pose_a.to_local_direction(pose_b.translation - pose_a.translation);
        c.point_a = pose_a.apply_inverse(r.point_a);
        c.point_b = pose_a.apply_inverse(r.point_b);
        c.iterations = r.iterations;
    }
    // The cores' gap after a rounding stop may hide their overlap, as between shapes without radii
    // (gjk_distance): cores of boxes tilted 1e-9, 1e-12 of the size inside at one end, were taken
    // as apart, and the depth was 1.9e-12 of the size short (TiltedContacts). The expansion decides.
    CoreDepth settled;
    if (margin > 0 && !c.overlap && dot(c.unit, c.unit) > 0 && unproven_rounding_stop(c.bounded, c.termination))
        [[unlikely]] {
        settled = overlap_behind_rounding_stop(ca, pose_a, cb, pose_b, c.unit, tolerance);
        c.overlap = settled.depth > 0;
    }
    // The cores apart: their axis must itself show the gap. Between a point and a needle 1e-12
    // apart it is the direction of a 1e-12 vector, tilted by rounding toward the needle, whose
    // support then moves by 1e-4 along it (found by fuzzing): such cores go to the expansion,
    // whose faces along the needle give the axis.
    bool apart = false, axis_shows_gap = false;
    double along = 0;  // the cores' separation along their axis: a lower bound of their gap
    Vec3 along_a;      // A's core's support point along the axis (A's frame)
    if (!c.overlap && dot(c.unit, c.unit) > 0) {
        apart = true;
        along = separation_along(ca, pose_a, cb, pose_b, c.unit, along_a);
        const double scale = max_abs(c.center_offset) + max_abs(c.point_a) + max_abs(c.point_b);
        axis_shows_gap = c.distance - along <= 0x1p-30 * scale;
    }
    CoreDepth depth;
    // Cylinders, cones and capsules about parallel axes (Near: the expansion's fallback, below).
    gjk_detail::CoaxialAnswer coaxial;
    const auto coaxial_accepted = [&] {
        coaxial = gjk_detail::coaxial_depth(ca, pose_a, cb, pose_b, tolerance, true);
        return coaxial.kind == gjk_detail::CoaxialAnswer::Kind::Accepted;
    };
    const auto near = [&] { return coaxial.kind == gjk_detail::CoaxialAnswer::Kind::Near; };
    double total;
    const bool point_solid = point_and_solid(ca, cb);
    // Cores apart with an axis that shows their gap hold no point of one inside the other: the
    // segment's points are not tried (the radii's overlap is the answer, below).
    const SegmentInSolid segment =
        axis_shows_gap ? SegmentInSolid{} : segment_in_solid(ca, pose_a, cb, pose_b, tolerance);
    // The room decides inside too, should it round otherwise than the cores' closed-form distance
    // (a GJK loop from a point 9e-8 inside a cone 3e-7 wide once took the cores as apart).
    if (point_solid) depth = point_in_solid_depth(ca, pose_a, cb, pose_b);
    if (point_solid && (c.overlap || depth.depth > 0)) {
        depth.depth = std::fmax(depth.depth, 0.0);
        total = depth.depth + margin;
    } else if (segment.lower > 0 && segment.upper.depth - segment.lower <= tolerance * segment.upper.depth) {
        depth = segment.upper;
        depth.iterations += c.iterations;
        total = depth.depth + margin;
    } else if (settled.depth > 0) {
        // The cores meet at GJK's points, a rounding apart (the expansion's may not be at the
        // contact: a curved rim's support point as its bound's witness); B's deepest point is the
        // depth from A's along the axis, as the result's contract has them. (Not always a
        // rounding: a capsule of length 0, a ball, whose centre lay 0.18 inside a cone 8282 long
        // stopped GJK on no progress, and its points were reported the radius apart for a depth
        // 0.18 larger; fuzz_queries.)
        depth = settled;
        depth.point_a = 0.5 * (c.point_a + c.point_b);
        depth.point_b = depth.point_a - settled.depth * settled.n;
        depth.iterations += c.iterations;
        total = depth.depth + margin;
    } else if (!apart && coaxial_accepted()) {
        depth = coaxial.depth;
        depth.iterations += c.iterations;
        total = depth.depth + margin;
    } else if (axis_shows_gap) {
        // Only the radii overlap: the cores' closest points and axis, the radii less their gap.
        depth.n = c.unit;
        depth.point_a = c.point_a;
        depth.point_b = c.point_b;
        depth.iterations = c.iterations;
        depth.termination = c.termination;
        total = margin - c.distance;
    } else {
        // The tetrahedron alone takes 6 to 12 support calls.
        const uint32_t budget = max_iterations < 128 ? (max_iterations < 16 ? 16 : max_iterations) : 128;
        depth = with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double) {
            using P = std::decay_t<decltype(pair)>;
            Expander<P> expander(pair, c.center_offset, budget, &held);
            // A segment in a solid: the least push out of its points tried bounds the depth.
            if (segment.lower > 0) expander.bound_from_above(&segment.upper);
            CoreDepth d = expander.run(tolerance);
            if constexpr (!(exact_support<decltype(P::sa)> && exact_support<decltype(P::sb)>)) {
                // A deep overlap on a cylinder's side can use up the 128 steps: support points
                // along nearly horizontal normals fall on the top or the bottom rim as rounding
                // decides, and each refinement in angle needs a vertex on both; so can a round C
                // (near-concentric curved shapes), whose depth the polytope approaches only as
                // its vertices multiply. Such a pair goes on with room for 252 vertices, on the
                // heap (about 110 kB: too much for a stack), from the polytope it has: it once
                // started again from nothing, and near-concentric generic shapes spent a third of
                // their time repeating the first 128 steps (a world step seconds long under the
                // sanitizers, found by fuzzing). A caller's max_iterations bounds the calls in all.
                if (d.termination == Termination::MaxIterations && max_iterations > budget && !near()) {
                    const uint32_t large = max_iterations < 252 ? max_iterations : 252;
                    d = std::make_unique<Expander<P, kMaxVerticesLarge>>(expander, large)->run(tolerance);
                }
            }
            return d;
        });
        // Nearly parallel axes: coaxial sides meet along a circle turned a little, which the
        // expansion approaches as slowly as the untilted one (of coaxial cylinders and cones
        // turned by 1e-9 to 1e-6 rad, over half used up 252 support calls, up to 0.4 ms, and
        // stopped up to 8e-4 of the size short). Unconverged, its answer E is a lower bound of the
        // depth, and so is the closed form's U less its error (U lies at most that above the
        // depth): the larger is kept, with U's axis and contact, at most that error short.
        if (near() && !depth.flat &&
            (depth.termination == Termination::MaxIterations || depth.termination == Termination::NoProgress) &&
            coaxial.depth.depth - coaxial.error > depth.depth) {
            const uint32_t calls = depth.iterations + coaxial.depth.iterations;  // the calls of both count
            const Termination stop = depth.termination;
            depth = coaxial.depth;
            depth.iterations = calls;
            depth.termination = stop;
            depth.depth -= coaxial.error;
            depth.point_b = depth.point_a - depth.depth * depth.n;
        }
        if (segment.lower > 0) depth.iterations += segment.upper.iterations;
        depth.iterations += c.iterations;
        total = depth.depth + margin;
        if (depth.flat) {  // the cores meet: at a point of A's core (GJK's), both deepest points
            depth.point_a = c.point_a;
            depth.point_b = c.point_a;
        }
        // The cores apart: a separation along an axis shows a gap the expansion (nothing to
        // enclose) could not, and the radii less it bound the depth, which that axis itself
        // gives (a ball 0.46 off a cylinder 1e4 long; found by fuzzing). Two axes: GJK's and the
        // expansion's. GJK's can be tilted by far more than its distance's error: a ball's
        // centre 1.2e-4 from a flat ellipse 50 wide had it 3e-7 off the normal, which showed
        // a gap 13 % short, while the flat expansion's normal showed all of it (fuzz_queries).
        // The deepest points: A's core's support point along the axis, B's the gap beyond.
        if (apart) {
            Vec3 n_a;
            const double along_n =
                dot(depth.n, depth.n) > 0 ? separation_along(ca, pose_a, cb, pose_b, depth.n, n_a) : -INFINITY;
            const bool use_n = along_n > along;
            const double gap = use_n ? along_n : along;
            if (gap > 0 && margin - gap < total) {
                const Vec3 axis = use_n ? depth.n : c.unit;
                depth.n = axis;
                depth.point_a = use_n ? n_a : along_a;
                depth.point_b = depth.point_a + gap * axis;
                total = margin - gap;
                if (!use_n) depth.termination = c.termination;
            }
            // A core distance ended by the guard bounds the cores' gap from above and a separation
            // bounds it from below: the radii less a separation overstate the depth (by 1.6e-3 for
            // an ellipsoid 306 wide and a ball of radius 325 at 16 support calls; fuzzing). Then
            // the radii less GJK's distance, with its axis and points: short of the depth, never
            // past it, as a bound from a guard-stopped query must be.
            if (c.termination == Termination::MaxIterations && margin - c.distance < total) {
                depth.n = c.unit;
                depth.point_a = c.point_a;
                depth.point_b = c.point_b;
                depth.termination = c.termination;
                total = margin - c.distance;
            }
        }
    }
    r.iterations = depth.iterations;
    r.termination = depth.termination;
    const Vec3 n = depth.n;
    if (!(total > 0)) {  // touching within rounding: gjk_distance's points, the depth's axis
        r.axis = pose_a.rotation * n;
        return r;
    }
    r.distance = -total;
    r.point_a = pose_a.apply(depth.point_a + ca.radius * n);
    r.point_b = pose_a.apply(depth.point_b - cb.radius * n);
    r.axis = pose_a.rotation * n;
    r.intersecting = true;
    return r;
}

}  // namespace kairos
