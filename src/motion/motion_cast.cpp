// SPDX-License-Identifier: MIT
// Motion cast: conservative advancement, with disk bounds and bisection where it cannot advance
// (see motion_cast.hpp and docs/algorithms.md §4). No heap allocation: the fattened shapes live on
// the stack for one window each.
#include "motion/motion_cast.hpp"

#include <cmath>

#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "shapes/radius.hpp"

namespace kairos {
namespace motion_detail {

// Tuning of the windows, measured on random rotating pairs of every kind (tests/test_motion_cast
// prints casts and distances per query; bench_motion_cast times them):
// - kWindow: a window starts no longer than the time in which the two disks could grow to
//   kWindow times the current distance (rho |angle| per step bounds the growth rate). 2 doubled
//   the casts (the fattened shapes touch at once and get halved); 0.5 and 1 were alike.
// - kCastSlack: a fattened cast stops once its ray point is within this fraction of the distance
//   (never looser than kMaxCastTolerance, relative): finer is wasted on a loose bound, coarser
//   would read the fattened shapes as touching at the start.
// - kLoopDistanceTolerance: relative error of the distance queries inside the loop; the final one
//   runs at the caller's tolerance when that is finer.
inline constexpr double kWindow = 1.0;
// Chord trials of the second-order advancement after its first span (see advancement), measured
// like kWindow: one left steps a fine search over spans would have saved, a third saved almost none.
inline constexpr int kChordTrials = 2;
// A cast that has not settled by then is read as touching (halve the window): fattened shapes
// that overlap make GJK crawl over the disk's flat, coplanar support points.
inline constexpr uint32_t kMaxCastIterations = 64;
// Windows are not halved below this length (2^-60 of the step).
inline constexpr double kMinWindow = 0x1p-60;
inline constexpr double kCastSlack = 0.25;
inline constexpr double kMaxCastTolerance = 1e-2;
inline constexpr double kLoopDistanceTolerance = 1e-4;
inline constexpr double kMinTolerance = 1e-15;
// Rounding allowance on separations computed from supports, relative to the size.
inline constexpr double kRounding = 1e-14;
// Rounding allowance of a fattened cast's proof, relative to the size (see the loop).
inline constexpr double kCastBackoff = 1e-8;
// The final distance query (normal and point) runs no finer than this: below it GJK read a flat
// simplex on a cylinder's rim as holding the origin (sphere/cylinder pairs 1e-3 apart, 0.1 % at
// 1e-13), and the normal gains nothing from it.
inline constexpr double kFinalDistanceFloor = 1e-10;

}  // namespace motion_detail

namespace {

using namespace motion_detail;

// The corner of s's local bounding box farthest from the origin (each coordinate >= 0). A box's
// and a ball's are their sizes (what six supports would give, without them).
Vec3 local_corner(const Shape& s) {
    if (s.kind() == ShapeKind::Box) {
        const Vec3 h = static_cast<const BoxShape&>(s).half_extents;
        return {std::fabs(h.x), std::fabs(h.y), std::fabs(h.z)};
    }
    if (s.kind() == ShapeKind::Sphere) {
        const double r = std::fabs(static_cast<const SphereShape&>(s).radius);
        return {r, r, r};
    }
    Vec3 lo, hi;
    bounds(s, Transform{}, lo, hi);
    return {std::fmax(std::fabs(lo.x), std::fabs(hi.x)), std::fmax(std::fabs(lo.y), std::fabs(hi.y)),
            std::fmax(std::fabs(lo.z), std::fabs(hi.z))};
}

// An upper bound of the farthest point of s from its local origin: the corner of its local box.
double bounding_radius(const Shape& s) {
    const Vec3 m = local_corner(s);
    // Scaled before squaring: a shape 1e-220 across must not read as a point (its squares
    // underflow to 0, and a point's rule takes the other shape's radius: found by fuzzing).
    const double big = std::fmax(m.x, std::fmax(m.y, m.z));
    if (!(big > 0) || !std::isfinite(big)) return 0;
    const double r = big * length(m / big);
    return std::isfinite(r) ? r : 0;
}

Transform pose_at(const Motion& m, double t) {
    const Pose b = m.at(t);
    return make_transform(b.position, m.rotates() ? b.orientation : m.start().orientation);
}

// One body over the step: its motion and what the disk bound needs.
struct Body {
    const Shape* shape;
    const Motion* motion;
    Vec3 local_axis;  // rotation axis in the body's local frame (constant over the motion)
    double rho = 0;   // extreme radius about that axis through the local origin
    bool rotates = false;

    Body(const Shape& s, const Motion& m) : shape(&s), motion(&m) {
        rotates = m.rotates();
        if (rotates) {
            const Transform p0 = pose_at(m, 0);
            local_axis = normalized_or(p0.to_local_direction(m.axis()), {0, 0, 1});
            rho = extreme_radius(s, local_axis);
            if (!(rho >= 0) || !std::isfinite(rho)) rho = 0;
        }
    }
    // Upper bound of how fast the disk radius grows per unit of time (rho |angle|).
    double rate() const { return rotates ? rho * motion->angle() : 0; }
    // An upper bound of the support h(d) = max d.(x - origin) over the body, x - origin measured
    // from its local origin, over every time in [t, t + span], at the pose `p` it has at t: the
    // body turns by phi = angle * span about `axis`, and d.R(phi) y = (d + phi m).y + r(phi) with
    // m = d x axis and |r| <= rho |m| (phi - sin phi + 1 - cos phi); (d + phi m).y is convex in
    // phi, so its largest value over the span is at an end. s0: the support along d at p (world
    // orientation, from the origin), which the caller has already: one more support.
    double support_bound(Vec3 d, const Transform& p, double span, Vec3 s0) const {
        double h = dot(d, s0);
        if (!rotates || !(span > 0)) return h;
        const double phi = motion->angle() * span;
        const Vec3 m = cross(d, motion->axis());
        const Vec3 d1 = d + phi * m;
        const Vec3 s1 = p.rotation * support(*shape, p.to_local_direction(d1));
        h = std::fmax(h, dot(d1, s1));
        // (phi - sin phi) + (1 - cos phi) from above by the two Taylor series cut after a positive
        // term (for phi >= 0, sin phi >= phi - phi^3/6 + phi^5/120 - phi^7/5040 and cos phi >=
        // 1 - phi^2/2 + phi^4/24 - phi^6/720; at most 6 % above at phi = pi, where steps are
        // long anyway, and closer than the rounded differences at small phi): no sin or cos.
        const double p2 = phi * phi;
        const double g = p2 * ((0.5 + phi * (1.0 / 6)) -
                               p2 * ((1.0 / 24 + phi * (1.0 / 120)) - p2 * (1.0 / 720 + phi * (1.0 / 5040))));
        return h + rho * length(m) * g;
    }
    // Radius of the disk swept over [t0, t1], with a hair of slack for rounding in the poses.
    double disk(double t0, double t1) const {
        if (!rotates || !(rho > 0)) return 0;
        return motion->disk_radius(rho, t0, t1) * (1 + 1e-12);
    }
    // Velocity of the world point p carried by the body (per step), at any time: linear part plus
    // angular velocity (axis * angle) cross the arm from the body's origin at time t.
    Vec3 velocity(Vec3 p, double t) const {
        const Vec3 origin = motion->start().position + t * motion->linear();
        Vec3 v = motion->linear();
        if (rotates) v += cross(motion->angle() * motion->axis(), p - origin);
        return v;
    }
};

// Casts body x (at pose px, fattened by a disk of radius rx) against body y likewise.
CastResult fattened_cast(const Body& x, const Transform& px, double rx, Vec3 tx, const Body& y, const Transform& py,
                         double ry, Vec3 ty, double tolerance, uint32_t max_iterations) {
    // The disks and sums are stack objects: their reference counts go up and down but never
    // reach zero, so nothing is deleted; the caller's shapes keep their own references.
    const DiskShape disk_x(x.local_axis, rx), disk_y(y.local_axis, ry);
    const MinkowskiSumShape fat_x(*x.shape, disk_x), fat_y(*y.shape, disk_y);
    const Shape& sx = rx > 0 ? static_cast<const Shape&>(fat_x) : *x.shape;
    const Shape& sy = ry > 0 ? static_cast<const Shape&>(fat_y) : *y.shape;
    // At toi 0 the caller halves its window and needs no normal: no signed distance is run.
    return shape_cast(sx, px, tx, sy, py, ty, tolerance, max_iterations, false);
}

// The loop over windows of one rotating pair (at least one motion turns); run() once.
class MotionCaster {
public:
    MotionCaster(const Shape& a, const Motion& ma, const Shape& b, const Motion& mb, double tolerance,
                 uint32_t max_iterations, double size, double radii, MotionCastStats& stats)
        : a_(a),
          b_(b),
          ma_(ma),
          mb_(mb),
          body_a_(a, ma),
          body_b_(b, mb),
          tolerance_(tolerance),
          max_iterations_(max_iterations),
          size_(size),
          radii_(radii),
          delta_(tolerance * size),
          rate_(body_a_.rate() + body_b_.rate()),
          loop_tolerance_(std::fmax(tolerance, kLoopDistanceTolerance)),
          linear_rel_(mb.linear() - ma.linear()),
          speed_bound_(length(linear_rel_) + rate_),
          stats_(stats) {}

    CastResult run() {
        pa_ = pose_at(ma_, 0);
        pb_ = pose_at(mb_, 0);
        dist_ = distance_now(loop_tolerance_);
        for (;;) {
            if (stats_.steps >= kMaxMotionSteps) return report(Termination::MaxIterations);
            ++stats_.steps;
            if (dist_.intersecting || dist_.distance <= delta_) return report(Termination::Hit);
            const double h = advancement();
            if (h > 1 - t0_) return no_hit();  // no contact before the step's end
            if (t0_ + h > t0_) {
                advance(t0_ + h);
                continue;
            }
            // The advancement cannot move t0 (near contact when GJK's axis or distance is not good
            // enough to certify a step, e.g. curved surfaces below 1e-7 of their size): a window
            // short enough that the disks stay within kWindow times the distance.
            double t1 = t0_ + std::fmin(rate_ > 0 ? kWindow * dist_.distance / rate_ : 1.0, window_cap_);
            if (t1 > t_end_) t1 = t_end_;
            if (!(t1 > t0_) || window_cap_ < kMinWindow) return report(Termination::NoProgress);
            if (!cast_window(t1)) return no_hit();
        }
    }

private:
    // Distance at the current poses. A FullSimplex claim is checked by a cast with no motion and,
    // when that finds the shapes apart, measured again at a coarse tolerance. (Written when GJK
    // read capsule/cone pairs 1e-6 apart at tolerance 1e-10 as intersecting; the simplex (gjk/simplex.hpp) now rejects
    // flat tetrahedra and sub-simplices below the lower bound, and the motion tests pass without
    // this check. It stays as a cheap second opinion: it runs only on an intersection claim.)
    DistanceResult distance_now(double tol) {
        DistanceResult d = gjk_distance(a_, pa_, b_, pb_, tol, max_iterations_, nullptr, &seed_);
        dist_tolerance_ = tol;
        iterations_ += d.iterations;
        ++stats_.distances;
        if (d.intersecting && d.termination == Termination::FullSimplex) {
            const CastResult c =
                shape_cast(a_, pa_, Vec3{}, b_, pb_, Vec3{}, kMinTolerance, max_iterations_, false);  // the verdict only
            iterations_ += c.iterations;
            ++stats_.casts;
            if (!c.hit) {
                const DistanceResult coarse = gjk_distance(a_, pa_, b_, pb_, kMaxCastTolerance, max_iterations_);
                iterations_ += coarse.iterations;
                ++stats_.distances;
                if (!coarse.intersecting) {
                    d = coarse;
                    dist_tolerance_ = kMaxCastTolerance;
                }
            }
        }
        return d;
    }

    CastResult no_hit() const {
        CastResult r;
        r.hit = false;
        r.toi = 1;
        r.termination = Termination::Separated;
        r.iterations = iterations_;
        return r;
    }

    // A hit at t0 from the distance query there.
    CastResult report(Termination termination) {
        if (loop_tolerance_ > tolerance_ && !dist_.intersecting)
            dist_ = distance_now(std::fmax(tolerance_, kFinalDistanceFloor));
        CastResult r;
        r.hit = true;
        r.toi = t0_;
        r.termination = termination;
        r.iterations = iterations_;
        r.point = 0.5 * (dist_.point_a + dist_.point_b);
        if (!dist_.intersecting && dist_.distance > 0) {
            r.normal = dist_.axis;
        } else if (t0_ == 0) {
            // Overlap at the start: the minimum translation's axis, as shape_cast's; touching, the
            // normal opposes the relative velocity of the contact point (B's relative to A's), else
            // points from A's origin toward B's.
            const DistanceResult sd = signed_distance(a_, pa_, b_, pb_, tolerance_, max_iterations_);
            if (sd.distance < 0 && is_finite(sd.axis) && is_finite(sd.point_a + sd.point_b)) {
                r.normal = sd.axis;
                r.point = 0.5 * (sd.point_a + sd.point_b);
            } else {
                const Vec3 rel = body_b_.velocity(r.point, 0) - body_a_.velocity(r.point, 0);
                r.normal = normalized_or(-rel, normalized_or(pb_.translation - pa_.translation, dist_.axis));
            }
        } else {
            r.normal = clipped_ ? clip_normal_ : dist_.axis;
        }
        return r;
    }

    void advance(double t) {
        t0_ = t;
        if (t0_ >= t_end_) t_end_ = 1;  // the window is done: the rest of the step is next
        window_cap_ = INFINITY;
        pa_ = pose_at(ma_, t0_);
        pb_ = pose_at(mb_, t0_);
        dist_ = distance_now(loop_tolerance_);
    }

    // The conservative-advancement step from t0: the largest of three proven lower bounds of the
    // time to the next contact, from the distance query at t0 (0 when none proves anything).
    // (1) The separation along the distance's axis n, from two supports (exact whatever GJK's
    //     accuracy; differences taken before rotating, so far from the world origin it keeps its
    //     digits), bounds the distance from below and shrinks no faster than the approach along n
    //     plus, per body, angle * rho * |n x axis| (a point within rho of the axis moves along n no
    //     faster).
    // (2) The distance, when GJK certified it (rule 1: within its query's tolerance), shrinks no
    //     faster than the relative speed plus rho * angle per body, in any direction.
    // (3) Second order: near a closest approach the separation along n barely changes while the
    //     first-order bound still charges the full turning speed, and (1) crawls in steps of the
    //     distance over the speed (a rod turning by nearly pi past a ball 4e-8 away ran out of its
    //     4096 steps). Over a span the separation along n is at least the smaller end value of
    //     the (linear) centre term minus each body's support bound over the span
    //     (Body::support_bound), which costs a support per turning body and proves a span about
    //     sqrt(distance) long. That bound L(s) over a span s is concave in s (a minimum of linear
    //     centre terms less convex support terms), so the chord between a proven span and a failed
    //     one crosses delta no later than L does: its root is a candidate that usually proves, and
    //     each trial is checked (L > delta) whatever the shape of L. Two chords from (0, span0)
    //     come close to the longest span the bound proves (a ladder of spans a factor 4 apart,
    //     longest first, stopped well short of it and took more trials).
    double advancement() const {
        const Vec3 n = dist_.axis;
        const Vec3 sa = pa_.rotation * support(a_, pa_.to_local_direction(n));
        const Vec3 sb = pb_.rotation * support(b_, pb_.to_local_direction(-n));
        const double sep = dot(n, (pb_.translation - pa_.translation) + (sb - sa)) - kRounding * size_;
        const double rate_n = std::fmax(0.0, -dot(n, linear_rel_)) + body_a_.rate() * length(cross(n, ma_.axis())) +
                              body_b_.rate() * length(cross(n, mb_.axis()));
        double h = 0;
        if (sep > 0) h = rate_n > 0 ? sep / rate_n : INFINITY;
        if (dist_.termination == Termination::RelativeError && speed_bound_ > 0) {
            const double certified = dist_.distance * (1 - dist_tolerance_) - kRounding * size_;
            if (certified / speed_bound_ > h) h = certified / speed_bound_;
        }
        if (sep > delta_ && h < 1 - t0_) {
            const Vec3 c0 = pb_.translation - pa_.translation;
            double span = 1 - t0_;
            const double curvature = body_a_.rate() * ma_.angle() + body_b_.rate() * mb_.angle();
            if (curvature > 0) span = std::fmin(span, std::fmax(4 * h, std::sqrt(2 * sep / curvature)));
            if (span > h) {
                auto lower = [&](double s) {
                    const double centre = std::fmin(dot(n, c0), dot(n, c0 + s * linear_rel_));
                    return centre - body_a_.support_bound(n, pa_, s, sa) - body_b_.support_bound(-n, pb_, s, sb) -
                           kRounding * size_;
                };
                // [lo, hi]: lo proven (L(lo) > delta, or lo = 0), hi not. The comparisons fail on NaN.
                double lo = 0, lower_lo = lower(0), hi = span, lower_hi = lower(span);
                if (lower_hi > delta_) return span;
                for (int trial = 0; trial < kChordTrials; ++trial) {
                    // A candidate no longer than h would prove nothing new (far from contact, where
                    // the first-order bound wins, that ends the trials at once).
                    const double s = lo + (hi - lo) * ((lower_lo - delta_) / (lower_lo - lower_hi));
                    if (!(s > lo && s > h && s < hi)) break;
                    const double l = lower(s);
                    if (l > delta_) {
                        lo = s;
                        lower_lo = l;
                    } else {
                        hi = s;
                        lower_hi = l;
                    }
                }
                if (lo > h) return lo;
            }
        }
        return h;
    }

    // Casts the fattened shapes over the window [t0, t1] and moves t0 past what the cast proves
    // free of contact, or halves the window while the fattened shapes touch at t0. False when the
    // cast proves the rest of the step free.
    bool cast_window(double t1) {
        // Each body at its orientation at the window's middle (every orientation of the window is
        // within half the angle of it, so the disk is about half as wide as one about the start)
        // and its position at t0, cast with its translation.
        const double tm = 0.5 * (t0_ + t1);
        const double ra = body_a_.disk(t0_, tm), rb = body_b_.disk(t0_, tm);
        Transform qa = pa_, qb = pb_;
        if (body_a_.rotates) qa.rotation = pose_at(ma_, tm).rotation;
        if (body_b_.rotates) qb.rotation = pose_at(mb_, tm).rotation;
        const Vec3 ta = (t1 - t0_) * ma_.linear(), tb = (t1 - t0_) * mb_.linear();
        // The cast's accuracy (absolute): no finer than needed to land within delta / 2 of the
        // true contact when the disks are that thin, and coarse enough elsewhere; always well below
        // the distance so that "touching at the start" means the disks, not the cast's slack.
        const double reach = length(pb_.translation - pa_.translation) + radii_ + 2 * (ra + rb);
        const double target = std::fmax(0.5 * delta_, std::fmin(kCastSlack * dist_.distance, ra + rb));
        double cast_tolerance = reach > 0 ? target / reach : kMaxCastTolerance;
        if (!(cast_tolerance <= kMaxCastTolerance)) cast_tolerance = kMaxCastTolerance;
        if (!(cast_tolerance >= kMinTolerance)) cast_tolerance = kMinTolerance;

        const CastResult c = fattened_cast(body_a_, qa, ra, ta, body_b_, qb, rb, tb, cast_tolerance,
                                           std::min(max_iterations_, kMaxCastIterations));
        iterations_ += c.iterations;
        ++stats_.casts;

        // A cast's proof rests on support points and clipping planes computed in double precision:
        // on curved surfaces near contact (distances near 1e-9 of the size) a clip or a miss came
        // out up to 2.4e-10 of the step past the truth. Each advance by a cast backs off by the
        // time in which the shapes could close kCastBackoff of their size.
        const double backoff = speed_bound_ > 0 ? kCastBackoff * size_ / speed_bound_ : 0;
        double t_next = t0_;
        if (!c.hit) {
            // Proven free of contact over [t0, t1].
            if (t1 >= 1) return false;
            t_next = t1 - backoff;
            t_end_ = 1;
        } else {
            const double t_clip = t0_ + c.toi * (t1 - t0_) - backoff;
            if (c.toi > 0 && t_clip > t0_) {
                // No contact before the fattened shapes meet.
                t_next = t_clip < t1 ? t_clip : t1;
                clip_normal_ = c.normal;
                clipped_ = true;
            } else {
                ++stats_.bisections;
            }
        }
        if (t_next > t0_) {
            advance(t_next);
        } else {
            // The fattened shapes touch at t0 while the true ones are apart, and nothing else
            // moved t0: halve the window, first half first (the same t0 and distance).
            window_cap_ = 0.5 * std::fmin(window_cap_, t1 - t0_);
        }
        return true;
    }

    const Shape& a_;
    const Shape& b_;
    const Motion& ma_;
    const Motion& mb_;
    const Body body_a_, body_b_;
    const double tolerance_;
    const uint32_t max_iterations_;
    const double size_;            // the contact distance's scale (see motion_cast)
    const double radii_;           // the sum of the shapes' bounding radii
    const double delta_;           // "within the tolerance of contact": tolerance * size
    const double rate_;            // the disks grow at most this fast (per step)
    const double loop_tolerance_;  // of the distance queries inside the loop
    const Vec3 linear_rel_;        // B's velocity relative to A's (per step)
    const double speed_bound_;     // |d distance / dt| <= this (per step)
    MotionCastStats& stats_;
    uint32_t iterations_ = 0;    // support evaluations of every query so far
    double t0_ = 0;              // no contact in [0, t0]
    Transform pa_, pb_;          // the poses at t0
    DistanceResult dist_;        // the distance at t0
    DistanceSeed seed_;          // the last distance's simplex, where the next one starts
    double dist_tolerance_ = 0;  // the relative tolerance of the query behind dist_
    Vec3 clip_normal_{};         // world, from A toward B, of the latest clip of a fattened cast
    bool clipped_ = false;
    // The current window is [t0, t1] with t1 = min(t_end, t0 + window_cap, the disk rule).
    double t_end_ = 1;              // the end of the window being worked through
    double window_cap_ = INFINITY;  // halved while the fattened shapes touch at t0; reset on progress
};

}  // namespace

CastResult motion_cast(const Shape& a, const Motion& ma, const Shape& b, const Motion& mb, double tolerance,
                       uint32_t max_iterations, MotionCastStats* out_stats) {
    MotionCastStats stats;
    if (max_iterations == 0) max_iterations = 1;
    // Comparisons written so that NaN takes the minimum.
    if (!(tolerance >= kMinTolerance)) tolerance = kMinTolerance;
    if (tolerance > 0.5) tolerance = 0.5;

    // The contact distance scales with the smaller shape (a rod against a huge wall: the rod), or
    // the other one when that is a point.
    const double radius_a = bounding_radius(a), radius_b = bounding_radius(b);
    const double size = radius_a > 0 && radius_b > 0 ? std::fmin(radius_a, radius_b) : std::fmax(radius_a, radius_b);

    if (!ma.rotates() && !mb.rotates()) {
        // Pure translations: the exact shape cast, nothing paid for rotation. It stops with the
        // ray point within eps * max|y| of A - B, and near contact max|y| <= gap + diam(A - B) <=
        // gap + 2 (rA + rB); this eps keeps the gap within delta, as the contract says.
        stats.casts = 1;
        stats.steps = 1;
        if (out_stats) *out_stats = stats;
        const double delta = tolerance * size;
        const double reach = 2 * (radius_a + radius_b);
        // delta may underflow to 0 (a segment 5e-324 long against a ball: tolerance * 5e-324): the
        // finest cast then, not the caller's tolerance, which is relative to the reach (a hit 1e-3
        // short of contact at tolerance 0.5; found by fuzzing).
        const double cast_tolerance = reach > 0 ? std::fmax(delta / (reach + delta), kMinTolerance) : tolerance;
        return shape_cast(a, make_transform(ma.start().position, ma.start().orientation), ma.linear(), b,
                          make_transform(mb.start().position, mb.start().orientation), mb.linear(), cast_tolerance,
                          max_iterations);
    }
    const CastResult r = MotionCaster(a, ma, b, mb, tolerance, max_iterations, size, radius_a + radius_b, stats).run();
    if (out_stats) *out_stats = stats;
    return r;
}

}  // namespace kairos
