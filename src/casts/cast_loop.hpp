// SPDX-License-Identifier: MIT
// The GJK ray cast's iteration (docs/algorithms.md §3), shared by the ray cast and the shape cast
// (cast.cpp): a ray x(lambda) = s + lambda r against C given by a support (one shape, or A - B),
// with its guards. Internal; one object per cast, instantiated per pair of support kinds.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "casts/rebuild.hpp"
#include "gjk/simplex.hpp"
#include "gjk/support_kernels.hpp"
#include "gjk/termination.hpp"
#include "math/math.hpp"

namespace kairos::cast_detail {

using gjk_detail::Simplex;
using kernels::adopt_scale;
using kernels::exact_support;
using kernels::first_scale;
using kernels::pair_scale;

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
    bool clipped;               // at least one clip happened: `normal` holds its plane's normal
    bool settled;               // a Johnson failure at a ray point already within five tolerances of C's size
    bool v_plane_cuts = false;  // CastLoop::v_plane_cuts: the final v's plane cuts C at x
    double lambda;
    Vec3 normal;            // v of the latest clip (not unit)
    Vec3 v;                 // final x - c
    Vec3 point_a, point_b;  // barycentric points of the final simplex (cores)
    double size;            // max(|x|, the largest distance from x to a simplex point): v's rounding scale
    // Within this gap of C a stop on a rounding rule counts as contact: exact_gap, twice the
    // stopping rule's eps * size; contact_gap, on curved and general supports at least 5e-8 of
    // C's spread of support points, where double precision stalls (the bound the header states
    // for cylinders), else exact_gap.
    double exact_gap, contact_gap;
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
    // lambda0: where on the ray the iteration starts (a point known to lie before any contact).
    CastLoop(Support sup, double margin, Vec3 s, Vec3 r, double tolerance, double lambda0 = 0)
        : sup_(sup),
          margin_(margin),
          s_(s),
          r_(r),
          x_(lambda0 != 0 ? s + lambda0 * r : s),
          // Below 64 ulp of the simplex's size v carries no digit: the tolerance is clamped there.
          eps_sq_(std::fmax(tolerance * tolerance, gjk_detail::kNearContact)),
          eps_(std::sqrt(eps_sq_)),
          lambda_(lambda0) {}

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
        LocalCast out = result(stop, it);
        if (margin_ > 0 && out.hit && clipped_ && sx_.bits != 0) out.v_plane_cuts = v_plane_cuts();
        return out;
    }

private:
    void adopt_first_scale(Vec3& a, Vec3& b, Vec3& p) {
        const double sc = cast_scale(sup_, a, b, x_, r_);
        if (sc == 1) return;
        adopt_scale(sup_, sc, a, b, margin_);
        p = a - b;
        s_ = sc * s_;
        r_ = sc * r_;
        x_ = lambda_ != 0 ? s_ + lambda_ * r_ : s_;
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
                v = unit_scale(m) * v;
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
        } else if (passes_beside(v, vw - offset, p)) {
            return false;
        }
        return true;
    }

    // x stays put though the plane holds it well clear of C: the crossing's lambda is below
    // rounding (a start 1e-300 beside a point with a motion of 1e62: lambda 3e-362 underflowed),
    // and the loop could only stop on a rounding rule, read as a hit. A plane parallel to the ray
    // that holds x off C proves a miss, but a normal built by rounding (v less its part along r)
    // tilts by eps, and over a motion 1e340 times the gap the ray crosses it. r's components
    // swapped in pairs, one negated, are normal to r exactly (their dot product with r is
    // r_i r_j - r_j r_i): the three such planes through C's supports are tried. Asked only for a
    // gap above 2^-20 of |x| + |p| (a clip at convergence that leaves x put costs nothing).
    bool passes_beside(Vec3 v, double gap, Vec3 p) {
        if (!(gap > 0x1p-20 * std::sqrt(dot(v, v)) * (max_abs(x_) + max_abs(p)))) return false;
        const Vec3 normals[3] = {{r_.y, -r_.x, 0}, {0, r_.z, -r_.y}, {-r_.z, 0, r_.x}};
        for (Vec3 n : normals) {
            const double m = max_abs(n);
            if (!(m > 0) || !std::isfinite(m)) continue;
            n = unit_scale(m) * n;  // keeps it normal to r exactly
            if (dot(n, v) < 0) n = -n;
            Vec3 a, b;
            const Vec3 q = sup_(n, a, b);
            const double offset = margin_ > 0 ? margin_ * std::sqrt(dot(n, n)) : 0.0;
            const double rounding = 32 * std::numeric_limits<double>::epsilon() * (max_abs(x_) + max_abs(q) + margin_);
            if (dot(n, x_ - q) - offset > rounding) return true;
        }
        return false;
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
            // Before a restart, the hull of the last points searched geometrically: at the rounding
            // limit of curved pairs (||v|| 1e-9 of the size, above the bound just tested) it
            // usually holds a point nearer x than the last estimate, while the newest point alone
            // can be a far corner of a flat part of C (restarting from it took about 20 calls back
            // to where the iteration was, in 1 of 10 cylinder/cone hits).
            if (!moved_ && prev_bits != 0 && vv_ <= kLoose * kLoose * size_sq() &&
                sx_.nearer_in_hull(sx_.last_all, vv_)) {
                o = Simplex::Outcome::Reduced;
            } else {
                // No valid sub-simplex even after the backup pass: restart from the newest point.
                if (restarts_left_ == 0) return Termination::JohnsonFailed;
                --restarts_left_;
                sx_.bits = 0;
                o = sx_.add(w, a, b, INFINITY);
                moved_ = true;
            }
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
            const double k = unit_scale(m);
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

    // Whether the plane of the final v, offset by the margin (the contact normal a rounded pair
    // takes, contact_normal in cast.cpp), cuts C grown by the margin at x by more than the
    // tolerance, at most 1e-6, of the loop's size. At loose tolerances v tilts by about the square
    // root of the tolerance: its plane cut an ellipsoid 306 wide and a unit sphere by 1.72 at
    // tolerance 1e-3 (fuzzing). One more support call, for rounded shapes' hits only.
    bool v_plane_cuts() {
        const Vec3 v = sx_.v;
        const double vv = dot(v, v);
        if (!(vv > 0) || !std::isfinite(vv)) return false;
        Vec3 a, b;
        const Vec3 p = sup_(v, a, b);
        const double norm = std::sqrt(vv);
        const double size = std::sqrt(std::max(sx_.max_norm_sq(), dot(x_, x_)));
        // v.(x - p) >= (margin - the allowance) |v| holds x beyond the plane, up to the allowance.
        return dot(v, x_ - p) < (margin_ - std::fmin(eps_, 1e-6) * size) * norm;
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
        out.exact_gap = out.contact_gap = 2 * eps_ * out.size;
        if constexpr (kCurved) out.contact_gap = std::fmax(out.exact_gap, 5e-8 * std::sqrt(extent_sq_));
        if (sup_.scale != 1) {
            const double inv = 1 / sup_.scale;  // exact: a power of two within 2^+-1000
            out.size *= inv;
            out.exact_gap *= inv;
            out.contact_gap *= inv;
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
    double lambda_;
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

}  // namespace kairos::cast_detail
