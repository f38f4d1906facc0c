// SPDX-License-Identifier: MIT
// GJK ray cast and shape cast loops, instantiated per pair of support kinds (no virtual call, no
// allocation). Shape casts run in A's local frame; results go back to the world frame.
//
// After a clip the simplex is kept and re-expressed about the new ray point; restarting from the
// last support point (docs/algorithms.md §3) took more iterations and time in bench_cast.
#include "casts/cast.hpp"
#include "casts/box_cast.hpp"
#include "casts/cast_loop.hpp"
#include "gjk/closed_forms.hpp"
#include "gjk/core_distance.hpp"
#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "gjk/support_kernels.hpp"

#include <cmath>

namespace kairos {
namespace {
using namespace kernels;
using cast_detail::CastLoop;
using cast_detail::LocalCast;
using cast_detail::SingleSupport;

// The normal of the latest clipping plane. With a radius the final v (x minus the core's closest
// point, about the radius long) is the normal of the rounded shape's support plane through the
// contact, exact to the tolerance, while the last clip may be an iteration older; it is used then,
// unless it fails to oppose the motion r (a guard stop short of contact, or a coarse tolerance
// stopping far from it; a clipping plane's normal always opposes r), or the radius is below 2^-20
// of l.size: v's direction then carries rounding of eps * size / radius (0.95 rad on a capsule 2e4
// long of radius 7e-300; found by fuzzing), while a clipping plane never lies past the shape;
// or when v's plane cuts the shapes at toi by more than the tolerance allows (l.v_plane_cuts: at
// loose tolerances v tilts by about the square root of the tolerance), unless honour_plane_check
// is false (shape_cast's rounding-stop judgement wants v's normal as the loop left it).
// `fallback` is a callable, called only when needed (the start-inside normal, see StartNormal).
template <class Fallback>
Vec3 contact_normal(const LocalCast& l, double margin, Vec3 r, const Fallback& fallback,
                    bool honour_plane_check = true) {
    if (!l.clipped) return fallback();
    if (margin > 0x1p-20 * l.size && l.termination != Termination::MaxIterations &&
        !(honour_plane_check && l.v_plane_cuts) && dot(l.v, l.v) > 0.25 * margin * margin && dot(l.v, l.normal) > 0 &&
        dot(l.v, r) < 0)
        return normalized_or_else(l.v, fallback);
    return normalized_or_else(l.normal, fallback);
}

// The normal of a start inside, in the loop's frame: against the motion (-r), or from the first
// shape's origin toward the other's (or the ray's start), or world +z. A callable: the hits
// that need it are rare, and each choice costs a normalisation.
struct StartNormal {
    Vec3 r, toward;
    const Transform* pose;
    Vec3 operator()() const {
        return normalized_or_else(-r, [&] { return normalized_or(toward, pose->to_local_direction({0, 0, 1})); });
    }
};

// A first search direction: x - c for some c of C. Against the ray (-r) the first support is C's
// point nearest the ray's start along r, whose plane is usually the first clip.
Vec3 first_direction(Vec3 r, Vec3 toward_x) {
    if (dot(r, r) > 0 && std::isfinite(dot(r, r))) return -r;
    if (dot(toward_x, toward_x) > 0) return toward_x;
    return {1, 0, 0};
}

// The part of a result both casts fill alike: iterations, termination, hit, and toi (1 on a miss).
CastResult result_head(const LocalCast& l) {
    CastResult out;
    out.iterations = l.iterations;
    out.termination = l.termination;
    out.hit = l.hit;
    out.toi = l.hit ? l.lambda : 1;
    return out;
}

// A ray from s (relative to a ball's centre, any frame) along r against the ball of `radius` (a
// point core: a sphere, a point, or a sphere around one; for a shape cast, the two balls' cores
// with the radii summed): the closed form, one "iteration". On a hit, `normal` is from the centre
// toward the ray point at toi (the fallback when that is the centre itself, as a start inside
// with the GJK loop) and `dir` the direction of the contact from the centre.
struct BallHit {
    CastResult head;
    Vec3 normal, dir;
};
BallHit ball_cast(Vec3 s, Vec3 r, double radius, const StartNormal& fallback) {
    BallHit b;
    b.head.iterations = 1;
    const closed_form::BallEntry e = closed_form::ball_entry(s, r, radius);
    const double lambda = e.lambda;
    if (!(lambda >= 0)) {
        b.head.termination = Termination::Separated;
        return b;
    }
    b.head.hit = true;
    b.head.termination = Termination::Hit;
    b.head.toi = lambda;
    if (lambda > 0) {
        b.normal = normalized_or_else(e.offset, fallback);
        b.dir = b.normal;
    } else {  // overlapping at the start: the GJK loop's normal, the contact toward the start
        b.normal = fallback();
        b.dir = normalized_or(s, b.normal);
    }
    return b;
}

// The loop's rules that stop at the rounding limit rather than at contact or a miss.
bool rounding_stop(Termination t) {
    return t == Termination::NoProgress || t == Termination::RepeatedSupport || t == Termination::JohnsonFailed;
}

// A stop on a rounding rule (a stall, a repeated point, a failed sub-simplex) away from contact
// is a hit at a lower bound, and the shapes may be apart there: a segment gliding 1.3e-6 over
// another's plane (C flat, its support points tied along the plane's normal) stalled and was read
// as touching, so was a point 4e-9 from a segment with no motion, in one argument order only, and
// rays gliding 1e-8 over a triangle (found by a hard-input sweep). The distance at toi decides:
// apart by more than the loop's contact gap (polytopes, general supports included: exact_gap),
// the iteration goes on from there, searching first along the distance's axis (a plane that
// separates the rest of the ray from C ends it as a miss). Each clip only moves x towards C, so
// going on never skips a contact. Twice at most. cast_from(lambda0, v0, budget) runs the loop;
// distance_at(lambda) is the distance at lambda (world frame, from C's first shape toward the
// other), to_local its axis in the loop's frame; at_stop and at_stop_toi keep the last one.
template <class CastFrom, class DistanceAt, class ToLocal>
LocalCast go_on_past_rounding_stops(LocalCast l, uint32_t max_iterations, bool polytopes, CastFrom&& cast_from,
                                    DistanceAt&& distance_at, ToLocal&& to_local, DistanceResult& at_stop,
                                    double& at_stop_toi) {
    for (int resume = 0;
         resume < 2 && l.hit && !l.settled && l.iterations < max_iterations && rounding_stop(l.termination); ++resume) {
        at_stop = distance_at(l.lambda);
        at_stop_toi = l.lambda;
        const double gap = polytopes ? l.exact_gap : l.contact_gap;
        if (at_stop.intersecting || !(at_stop.distance > gap) || !is_finite(at_stop.axis)) break;
        const uint32_t used = l.iterations;
        const Vec3 axis = to_local(at_stop.axis);
        const bool clipped_before = l.clipped;
        const Vec3 normal_before = l.normal;
        l = cast_from(l.lambda, axis, max_iterations - used);
        l.iterations += used;
        // A resumed loop that hits without clipping would read as a start inside (normal -r): at
        // a ray point 4e-10 beside a needle, that plane cut the needle 0.18 deep (fuzzing). The
        // ray point has not moved, so the last clip's plane still holds it exactly; without one,
        // the distance's axis (on needles its plane lay up to 3e-7 of the size past the ray point).
        if (l.hit && !l.clipped && l.lambda > 0) {
            l.clipped = true;
            l.normal = clipped_before ? normal_before : axis;
        }
    }
    return l;
}

// How far apart the planes normal to n (world frame, from A toward B) through the shapes' extreme
// points lie: positive when n separates them, the overlap along n when negative.
double separation(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b, Vec3 n) {
    return dot(n, support(b, pose_b, -n)) - dot(n, support(a, pose_a, n));
}

Vec3 half_extents(const CoreOf& c) { return static_cast<const BoxShape&>(*c.shape).half_extents; }

// A ray s + lambda r (the core's frame) against a box or a segment core grown by rho >= 0, in
// closed form (box_cast.hpp), or Declined.
cast_detail::BoxCast ray_rounded_core(const CoreOf& c, double rho, Vec3 s, Vec3 r) {
    if (c.core == Core::Segment) return cast_detail::ray_capsule(segment_half_length(*c.shape), rho, s, r);
    return cast_detail::ray_rounded_box(half_extents(c), rho, s, r);
}

// A closed form's answer (box_cast.hpp; Hit or Miss, not Declined) as a cast result, one
// "iteration": normal and point (the contact at toi) in the frame that `pose` maps to the world.
CastResult closed_result(const cast_detail::BoxCast& bc, const Transform& pose, Vec3 normal, Vec3 point) {
    CastResult out;
    out.iterations = 1;
    out.termination = Termination::Separated;
    if (bc.verdict != cast_detail::BoxCast::Verdict::Hit) return out;
    out.hit = true;
    out.termination = Termination::Hit;
    out.toi = bc.toi;
    out.normal = pose.rotation * normal;
    out.point = pose.apply(point);
    return out;
}

}  // namespace

CastResult ray_cast(const Shape& shape, const Transform& pose, Vec3 origin, Vec3 translation, double tolerance,
                    uint32_t max_iterations) {
    if (rigidly_placed(shape)) {
        const PlacedShape u = unwrap_rigid(shape, pose);
        return ray_cast(*u.shape, u.pose, origin, translation, tolerance, max_iterations);
    }
    if (max_iterations == 0) max_iterations = 1;
    const Vec3 s = pose.apply_inverse(origin);
    const Vec3 r = pose.to_local_direction(translation);
    const CoreOf c = classify(shape);
    if (c.core == Core::Point) {
        const BallHit b = ball_cast(s, r, c.radius, StartNormal{r, s, &pose});
        CastResult out = b.head;
        if (!out.hit) return out;
        out.normal = pose.rotation * b.normal;
        out.point = pose.apply(c.radius * b.dir);
        return out;
    }
    // A box, rounded or not, or a capsule: in closed form (box_cast.hpp), one "iteration", unless
    // declined (a start on or in it, a graze of a plain box, a segment).
    if (c.core == Core::Box || c.core == Core::Segment) {
        const cast_detail::BoxCast bc = ray_rounded_core(c, c.radius, s, r);
        if (bc.verdict != cast_detail::BoxCast::Verdict::Declined) return closed_result(bc, pose, bc.normal, bc.point);
    }
    auto cast_from = [&](double lambda0, Vec3 v0, uint32_t budget) {
        return with_support(c, [&](auto core) {
            return CastLoop(SingleSupport<decltype(core)>{core}, c.radius, s, r, tolerance, lambda0).run(v0, budget);
        });
    };
    DistanceResult at_stop{};
    double at_stop_toi = -1;
    const LocalCast l = go_on_past_rounding_stops(
        cast_from(0, first_direction(r, s), max_iterations), max_iterations, polytope(shape), cast_from,
        [&](double lambda) {
            const PointShape ray_point;
            return gjk_distance(shape, pose, ray_point, make_transform(origin + lambda * translation, Quat{}),
                                tolerance, max_iterations);
        },
        [&](Vec3 axis) { return pose.to_local_direction(axis); }, at_stop, at_stop_toi);
    CastResult out = result_head(l);
    if (!l.hit) return out;
    Vec3 n = contact_normal(l, c.radius, r, StartNormal{r, s, &pose});
    // Point on the surface: the core's closest point pushed out by the radius along v.
    Vec3 p = l.point_a;
    if (c.radius > 0) p += c.radius * normalized_or(l.v, n);
    // After a rounding stop the simplex may lie off the ray point though the shape does not (a
    // needle of aspect 9e4: a point 2.4e-3 from the ray point, the shape 0 from it): the check's
    // distance at this toi gives a point of the shape too, and the nearer one is kept.
    if (at_stop_toi == l.lambda && rounding_stop(l.termination)) {
        const Vec3 x = s + l.lambda * r;
        const Vec3 q = pose.apply_inverse(at_stop.point_a);
        if (is_finite(q) && dot(q - x, q - x) < dot(p - x, p - x)) p = q;
    }
    // A segment or box core (capsules, rounded boxes) has its nearest point to the ray point in
    // closed form: the normal and point from it, whatever the tolerance left in v. At 1e-3 a
    // capsule's v tilted 0.009 rad along the straight side, and the plane of that normal cut the
    // ray point by 0.018 (found by fuzzing); the exact one never does.
    if (l.lambda > 0 && c.radius > 0 && (c.core == Core::Segment || c.core == Core::Box)) {
        const Vec3 x = s + l.lambda * r;
        const Vec3 q = c.core == Core::Segment
                           ? Vec3{0, 0, closed_form::clamp_to(x.z, segment_half_length(*c.shape))}
                           : closed_form::box_nearest(static_cast<const BoxShape&>(*c.shape).half_extents, x);
        const Vec3 away = x - q;
        if (is_finite(away) && max_abs(away) > 0) {
            n = normalized_or(away, n);
            p = q + c.radius * n;
        }
    }
    out.normal = pose.rotation * n;
    out.point = pose.apply(p);
    return out;
}

CastResult shape_cast(const Shape& a, const Transform& pose_a, Vec3 translation_a, const Shape& b,
                      const Transform& pose_b, Vec3 translation_b, double tolerance, uint32_t max_iterations,
                      bool overlap_normal) {
    if (rigidly_placed(a) || rigidly_placed(b)) {
        const PlacedShape ua = unwrap_rigid(a, pose_a), ub = unwrap_rigid(b, pose_b);
        return shape_cast(*ua.shape, ua.pose, translation_a, *ub.shape, ub.pose, translation_b, tolerance,
                          max_iterations, overlap_normal);
    }
    if (max_iterations == 0) max_iterations = 1;
    const CoreOf ca = classify(a), cb = classify(b);
    const RelativeFrame frame = relative_frame(pose_a, pose_b);
    const Mat3& rot = frame.r;
    const Vec3 t = frame.t;
    const Vec3 ta = pose_a.to_local_direction(translation_a);
    const Vec3 tb = pose_a.to_local_direction(translation_b);
    const Vec3 r = pose_a.to_local_direction(translation_b - translation_a);
    const double margin = ca.radius + cb.radius;
    if (ca.core == Core::Point && cb.core == Core::Point) {
        // B's centre relative to A's moves from t along r: a ray against a ball of both radii.
        const BallHit h = ball_cast(t, r, margin, StartNormal{r, t, &pose_a});
        CastResult out = h.head;
        if (!out.hit) return out;
        // The contact point: each centre at toi pushed out by its radius toward the other; the two
        // agree to rounding, the midpoint is taken (as the GJK path does).
        const Vec3 pa = ca.radius * h.dir + out.toi * ta;
        const Vec3 pb = t + out.toi * tb - cb.radius * h.dir;
        out.normal = pose_a.rotation * h.normal;
        out.point = pose_a.apply(0.5 * (pa + pb));
        return out;
    }
    // Closed forms against a box (box_cast.hpp), one "iteration"; what they decline (touching at
    // the start, grazes, nearly parallel edges) goes to the GJK cast. normal and point: A's frame,
    // A kept at its start pose.
    using cast_detail::BoxCast;
    auto closed = [&](const BoxCast& bc, Vec3 normal, Vec3 point) {
        return closed_result(bc, pose_a, normal, point + bc.toi * ta);
    };
    // Two boxes: the separating axis test over the step.
    if (ca.core == Core::Box && cb.core == Core::Box && margin == 0) {
        const BoxCast bc = cast_detail::box_box_cast(half_extents(ca), half_extents(cb), rot, t, r, tolerance);
        if (bc.verdict != BoxCast::Verdict::Declined) return closed(bc, bc.normal, bc.point);
    }
    // A ball (or point) and a box, rounded or not, or a capsule: the ball's centre as a ray against
    // the core grown by both radii, in the core's frame; the contact point is the centre at toi less
    // the ball's radius along the normal.
    const bool box_or_segment_a = ca.core == Core::Box || ca.core == Core::Segment;
    const bool box_or_segment_b = cb.core == Core::Box || cb.core == Core::Segment;
    if (box_or_segment_a && cb.core == Core::Point) {
        const BoxCast bc = ray_rounded_core(ca, margin, t, r);
        if (bc.verdict != BoxCast::Verdict::Declined) return closed(bc, bc.normal, bc.point - cb.radius * bc.normal);
    }
    if (ca.core == Core::Point && box_or_segment_b) {
        // A's centre seen from B (B's frame), moving by -r.
        const BoxCast bc = ray_rounded_core(cb, margin, -mul_transpose(rot, t), -mul_transpose(rot, r));
        if (bc.verdict != BoxCast::Verdict::Declined) {
            const Vec3 b_at = t + bc.toi * r;  // B's centre at toi, A's frame
            return closed(bc, -(rot * bc.normal), b_at + rot * (bc.point - ca.radius * bc.normal));
        }
    }
    // Two capsules: B's centre as a ray against the parallelogram of their segments grown by both radii.
    if (ca.core == Core::Segment && cb.core == Core::Segment && margin > 0) {
        const BoxCast bc = cast_detail::capsule_pair_cast(
            segment_half_length(*ca.shape), segment_half_length(*cb.shape), rot, t, r, ca.radius, cb.radius, tolerance);
        if (bc.verdict != BoxCast::Verdict::Declined) return closed(bc, bc.normal, bc.point);
    }
    // The iteration from lambda0 on, first searching along v0.
    auto cast_from = [&](double lambda0, Vec3 v0, uint32_t budget) {
        return with_support(ca, [&](auto sa) {
            return with_support(cb, [&](auto sb) {
                return CastLoop(PairSupport<decltype(sa), decltype(sb)>{sa, sb, rot, t}, margin, Vec3{}, r, tolerance,
                                lambda0)
                    .run(v0, budget);
            });
        });
    };
    auto at_toi = [&](const Transform& pose, Vec3 translation, double toi) {
        Transform moved = pose;
        moved.translation = pose.translation + toi * translation;
        return moved;
    };
    DistanceResult at_stop{};
    double at_stop_toi = -1;
    const LocalCast l = go_on_past_rounding_stops(
        cast_from(0, first_direction(r, t), max_iterations), max_iterations, polytope(a) && polytope(b), cast_from,
        [&](double lambda) {
            return gjk_distance(a, at_toi(pose_a, translation_a, lambda), b, at_toi(pose_b, translation_b, lambda),
                                tolerance, max_iterations);
        },
        [&](Vec3 axis) { return pose_a.to_local_direction(axis); }, at_stop, at_stop_toi);
    CastResult out = result_head(l);
    if (!l.hit) return out;
    const StartNormal fallback{r, t, &pose_a};
    const Vec3 n = contact_normal(l, margin, r, fallback);
    // Contact point: the cores' barycentric points pushed out by their radii along v (from A toward
    // B), each moved to its place at toi; they agree within the tolerance, the midpoint is taken.
    const Vec3 dir = margin > 0 ? normalized_or(l.v, n) : n;
    const Vec3 pa = l.point_a + ca.radius * dir + l.lambda * ta;
    const Vec3 pb = l.point_b - cb.radius * dir + l.lambda * tb;
    out.normal = pose_a.rotation * n;
    out.point = pose_a.apply(0.5 * (pa + pb));
    // Overlapping at the start (depth > 0): the minimum translation's axis and the deepest points'
    // midpoint (touching keeps the rule above, opposing the relative motion; so does a non-finite
    // answer, never expected, so that a world's contacts stay finite whatever the expansion gives).
    if (out.toi == 0) {
        if (!overlap_normal) return out;
        const DistanceResult sd = signed_distance(a, pose_a, b, pose_b, tolerance, max_iterations);
        if (sd.distance < 0 && is_finite(sd.axis) && is_finite(sd.point_a + sd.point_b)) {
            out.normal = sd.axis;
            out.point = 0.5 * (sd.point_a + sd.point_b);
        }
        return out;
    }
    // Rounded shapes whose cores have closed forms (spheres and capsules among themselves, a sphere
    // and a rounded box): the normal and point from the cores' exact closest points at toi, as the
    // ray cast does, whatever the tolerance left in v (at 1e-3 it tilted up to 0.06 rad on capsule
    // pairs and 0.11 on a sphere and a box; at 1e-1, 0.8). A direction that does not oppose the
    // motion (grazing) keeps the cast's normal.
    if (margin > 0 && closed_form_cores(ca, cb)) {
        const Transform at_a = at_toi(pose_a, translation_a, out.toi), at_b = at_toi(pose_b, translation_b, out.toi);
        const CoreDistance cd = core_distance(ca, at_a, cb, at_b, tolerance, max_iterations);
        const Vec3 nw = at_a.rotation * cd.unit;
        const Vec3 mid = 0.5 * ((cd.point_a + ca.radius * cd.unit) + (cd.point_b - cb.radius * cd.unit));
        // Cores within the rounding of their points' coordinates (radii of 1e-300 .. 1e-13 of the
        // size: the cores touch at toi) have no direction between them: a segment 4747 long
        // crossing a capsule's of radius 7e-300 got one 87 degrees off their cross product, and
        // the shapes overlapped by 20.9 across it at toi (fuzz_queries). The closed form's
        // direction is kept when it separates the shapes at toi at least as well as the cast's. A
        // gap above 2^-30 of the coordinates' scale holds the direction to 1e-6 rad: no check.
        const double coords = max_abs(at_a.translation) + max_abs(at_b.translation) + max_abs(cd.point_a) +
                              max_abs(cd.point_b);
        if (!cd.overlap && dot(cd.unit, cd.unit) > 0.5 && is_finite(mid) &&
            dot(nw, translation_b - translation_a) < 0 &&
            (cd.distance > 0x1p-30 * coords ||
             separation(a, at_a, b, at_b, nw) >= separation(a, at_a, b, at_b, out.normal))) {
            out.normal = nw;
            out.point = at_a.apply(mid);
        }
        return out;
    }
    // A stop on a rounding rule can leave a simplex whose v, and the last clipping plane, are far
    // from the contact normal on a long shape (15 degrees on a capsule stretched to 1e5 by a
    // transform, 1e-4 short of contact; found by fuzzing): the normal and point then come from
    // the distance at toi, when it opposes the motion as a contact normal does.
    // A stop within five tolerances of contact (LocalCast::settled) keeps the cast's normal: the
    // distance would cost what the stop saved, and its normal was no better on 2048 bench casts.
    if (out.toi > 0 && !l.settled && rounding_stop(l.termination)) {
        const Transform at_a = at_toi(pose_a, translation_a, out.toi), at_b = at_toi(pose_b, translation_b, out.toi);
        const DistanceResult d =
            at_stop_toi == out.toi ? at_stop : gjk_distance(a, at_a, b, at_b, tolerance, max_iterations);
        // The better of the two separates the shapes at toi by more (near a curved rim, where the
        // gap is at rounding level, the cast's own normal is). The cast's normal is judged as v
        // gives it even where v's plane cut the shapes and the clip's normal was taken: the clip's
        // plane separates well while the simplex's point may lie off the shapes after the stop
        // (0.28 outside a unit ball beside a capsule stretched to 1.3e5; fuzzing), and the
        // distance's point is the one to keep then.
        const Vec3 judged =
            l.v_plane_cuts ? pose_a.rotation * contact_normal(l, margin, r, fallback, false) : out.normal;
        if (!d.intersecting && dot(d.axis, translation_b - translation_a) < 0 &&
            separation(a, at_a, b, at_b, d.axis) > separation(a, at_a, b, at_b, judged)) {
            out.normal = d.axis;
            out.point = 0.5 * (d.point_a + d.point_b);
        }
    }
    return out;
}

}  // namespace kairos
