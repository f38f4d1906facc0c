// SPDX-License-Identifier: MIT
// GJK ray cast and shape cast loops, instantiated per pair of support kinds (no virtual call, no
// allocation). Shape casts run in A's local frame; results go back to the world frame.
//
// After a clip the simplex is kept and re-expressed about the new ray point; restarting from the
// last support point (docs/algorithms.md §3) took more iterations and time in bench_cast.
#include "casts/cast.hpp"
#include "casts/rebuild.hpp"
#include "gjk/closed_forms.hpp"
#include "gjk/core_distance.hpp"
#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "gjk/simplex.hpp"
#include "gjk/support_kernels.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace kairos {
namespace {
using namespace kernels;
using gjk_detail::Simplex;
using cast_detail::coordinates_sane;
using cast_detail::on_boundary_face;
using cast_detail::rebuild;

// C = one shape (ray cast): p = s(d); b is zero. `scale` as in PairSupport.
template <class S>
struct SingleSupport {
    static constexpr bool exact = exact_support<S>;
    S s;
    double scale = 1;
    [[gnu::always_inline]] Vec3 operator()(Vec3 d, Vec3& out_a, Vec3& out_b) const {
        out_a = s(d);
        if (scale != 1) [[unlikely]]
            out_a = scale * out_a;
        out_b = Vec3{};
        return out_a;
    }
};

// The cast's scale (a power of two, as first_scale): from the first support points and the ray's
// start, lowered while the motion r would leave 2^400 (its products with v, which is about 1 at
// that scale, stay finite).
template <class Pair>
double cast_scale(const Pair& pair, Vec3 a, Vec3 b, Vec3 x, Vec3 r) {
    double sc = first_scale(pair, a, b, x);
    const double rmax = max_abs(r);
    while (sc > 1 && !(rmax * sc <= 0x1p400)) sc = std::fmax(1.0, sc * 0x1p-100);
    return sc;
}

// ---- The cast loop ------------------------------------------------------------------------------

struct LocalCast {
    bool hit;
    bool clipped;  // at least one clip happened: `normal` holds its plane's normal
    bool settled;  // a Johnson failure at a ray point already within five tolerances of C's size
    double lambda;
    Vec3 normal;            // v of the latest clip (not unit)
    Vec3 v;                 // final x - c
    Vec3 point_a, point_b;  // barycentric points of the final simplex (cores)
    double size;            // max(|x|, the largest distance from x to a simplex point): v's rounding scale
    uint32_t iterations;
    Termination termination;
};

// Ray x(lambda) = s + lambda r against C (+ a ball of radius `margin`), C given by `sup`: the
// iteration of docs/algorithms.md §3 with its guards. One object per cast; run() once.
// The loop runs at the scale cast_scale picks after the first support (sup is a copy: its scale is
// set then); lambda does not depend on it, and the result's v and points are at the caller's.
template <class Support>
class CastLoop {
public:
    CastLoop(Support sup, double margin, Vec3 s, Vec3 r, double tolerance)
        : sup_(sup),
          margin_(margin),
          s_(s),
          r_(r),
          x_(s),
          // Below 64 ulp of the simplex's size v carries no digit: the tolerance is clamped there.
          eps_sq_(std::fmax(tolerance * tolerance, gjk_detail::kNearContact)),
          eps_(std::sqrt(eps_sq_)) {}

    // v0: the first search direction (x - some point of C; any non-zero vector works).
    LocalCast run(Vec3 v0, uint32_t max_iterations) {
        // Only v0's direction matters: brought to about unit length (exact) so its products
        // neither underflow nor overflow.
        v_ = pair_scale(v0, Vec3{}) * v0;
        // Every exit but a miss leaves lambda as a lower bound of a hit.
        Termination stop = Termination::MaxIterations;
        uint32_t it = 0;
        while (it < max_iterations) {
            Vec3 a, b;
            Vec3 p = sup_(v_, a, b);
            if (it == 0) adopt_first_scale(a, b, p);
            if constexpr (kCurved) {
                if (it == 0) first_p_ = p;
                const Vec3 spread = p - first_p_;
                const double spread_sq = dot(spread, spread);
                if (spread_sq > extent_sq_) extent_sq_ = spread_sq;
            }
            ++it;
            Vec3 w = x_ - p;
            if (!clip(p, w)) {
                stop = Termination::Separated;
                break;
            }
            stop = step(w, a, b, p);
            if (stop != Termination::None) break;
            stop = Termination::MaxIterations;
        }
        return result(stop, it);
    }

private:
    void adopt_first_scale(Vec3& a, Vec3& b, Vec3& p) {
        const double sc = cast_scale(sup_, a, b, x_, r_);
        if (sc == 1) return;
        adopt_scale(sup_, sc, a, b, margin_);
        p = a - b;
        s_ = sc * s_;
        r_ = sc * r_;
        x_ = s_;
    }

    // The support plane through p (offset by the margin along v) is tested against x. When it
    // separates x from C it clips: lambda advances to where the ray crosses it, and w follows x.
    // False when the ray misses C (x moves away from the plane, or crosses it past lambda = 1).
    bool clip(Vec3 p, Vec3& w) {
        // A tiny v is brought to about unit size first (by a power of two: exact, and every test
        // below is homogeneous in v). The loop's scale cannot always bring the gap near 1: with a
        // start 1e-300 from a point-sized shape and a motion of 10 it stops where the motion
        // reaches 2^400, the gap stays near 1e-181, and v.w underflowed to 0, so a ray passing
        // beside the shape never clipped and was read as a hit (fuzzing).
        Vec3 v = v_;
        double vw = dot(v, w);
        if (!(std::fabs(vw) > 0x1p-900)) [[unlikely]] {
            const double m = max_abs(v);
            if (m > 0 && m < 0x1p-400) {
                v = std::ldexp(1.0, -std::ilogb(m)) * v;
                vw = dot(v, w);
            }
        }
        const double offset = margin_ > 0 ? margin_ * std::sqrt(dot(v, v)) : 0.0;
        if (!(vw > offset)) return true;  // NaN fails and does not clip
        const double vr = dot(v, r_);
        if (!(vr < 0)) return false;
        double next = lambda_ - (vw - offset) / vr;
        if (!(next <= 1)) {
            // The plane's offset v.w carries rounding of a few eps |v| (|x| + |p|), which can be far
            // above the overlap when C is huge beside the other shape (a slab 1e19 wide and a unit
            // sphere ending 4 inside it): a crossing past 1 by less than that rounding is read as
            // reaching the step's end, so an entry there is never missed. Compared as the plane's
            // separation of the ray's end, not as lambdas: over a motion of subnormal length both
            // quotients overflow to inf, and inf <= inf let a ray stopped 1e10 away hit (fuzzing).
            const double rounding = 4 * std::numeric_limits<double>::epsilon() * std::sqrt(dot(v, v)) * (max_abs(x_) + max_abs(p) + margin_);
            if (!((vw - offset) + (1 - lambda_) * vr <= rounding)) return false;
            next = 1;
        }
        lambda_ = next;
        const Vec3 x_new = s_ + lambda_ * r_;
        normal_ = v_;
        clipped_ = true;
        // A clip that leaves x where it was (the step is below rounding) is not a move: the
        // iteration goes on about the same point, and its guards (rules 5 and 6) apply.
        if (!(x_new == x_)) {
            x_ = x_new;
            w = x_ - p;
            moved_ = true;
        }
        return true;
    }

    // A guard fired (rule 5, rule 6, or a stall) while ||v|| is still large: the simplex went bad
    // by rounding (near-duplicate or coplanar points), so x's status is unknown. Empties the
    // simplex (the caller adds the newest support point) while the budget lasts; a small ||v|| is
    // convergence.
    bool restart(double norm_sq) {
        if (restarts_left_ == 0 || norm_sq <= kLoose * kLoose * size_sq()) return false;
        --restarts_left_;
        sx_.bits = 0;
        sx_.last_all = 0;
        return true;
    }

    // A support point equal to a kept one, or within rounding of it, adds nothing but degeneracy.
    bool known(Vec3 a, Vec3 b, Vec3 p) const {
        const double close_sq = 1e-24 * sx_.max_norm_sq();
        for (unsigned q = sx_.bits; q; q &= q - 1) {
            const int i = std::countr_zero(q);
            const Vec3 d = (sx_.pa[i] - sx_.pb[i]) - p;
            if ((sx_.pa[i] == a && sx_.pb[i] == b) || dot(d, d) <= close_sq) return true;
        }
        return false;
    }

    // Puts w = x - p (p = a - b) into the simplex, then applies the stopping rules. Returns the
    // termination, or None to go on with the next search direction v_.
    Termination step(Vec3 w, Vec3 a, Vec3 b, Vec3 p) {
        Simplex::Outcome o;
        const unsigned prev_bits = sx_.bits;
        if (!moved_ && sx_.contains(w)) {
            if (sx_.refine_dropped()) {
                // The point came back because rounding dropped it: the simplex now holds the
                // nearer face found geometrically, and the iteration goes on from its estimate.
                // Each success shrinks ||v|| by more than rounding, so this cannot cycle (and the
                // iteration cap holds).
                vv_ = dot(sx_.v, sx_.v);
                v_ = sx_.v;
                return Termination::None;
            }
            // Rule 5 (only while x stays put: after a clip a known point is new information).
            if (!restart(vv_)) return Termination::RepeatedSupport;
            o = sx_.add(w, a, b, INFINITY);
            moved_ = true;  // a fresh simplex: its first estimate is not compared with the last
        } else if (!moved_) {
            o = sx_.add(w, a, b, vv_);
        } else if (sx_.bits != 0) {
            o = rebuild(sx_, x_, !known(a, b, p), a, b);
        } else {
            o = sx_.add(w, a, b, INFINITY);
        }
        // Near-duplicate support points (a rim point found again from a direction one ulp away)
        // make the simplex degenerate: its barycentric coordinates blow up (+-1e14 seen) and v is
        // then a point off the simplex, short enough to fake a hit. Treated as a Johnson failure.
        if ((o == Simplex::Outcome::Reduced || o == Simplex::Outcome::Backup) && !coordinates_sane(sx_))
            o = Simplex::Outcome::Failed;
        if (o == Simplex::Outcome::Failed) {
            // At a ray point already within five tolerances of C's size, a failure is the rounding
            // limit, as rules 5 and 6 judge theirs: the previous estimate stands. A restart there
            // took about 20 calls to come back to the same point on curved pairs.
            if (!moved_ && prev_bits != 0 && vv_ <= 25 * eps_sq_ * size_sq()) {
                sx_.restore(prev_bits);
                settled_ = true;
                return Termination::JohnsonFailed;
            }
            // No valid sub-simplex even after the backup pass: restart from the newest point.
            if (restarts_left_ == 0) return Termination::JohnsonFailed;
            --restarts_left_;
            sx_.bits = 0;
            o = sx_.add(w, a, b, INFINITY);
            moved_ = true;
        }
        if (o == Simplex::Outcome::Full) {  // x lies inside the core
            if (clipped_) on_boundary_face(sx_);
            return Termination::FullSimplex;
        }
        const double nv = dot(sx_.v, sx_.v);
        if (reached(nv)) return Termination::Hit;
        if (no_progress(nv)) {
            if (!restart(nv)) return Termination::NoProgress;
            sx_.add(w, a, b, INFINITY);
            best_vv_ = INFINITY;
            stalled_ = 0;
            vv_ = dot(sx_.v, sx_.v);
            v_ = sx_.v;
            return Termination::None;
        }
        moved_ = false;
        vv_ = nv;
        v_ = sx_.v;
        return Termination::None;
    }

    // The stop: ||v|| (less the margin) within eps of the simplex's size seen from x
    // (docs/algorithms.md §3), that size not below 2^-10 of C's: a simplex shrunk around x asked
    // for more digits than double has. Squares near underflow (a gap of 1e-181 at the loop's
    // scale read 0 <= 0, a hit beside a point-sized shape; fuzzing) are compared again at a
    // scale that brings v to about 1 (a power of two: exact).
    bool reached(double nv) const {
        double size_sq = std::max(sx_.max_norm_sq(), 0x1p-20 * extent_sq_), margin = margin_;
        const double m = nv < 0x1p-800 ? max_abs(sx_.v) : 0.0;
        if (m > 0) [[unlikely]] {
            const double k = std::ldexp(1.0, -std::ilogb(m));
            const Vec3 v = k * sx_.v;
            nv = dot(v, v);
            size_sq = 0;
            for (unsigned q = sx_.bits; q; q &= q - 1) {
                const Vec3 y = k * sx_.y[std::countr_zero(q)];
                size_sq = std::max(size_sq, dot(y, y));
            }
            const double e = k * std::sqrt(extent_sq_);
            size_sq = std::max(size_sq, 0x1p-20 * (e * e));
            margin *= k;
        }
        return margin > 0 ? std::sqrt(nv) - margin <= eps_ * std::sqrt(size_sq) : nv <= eps_sq_ * size_sq;
    }

    // Rule 6 while x stays put: GJK about a fixed point has converged to rounding. On curved
    // shapes rounding can also make ||v|| wander without a clip: kStall estimates in a row that do
    // not improve on the best since the last clip end the iteration the same way.
    bool no_progress(double nv) {
        bool stop = !moved_ && vv_ - nv <= gjk_detail::kNoProgress * vv_;
        if (moved_ || nv < best_vv_) {
            best_vv_ = nv;
            stalled_ = 0;
        } else if (++stalled_ >= kStall) {
            stop = true;
        }
        return stop;
    }

    LocalCast result(Termination stop, uint32_t iterations) const {
        LocalCast out{};
        out.hit = stop != Termination::Separated;
        out.termination = stop;
        out.iterations = iterations;
        out.lambda = lambda_;
        out.clipped = clipped_;
        out.settled = settled_;
        out.normal = normal_;
        out.v = sx_.bits != 0 ? sx_.v : v_;
        if (sx_.bits != 0) {
            // Coordinates that do not reproduce v (two opposite rim points of a cylinder's cap and
            // its centre: a hit point 2.5 from the ray point; found by fuzzing) give way to the
            // nearest sub-simplex whose coordinates do (points' and edges' always do).
            const Simplex* sx = &sx_;
            Simplex nearer;
            if (gjk_detail::kBitCount[sx_.bits] >= 3 && !sx_.coordinates_reproduce_v(0x1p-60)) {
                nearer = sx_;
                nearer.nearest_in_hull(nearer.bits, INFINITY, 0x1p-60);
                sx = &nearer;
            }
            sx->closest_points(out.point_a, out.point_b);
            out.size = std::sqrt(sx->max_norm_sq());
        }
        // v = x - c is rounded at eps |x| too (a one-point simplex within a radius of 1e-15 of x
        // is small, v's direction noise: a normal 1.6 degrees off; found by fuzzing).
        out.size = std::fmax(out.size, std::sqrt(dot(x_, x_)));
        if (sup_.scale != 1) {
            const double inv = 1 / sup_.scale;  // exact: a power of two within 2^+-1000
            out.size *= inv;
            out.v = inv * out.v;
            out.point_a = inv * out.point_a;
            out.point_b = inv * out.point_b;
        }
        return out;
    }

    // Below this ||v|| relative to the simplex's size a stall is convergence (curved surfaces
    // stall near 1e-7 in double precision); above it the simplex is restarted.
    static constexpr double kLoose = 1e-6;
    static constexpr int kStall = 4;

    Support sup_;
    double margin_;  // at the loop's scale, as s_, r_, x_ and every point of the simplex
    Vec3 s_, r_;     // the ray's start and motion
    Vec3 x_;         // the ray point s + lambda r
    const double eps_sq_, eps_;
    double lambda_ = 0;
    Vec3 v_;                     // search direction: x minus the simplex's closest point
    Vec3 normal_{};              // v of the latest clip (not unit)
    bool clipped_ = false;       // a clip happened: normal_ holds its plane's normal
    bool settled_ = false;       // LocalCast::settled
    bool moved_ = true;          // x moved since the last add (nothing added yet counts as moved)
    int restarts_left_ = 2;      // restarts of the simplex by the guards (Johnson failure, stalls)
    double vv_ = INFINITY;       // ||v||^2 of the current simplex estimate
    double best_vv_ = INFINITY;  // smallest ||v||^2 since the last clip
    int stalled_ = 0;            // estimates in a row, since then, that did not improve on it
    // Curved or general supports (a cylinder, a cone, a Minkowski sum): the simplex can shrink
    // around x below C's size. Polytope supports (exact vertices) keep the simplex's own size.
    static constexpr bool kCurved = !Support::exact;

    // C's size for the guards: the simplex's points seen from x, or the widest spread of C's
    // support points seen, if larger (curved supports). Near a curved contact the simplex shrinks
    // around x (points 5e-8 apart on a cylinder/cone's rim): relative to it alone a stall or
    // failure at the rounding limit looked unconverged and restarted the simplex, about 20 calls
    // to come back to the same point.
    double size_sq() const {
        const double s = sx_.max_norm_sq();
        return s > extent_sq_ ? s : extent_sq_;
    }
    Vec3 first_p_{};
    double extent_sq_ = 0;
    Simplex sx_;
};

// The normal of the latest clipping plane. With a radius the final v (x minus the core's closest
// point, about the radius long) is the normal of the rounded shape's support plane through the
// contact, exact to the tolerance, while the last clip may be an iteration older; it is used then,
// unless it fails to oppose the motion r (a guard stop short of contact, or a coarse tolerance
// stopping far from it; a clipping plane's normal always opposes r), or the radius is below 2^-20
// of l.size: v's direction then carries rounding of eps * size / radius (0.95 rad on a capsule 2e4
// long of radius 7e-300; found by fuzzing), while a clipping plane never lies past the shape.
Vec3 contact_normal(const LocalCast& l, double margin, Vec3 r, Vec3 fallback) {
    if (!l.clipped) return fallback;
    if (margin > 0x1p-20 * l.size && l.termination != Termination::MaxIterations &&
        dot(l.v, l.v) > 0.25 * margin * margin && dot(l.v, l.normal) > 0 && dot(l.v, r) < 0)
        return normalized_or(l.v, fallback);
    return normalized_or(l.normal, fallback);
}

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
BallHit ball_cast(Vec3 s, Vec3 r, double radius, Vec3 fallback) {
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
        b.normal = normalized_or(e.offset, fallback);
        b.dir = b.normal;
    } else {  // overlapping at the start: the GJK loop's normal, the contact toward the start
        b.normal = fallback;
        b.dir = normalized_or(s, fallback);
    }
    return b;
}

}  // namespace

CastResult ray_cast(const Shape& shape, const Transform& pose, Vec3 origin, Vec3 translation, double tolerance,
                    uint32_t max_iterations) {
    if (max_iterations == 0) max_iterations = 1;
    const Vec3 s = pose.apply_inverse(origin);
    const Vec3 r = pose.to_local_direction(translation);
    const CoreOf c = classify(shape);
    if (c.core == Core::Point) {
        const Vec3 fallback = normalized_or(-r, normalized_or(s, pose.to_local_direction({0, 0, 1})));
        const BallHit b = ball_cast(s, r, c.radius, fallback);
        CastResult out = b.head;
        if (!out.hit) return out;
        out.normal = pose.rotation * b.normal;
        out.point = pose.apply(c.radius * b.dir);
        return out;
    }
    const LocalCast l = with_support(c, [&](auto core) {
        return CastLoop(SingleSupport<decltype(core)>{core}, c.radius, s, r, tolerance)
            .run(first_direction(r, s), max_iterations);
    });
    CastResult out = result_head(l);
    if (!l.hit) return out;
    // Start inside: -r, or from the shape's origin toward the ray's start, or world +z.
    const Vec3 fallback = normalized_or(-r, normalized_or(s, pose.to_local_direction({0, 0, 1})));
    Vec3 n = contact_normal(l, c.radius, r, fallback);
    // Point on the surface: the core's closest point pushed out by the radius along v.
    Vec3 p = l.point_a;
    if (c.radius > 0) p += c.radius * normalized_or(l.v, n);
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
        const Vec3 fallback = normalized_or(-r, normalized_or(t, pose_a.to_local_direction({0, 0, 1})));
        const BallHit h = ball_cast(t, r, margin, fallback);
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
    const LocalCast l = with_support(ca, [&](auto sa) {
        return with_support(cb, [&](auto sb) {
            return CastLoop(PairSupport<decltype(sa), decltype(sb)>{sa, sb, rot, t}, margin, Vec3{}, r, tolerance)
                .run(first_direction(r, t), max_iterations);
        });
    });
    CastResult out = result_head(l);
    if (!l.hit) return out;
    // Overlap at the start: -r, or from A's origin toward B's, or world +z.
    const Vec3 fallback = normalized_or(-r, normalized_or(t, pose_a.to_local_direction({0, 0, 1})));
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
    auto at_toi = [&](const Transform& pose, Vec3 translation) {
        Transform moved = pose;
        moved.translation = pose.translation + out.toi * translation;
        return moved;
    };
    if (margin > 0 && closed_form_cores(ca, cb)) {
        const Transform at_a = at_toi(pose_a, translation_a), at_b = at_toi(pose_b, translation_b);
        const CoreDistance cd = core_distance(ca, at_a, cb, at_b, tolerance, max_iterations);
        const Vec3 nw = at_a.rotation * cd.unit;
        const Vec3 mid = 0.5 * ((cd.point_a + ca.radius * cd.unit) + (cd.point_b - cb.radius * cd.unit));
        if (!cd.overlap && dot(cd.unit, cd.unit) > 0.5 && is_finite(mid) &&
            dot(nw, translation_b - translation_a) < 0) {
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
    const Termination stop = l.termination;
    if (out.toi > 0 && !l.settled &&
        (stop == Termination::NoProgress || stop == Termination::RepeatedSupport || stop == Termination::JohnsonFailed)) {
        const Transform at_a = at_toi(pose_a, translation_a), at_b = at_toi(pose_b, translation_b);
        const DistanceResult d = gjk_distance(a, at_a, b, at_b, tolerance, max_iterations);
        // The better of the two separates the shapes at toi by more (near a curved rim, where the
        // gap is at rounding level, the cast's own normal is).
        auto separation = [&](Vec3 n) {
            return dot(n, support(b, at_b, -n)) - dot(n, support(a, at_a, n));
        };
        if (!d.intersecting && dot(d.axis, translation_b - translation_a) < 0 &&
            separation(d.axis) > separation(out.normal)) {
            out.normal = d.axis;
            out.point = 0.5 * (d.point_a + d.point_b);
        }
    }
    return out;
}

}  // namespace kairos
