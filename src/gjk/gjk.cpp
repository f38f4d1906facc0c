// SPDX-License-Identifier: MIT
// GJK distance and intersection loops, instantiated per pair of support kinds (no virtual call and
// no allocation per iteration). All work happens in A's local frame; results go back to the world.
#include "gjk/gjk.hpp"
#include "gjk/bend.hpp"
#include "gjk/box_pair_distance.hpp"
#include "gjk/closed_form_distance.hpp"
#include "gjk/core_distance.hpp"
#include "gjk/loop_rules.hpp"
#include "gjk/parallel_axes.hpp"
#include "gjk/seed.hpp"
#include "gjk/simplex.hpp"
#include "gjk/support_kernels.hpp"

#include <cmath>
#include <type_traits>

namespace kairos {
namespace {

using gjk_detail::below_lower_bound;
using gjk_detail::closed_form_distance;
using gjk_detail::closed_form_pair;
using gjk_detail::LocalDistance;
using gjk_detail::prove_by_faces;
using gjk_detail::proven_axis;
using gjk_detail::refine_full_coordinates;
using gjk_detail::set_scale;
using gjk_detail::settle_floor;
using gjk_detail::settled;
using gjk_detail::Simplex;
using gjk_detail::touching;
using namespace kernels;

// ---- The distance loop -------------------------------------------------------------------------

// Recoveries from a rounding-limit stop per query (each shrinks ||v|| past rounding or restarts).
constexpr int kRecoveries = 6;

// margin: sum of the radii folded out of the shapes (0 for polytopes); the rounded shapes'
// distance is ||v|| - margin. The estimate never gets worse: a step whose new estimate is longer
// than the last one (Johnson's determinants decided by rounding on a flat tetrahedron, a sliver,
// near-duplicate points) is undone. When a rounding-limit rule fires far from the proven lower
// bound, the nearest point of the hull of the last points is found by enumeration
// (Simplex::nearest_in_hull), and failing that the simplex restarts from the best axis; the best
// estimate of every run is kept. Curved pairs' simplices slide along their rims (bend.hpp).

template <class Pair>
LocalDistance distance_loop(Pair pair, double margin, double tolerance, uint32_t max_iterations,
                            HeldTetrahedron* held = nullptr, DistanceSeed* seed = nullptr) {
    // pair by value: its scale is set from the first support points
    Simplex s;
    // First direction: B lies roughly along t from A, so the closest points are near A's support
    // toward t and B's support toward -t; v is a guess at a point of A - B (about -t).
    Vec3 v = -pair.t;
    if (!(dot(v, v) > 0)) v = normalized_or(v, {1, 0, 0});  // t may be too small to square
    double vv = 0;  // ||v||^2 of the simplex's point, once there is one
    double margin_sq = margin * margin;
    // Squared lower bound on the cores' distance: max over iterations of (v.w)^2 / ||v||^2 with
    // v.w > 0 (every point x of A - B has v.x >= v.w). No point of A - B is closer to the origin,
    // so an estimate below it is a rounding artefact (see below).
    // Kept as a fraction lower_num / lower_den (no division in the loop), with the w that gave it
    // (its norm scales the rounding of v.w).
    double lower_num = 0, lower_den = 1;
    Vec3 lower_w{}, lower_v{};
    // The best estimate of a run ended by a restart (INFINITY: none yet).
    Simplex best;
    double best_vv = INFINITY;
    int recoveries_left = kRecoveries;
    bool repeat_short = false;  // rule 5's point short of proving ||v|| along v (see the stop)

    LocalDistance out{};
    out.termination = Termination::MaxIterations;
    bool intersecting = false;
    bool scaled = false;
    gjk_detail::Slides<Pair> slides(seed != nullptr, tolerance);  // curved pairs (bend.hpp)
    s.want_lambda = slides.on;  // coordinates once, at the end, unless slides weigh by them
    if (seed != nullptr) {
        // The scale is adopted from the seed's first point when there is one (scaled then).
        gjk_detail::seed_simplex(pair, *seed, s, [&](Vec3& a, Vec3& b, Vec3& w) {
            set_scale(pair, a, b, w, margin, margin_sq);
            scaled = true;
        });
        if (s.bits != 0) {
            v = s.v;
            vv = dot(v, v);
        }
    }
    uint32_t it = 0;
    while (it < max_iterations) {
        Vec3 a, b;
        Vec3 w = pair(-v, a, b);
        slides.called(w);
        if (!scaled) {
            set_scale(pair, a, b, w, margin, margin_sq);
            scaled = true;
        }
        ++it;
        Termination stop = Termination::None;
        unsigned pool = 0;  // the points the recovery may use
        if (s.bits != 0) {
            const double vw = dot(v, w);
            if (vw > 0 && vw * vw * lower_den > lower_num * vv) {
                lower_num = vw * vw;
                lower_den = vv;
                lower_w = w;
                lower_v = v;
            }
            // Rule 1: the lower bound vw/||v|| is within tolerance of the upper bound ||v||. With a
            // margin the distance is ||v|| - margin, so the gap is compared with that instead.
            const double gap = vv - vw;
            if (margin == 0 ? gap <= tolerance * vv : gap <= tolerance * std::sqrt(vv) * (std::sqrt(vv) - margin)) {
                out.termination = Termination::RelativeError;
                break;
            }
            // Rule 5: w is a point seen before in this query: GJK would cycle.
            if (s.contains(w)) {
                stop = Termination::RepeatedSupport;
                pool = s.last_all;
                repeat_short = vw < gjk_detail::kProvenShare * vv;
            }
        }
        if (stop == Termination::None) {
            const unsigned prev_bits = s.bits;
            slides.adding(prev_bits, v);
            const Simplex::Outcome o = s.add(w, a, b, prev_bits != 0 ? vv : INFINITY);
            pool = s.last_all;
            if (o == Simplex::Outcome::Full) {
                out.termination = Termination::FullSimplex;
                intersecting = true;
                break;
            }
            if (o == Simplex::Outcome::Failed) {
                stop = Termination::JohnsonFailed;  // s keeps the previous estimate
            } else {
                const double nv = dot(s.v, s.v);
                if (prev_bits != 0 && nv * lower_den < lower_num &&
                    below_lower_bound(nv, lower_num / lower_den, dot(lower_w, lower_w))) {
                    // An estimate below the lower bound by more than the rounding of v.w cannot be
                    // a point of A - B: Johnson's determinants accepted a sub-simplex they could
                    // not resolve (a sliver triangle of support points a few ulps apart on a
                    // curved surface, whose plane passes nearer the origin than any of its
                    // points). The previous estimate is kept.
                    s.restore(prev_bits);
                    stop = Termination::JohnsonFailed;
                } else if (touching(nv, s.max_norm_sq(), margin_sq)) {
                    // A sliver triangle of A - B (two flat slabs overlapping) that Johnson's
                    // determinants accepted can have its plane through the origin while the
                    // triangle passes beside it: v is then the projection on the plane, and the
                    // coordinates, far from reproducing it, put the contact point off the shapes
                    // by their length. The triangle's own nearest point is taken instead; the loop
                    // goes on from it unless it touches too.
                    if (gjk_detail::kBitCount[s.bits] == 3) {
                        s.update_lambda();
                        if (!s.coordinates_reproduce_v(0x1p-60) && s.nearest_in_hull(s.bits, INFINITY, 0x1p-60) &&
                            !touching(dot(s.v, s.v), s.max_norm_sq(), margin_sq)) {
                            vv = dot(s.v, s.v);
                            v = s.v;
                            continue;
                        }
                    }
                    // Rule 2: v is within rounding of the origin relative to the simplex's size;
                    // or, rounded shapes, the cores are within the sum of the radii.
                    const double n2 = dot(s.v, s.v);
                    out.termination = n2 <= gjk_detail::kNearContact * s.max_norm_sq() ? Termination::NearContact
                                                                                      : Termination::FullSimplex;
                    intersecting = true;
                    break;
                } else if (prev_bits != 0 && vv - nv <= gjk_detail::kNoProgress * vv) {
                    // Rule 6: no progress. A longer estimate is rounding: the step is undone.
                    if (nv > vv) s.restore(prev_bits);
                    stop = Termination::NoProgress;
                } else {
                    vv = nv;
                    v = s.v;
                    if (slides.after_step(pair, s, vv, lower_num, lower_den, lower_w)) {
                        vv = dot(s.v, s.v);
                        v = s.v;
                    }
                    continue;
                }
            }
        }
        // A rounding-limit rule fired; s holds this run's best estimate, of norm^2 vv. After a
        // rejected step (no progress, Johnson failed) with the lower bound under half the estimate,
        // the points' hull may hold a nearer point the determinants missed, even when the estimate
        // counts as settled: a triangle of a slab 1e-8 thick holding the origin in its plane,
        // rejected, left an estimate 1e-9 of the size apart, lower bound 0. A repeated support
        // point (polytopes' usual end) adds no point, and a bound close to the estimate leaves no
        // room: settled decides.
        const bool rejected = (stop == Termination::NoProgress || stop == Termination::JohnsonFailed) &&
                              4 * lower_num < vv * lower_den;
        const bool done = settled(vv, lower_num / lower_den, s.max_norm_sq(), margin, tolerance, settle_floor<Pair>);
        const bool recover = recoveries_left > 0 && (!done || rejected);
        if (recover) --recoveries_left;
        // The hull's point is accepted when its coordinates reproduce it within 2^-30 of the
        // simplex's size, as the final witness points are: a sliver of two rim points close
        // together against both ends of a box's edge (the edge's support tied) reproduces its
        // projection only to about 1e-11 of the size, and at 2^-40 it was refused, so the loop
        // restarted and stalled up to 8e-8 of the size above the distance.
        if (recover && s.nearer_in_hull(pool, vv)) {
            vv = dot(s.v, s.v);
            v = s.v;
            if (vv <= gjk_detail::kNearContact * s.max_norm_sq() || vv <= margin_sq) {
                out.termination = vv <= margin_sq ? Termination::FullSimplex : Termination::NearContact;
                intersecting = true;
                break;
            }
            continue;
        }
        if (!recover || done) {
            out.termination = stop;
            // A repeated point proves ||v|| along v unless Johnson chose a triangle by rounding (a tip
            // over a box face's diagonal: v tilted, the repeated corner short by 6e-8 of the size).
            if ((stop != Termination::RepeatedSupport || repeat_short) && margin == 0)
                prove_by_faces(pair, s, pool, vv, lower_num, lower_den, lower_w, lower_v);
            break;
        }
        // Restart from the best axis with an empty simplex (v stays).
        if (vv < best_vv) {
            best = s;
            best_vv = vv;
        }
        s.bits = 0;
        s.last_all = 0;
    }
    // A thin tetrahedron held the origin (Simplex::hold): the shapes intersect, and an estimate
    // apart by more than 1e-9 of the tetrahedron's extent (the accuracy stated for curved pairs)
    // is a rounding stop gone wrong. Within it, the estimate's points are the more accurate answer
    // when the lower bound supports it (at least half of it); one no separating plane came near
    // is not evidence against the held signs (a box 1.3e9 long, 2 thick, through a cylinder
    // 9270 wide, both about the origin: a sliver of A - B held the origin by 0.2, the estimate
    // stopped 0.22 away with no lower bound, and the verdict was "apart" for shapes overlapping
    // by 4622; found by fuzzing).
    //
    // A lower bound that reaches half the estimate and stands clear of its own rounding (v.w is
    // rounded by some eps |w|) is a certificate, not a rounding stop: every point of A - B lies at
    // least that far from the origin, so the held signs are the ones rounding decided. A cone
    // 1.15e6 long beside a capsule's segment 0.0066 away: a sliver of A - B "held" the origin,
    // the bound proved 0.006619, and the held verdict made the signed distance 0.0066 too deep
    // (found by fuzzing).
    if (!intersecting && s.held) {
        const double est = s.bits == 0 || best_vv < dot(s.v, s.v) ? best_vv : dot(s.v, s.v);
        const bool unsupported = 4 * lower_num < est * lower_den;
        constexpr double k = 64 * 2.220446049250313e-16;
        const bool certified = !unsupported && lower_num > (k * k) * dot(lower_w, lower_w) * lower_den;
        if ((est > 1e-18 * s.held_extent_sq && !certified) || unsupported) {
            s.take_held();
            out.termination = Termination::FullSimplex;
            intersecting = true;
        }
    }
    bool changed = !intersecting && (s.bits == 0 || best_vv < dot(s.v, s.v));  // see proven_axis
    if (changed) s = best;
    // An estimate within the rounding of the support points themselves is contact, whichever rule
    // stopped (see Simplex::touches_at_points_rounding; rule 2 measures against |y| alone).
    if (!intersecting && s.bits != 0 && s.touches_at_points_rounding()) {
        out.termination = Termination::NearContact;
        intersecting = true;
    }
    out.iterations = it;
    if (seed != nullptr) gjk_detail::save_seed(pair, s, intersecting, *seed);
    s.update_lambda();
    refine_full_coordinates(s);
    // Witness points from coordinates that do not reproduce v (a sliver whose projection is right
    // and whose coordinates are not) would not be the distance apart: the nearest sub-simplex
    // whose coordinates do is taken instead (a single point always qualifies). Coordinates a
    // little below zero near an edge (clamped: the points move by up to 1e-9 of the size on
    // curved rims) are not worth a farther sub-simplex: the test allows 2^-30 of the size.
    // (A point's coordinate is 1 and an edge's are 1 - t and t of v = y_i + t e: only triangles
    // need the test.)
    if (!intersecting && gjk_detail::kBitCount[s.bits] == 3 && !s.coordinates_reproduce_v(0x1p-60)) {
        const double before = dot(s.v, s.v);
        changed |= s.nearest_in_hull(s.bits, INFINITY, 0x1p-60);
        out.lengthened = dot(s.v, s.v) > before * ((1 + tolerance) * (1 + tolerance));
    }
    const double nv = dot(s.v, s.v);
    out.intersecting = intersecting || nv <= margin_sq;
    // ||v|| and its direction without under- or overflow: a distance 1e-170 of the size squares to
    // a subnormal even at unit scale.
    const bool plain = nv > 1e-200 && nv < 1e200;
    out.unit = plain ? (-1 / std::sqrt(nv)) * s.v : normalized_or(-s.v, Vec3{});
    const Termination t = out.termination;
    if (margin == 0 && !intersecting && plain &&
        (changed || (t != Termination::RelativeError && t != Termination::RepeatedSupport) ||
         (t == Termination::RepeatedSupport && repeat_short)))
        out.proven = proven_axis(pair, s, t == Termination::RelativeError, lower_num, lower_den, lower_v);
    out.bounded = lower_num > 0;
    const double inv = 1 / pair.scale;
    const double m = max_abs(s.v);
    out.core = (plain ? std::sqrt(nv) : (m > 0 ? m * length(s.v / m) : 0.0)) * inv;
    out.v = inv * s.v;
    s.closest_points(out.point_a, out.point_b);
    out.point_a = inv * out.point_a;
    out.point_b = inv * out.point_b;
    if (intersecting && gjk_detail::common_point_on_b(s)) out.point_a = out.point_b + out.v;
    if (held != nullptr && intersecting && s.bits == 15u) {
        for (int i = 0; i < 4; ++i) held->a[i] = inv * s.pa[i], held->b[i] = inv * s.pb[i];
        held->valid = true;
    }
    return out;
}

// The distance loop, run again one support call short when its last step lengthened the
// estimate: on two curved surfaces close along a line (parallel cylinders side by side, 1e-9 of
// the size apart) GJK reaches the distance to rounding and then adds a point that makes a sliver
// triangle, whose plane's nearest point falls outside it by rounding; the nearest sub-simplex
// whose coordinates reproduce its point lay 8e-10 of the size farther, with an axis 56 degrees off
// the normal. The run one call short (deterministic, the same steps) ends at the step before.
// Both answers are points of A - B with their witness points: the nearer one is kept, with the
// first run's termination and the calls of both. One rerun at most; rare.
template <class Pair>
[[gnu::noinline, gnu::cold]] void rerun_shorter(const Pair& pair, double margin, double tolerance, LocalDistance& l) {
    const Termination t = l.termination;
    uint32_t calls = l.iterations, cap = l.iterations;
    for (int k = 0; k < 4 && cap > 1; ++k) {
        --cap;
        const LocalDistance e = distance_loop(pair, margin, tolerance, cap);
        calls += e.iterations;
        if (!e.intersecting && e.core < l.core) {
            // An axis proven for the longer estimate keeps its proof.
            const Vec3 proven = dot(e.proven, e.proven) > 0 ? e.proven : l.proven;
            l = e;
            l.proven = proven;
        }
        if (!e.lengthened) break;
    }
    l.termination = t;
    l.iterations = calls;
}
template <class Pair>
[[gnu::always_inline]] inline LocalDistance distance_query(const Pair& pair, double margin, double tolerance,
                                                           uint32_t max_iterations, HeldTetrahedron* held = nullptr,
                                                           DistanceSeed* seed = nullptr) {
    LocalDistance l = distance_loop(pair, margin, tolerance, max_iterations, held, seed);
    if (l.lengthened && !l.intersecting) [[unlikely]]
        rerun_shorter(pair, margin, tolerance, l);
    return l;
}

// ---- The intersection loop ---------------------------------------------------------------------

// The distance loop as the intersection test's rare fallback, kept out of its hot path.
template <class Pair>
[[gnu::noinline, gnu::cold]] LocalDistance distance_fallback(const Pair& pair, double margin, uint32_t max_iterations) {
    return distance_loop(pair, margin, 1e-9, max_iterations);
}

template <class Pair>
bool intersect_loop(Pair pair, double margin, Vec3& io_v, uint32_t max_iterations, uint32_t& out_iterations,
                    bool& out_unsure) {
    // pair by value: its scale is set from the first support points
    Simplex s;
    s.want_lambda = false;
    Vec3 v = io_v;
    double vv = 0;
    double margin_sq = margin * margin;
    uint32_t it = 0;
    bool result = true;
    while (it < max_iterations) {
        Vec3 a, b;
        Vec3 w = pair(-v, a, b);
        if (it == 0) set_scale(pair, a, b, w, margin, margin_sq);
        ++it;
        const double vw = dot(v, w);
        // Separating axis: every point of A - B lies beyond the plane v.x = vw > margin * ||v||.
        if (vw > 0 && vw * vw > margin_sq * dot(v, v)) {
            io_v = v;
            result = false;
            break;
        }
        // A rounding-limit rule (w seen before, no valid sub-simplex, no progress) says nothing
        // about the verdict while v is far from the origin: the distance loop, with its
        // recoveries, decides (rare).
        bool rounding_stop = s.bits != 0 && s.contains(w);
        if (!rounding_stop) {
            const unsigned prev_bits = s.bits;
            const Simplex::Outcome o = s.add(w, a, b, prev_bits != 0 ? vv : INFINITY);
            if (o == Simplex::Outcome::Full) break;
            if (o == Simplex::Outcome::Failed) {
                rounding_stop = true;
            } else {
                const double nv = dot(s.v, s.v);
                if (nv <= gjk_detail::kNearContact * s.max_norm_sq() || nv <= margin_sq) break;
                if (prev_bits != 0 && vv - nv <= gjk_detail::kNoProgress * vv) {
                    rounding_stop = true;
                } else {
                    vv = nv;
                    v = s.v;
                }
            }
        }
        if (rounding_stop) {
            const double scale = pair.scale;
            pair.scale = 1;  // the distance loop picks its own
            const LocalDistance d = distance_fallback(pair, margin / scale, max_iterations);
            it += d.iterations;
            if (!d.intersecting) {
                io_v = d.v;
                result = false;
                out_unsure = unproven_rounding_stop(d.bounded, d.termination);
            }
            break;
        }
    }
    out_iterations = it;
    return result;
}

Vec3 world_direction(const Transform& pose, Vec3 local) { return pose.rotation * local; }

// gjk_distance's answer for shapes without radii after a rounding stop with no lower bound: made
// an overlap when the expansion finds one (overlap_behind_rounding_stop). Out of gjk_distance's
// body, whose frame and registers the common path uses.
[[gnu::noinline, gnu::cold]] void settle_rounding_stop(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb,
                                                       const Transform& pose_b, Vec3 axis, double tolerance,
                                                       DistanceResult& r) {
    const epa_detail::CoreDepth d = overlap_behind_rounding_stop(ca, pose_a, cb, pose_b, axis, tolerance);
    r.iterations += d.iterations;
    if (!(d.depth > 0)) return;
    r.intersecting = true;
    r.distance = 0;
    // GJK's points, a rounding apart, are at the contact; the expansion's may not be (a curved
    // rim's support point as its bound's witness).
    r.point_a = r.point_b = 0.5 * (r.point_a + r.point_b);
    r.axis = world_direction(pose_a, d.n);
    r.termination = Termination::FullSimplex;
}

}  // namespace

bool closed_form_cores(const CoreOf& ca, const CoreOf& cb) { return closed_form_pair(ca, cb); }

CoreDistance core_distance(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b,
                           double tolerance, uint32_t max_iterations, HeldTetrahedron* held) {
    if (max_iterations == 0) max_iterations = 1;
    CoreDistance c;
    LocalDistance l;
    if (closed_form_pair(ca, cb)) {
        l = closed_form_distance(ca, pose_a, cb, pose_b, c.center_offset);
        l.intersecting = !(l.core > 0);
    } else if (!parallel_axes_distance(ca, pose_a, cb, pose_b, tolerance, l, c.center_offset)) {
        l = with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double) {
            c.center_offset = pair.t;
            return distance_query(pair, 0.0, tolerance, max_iterations, held);
        });
    }
    c.distance = l.intersecting ? 0 : l.core;
    c.overlap = l.intersecting;
    c.point_a = l.point_a;
    c.point_b = l.point_b;
    c.unit = l.unit;
    c.bounded = l.bounded;
    c.iterations = l.iterations;
    c.termination = l.termination;
    return c;
}

DistanceResult gjk_distance(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                            double tolerance, uint32_t max_iterations, HeldTetrahedron* held, DistanceSeed* seed) {
    if (rigidly_placed(a) || rigidly_placed(b)) {
        const PlacedShape ua = unwrap_rigid(a, pose_a), ub = unwrap_rigid(b, pose_b);
        return gjk_distance(*ua.shape, ua.pose, *ub.shape, ub.pose, tolerance, max_iterations, held, seed);
    }
    if (max_iterations == 0) max_iterations = 1;
    const CoreOf ca = classify(a), cb = classify(b);
    const double radius_a = ca.radius, radius_b = cb.radius;
    Vec3 center_offset;
    LocalDistance l;
    bool closed = closed_form_pair(ca, cb);  // no simplex to seed the next query with
    if (closed) {
        l = closed_form_distance(ca, pose_a, cb, pose_b, center_offset);
    } else if (parallel_axes_distance(ca, pose_a, cb, pose_b, tolerance, l, center_offset) ||
               box_pair_distance(ca, pose_a, cb, pose_b, l, center_offset)) {
        closed = true;
    } else {
        l = with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double margin) {
            center_offset = pair.t;
            return distance_query(pair, margin, tolerance, max_iterations, held, seed);
        });
    }
    if (seed != nullptr && closed) seed->count = 0;

    DistanceResult r;
    r.iterations = l.iterations;
    r.termination = l.termination;
    // Axis from A toward B: -v (v = a - b). Without a usable v (intersecting at the origin), the
    // direction between the local origins, or +x.
    const double core = l.core;
    const Vec3 n = dot(l.unit, l.unit) > 0 ? l.unit : normalized_or(center_offset, {1, 0, 0});
    Vec3 pa = l.point_a, pb = l.point_b;
    // Cores within the sum of the radii overlap, whichever rule ended the loop (a stop on no
    // progress, with the squared comparison a rounding short of it, reported distance 0 with two
    // witness points apart; found by fuzzing).
    r.intersecting = l.intersecting || !(core > radius_a + radius_b);
    if (r.intersecting) {
        r.distance = 0;
        // One contact point, inside both shapes: on the cores' closest points moved onto the overlap,
        // the point between them that splits their gap in the ratio of the radii.
        if (radius_a + radius_b > 0) pa = pa + ((core * radius_a / (radius_a + radius_b)) * n);
        pb = pa;
    } else {
        r.distance = core - (radius_a + radius_b);
        pa = pa + radius_a * n;
        pb = pb - radius_b * n;
    }
    r.point_a = pose_a.apply(pa);
    r.point_b = pose_a.apply(pb);
    const bool proven = radius_a + radius_b == 0 && dot(l.proven, l.proven) > 0;
    r.axis = world_direction(pose_a, proven ? l.proven : n);
    // A rounding stop's gap that no support call bounded from below may hide an overlap
    // (overlap_behind_rounding_stop, core_distance.hpp).
    if (!r.intersecting && radius_a + radius_b == 0 && unproven_rounding_stop(l.bounded, l.termination)) [[unlikely]]
        settle_rounding_stop(ca, pose_a, cb, pose_b, proven ? l.proven : n, tolerance, r);
    return r;
}

bool gjk_intersect(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b, Vec3& io_axis,
                   uint32_t* out_iterations) {
    if (rigidly_placed(a) || rigidly_placed(b)) {
        const PlacedShape ua = unwrap_rigid(a, pose_a), ub = unwrap_rigid(b, pose_b);
        return gjk_intersect(*ua.shape, ua.pose, *ub.shape, ub.pose, io_axis, out_iterations);
    }
    const CoreOf ca = classify(a), cb = classify(b);
    if (closed_form_pair(ca, cb)) {
        Vec3 center_offset;
        const LocalDistance l = closed_form_distance(ca, pose_a, cb, pose_b, center_offset);
        if (!l.intersecting) io_axis = world_direction(pose_a, l.unit);
        if (out_iterations) *out_iterations = 1;
        return l.intersecting;
    }
    uint32_t it = 0;
    bool unsure = false;
    Vec3 v_local = -pose_a.to_local_direction(io_axis);
    const bool usable = is_finite(v_local) && dot(v_local, v_local) > 0 && std::isfinite(dot(v_local, v_local));
    bool hit = with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double margin) {
        if (!usable) {
            v_local = -pair.t;
            if (!(dot(v_local, v_local) > 0)) v_local = {1, 0, 0};
        }
        return intersect_loop(pair, margin, v_local, 256, it, unsure);
    });
    const double vv = dot(v_local, v_local);
    if (!hit && unsure && ca.radius + cb.radius == 0) [[unlikely]] {  // see overlap_behind_rounding_stop
        const epa_detail::CoreDepth d =
            overlap_behind_rounding_stop(ca, pose_a, cb, pose_b, unit_or(-v_local, vv, {1, 0, 0}), 1e-9);
        it += d.iterations;
        hit = d.depth > 0;
    }
    if (!hit) io_axis = world_direction(pose_a, unit_or(-v_local, vv, {1, 0, 0}));
    if (out_iterations) *out_iterations = it;
    return hit;
}

}  // namespace kairos
