// SPDX-License-Identifier: MIT
// Verdicts on FCL's answers: distance, nearest points, collision and time of contact, each against
// Kairos's answer and, where Kairos can certify one, bounds of the truth (docs/fcl-regression.md,
// "Reading a verdict").
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/narrowphase/collision_object.h>

#include "kairos/fcl.hpp"

namespace kairos::fcl_check {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// FCL's conservative advancement stops once a step would be shorter than 1e-4 of the motion
// (ShapeConservativeAdvancementTraversalNode::t_err, fixed in FCL 0.7), measured with its own
// motion bound, which exceeds the reach used here (a bounding volume's corners, a screw's
// lever); an early answer is accepted up to ten times that threshold (conservative, not wrong).
constexpr double kFclAdvancementStop = 1e-3;

kairos_query_settings reference_settings() {
    kairos_query_settings s;
    kairos_query_settings_init(&s);
    s.tolerance = 1e-12;
    s.max_iterations = 1000;
    return s;
}

double dot(kairos_vec3 a, kairos_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
kairos_vec3 sub(kairos_vec3 a, kairos_vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
kairos_vec3 neg(kairos_vec3 a) { return {-a.x, -a.y, -a.z}; }
double norm(kairos_vec3 a) { return std::sqrt(dot(a, a)); }
double norm(const kairos_pose& p) { return norm(p.position); }

std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* format, ...) {
    char buf[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    return buf;
}

void require(int32_t status, const char* what) {
    if (status != KAIROS_OK)
        throw std::runtime_error(std::string("kairos_fcl: ") + what + " failed: " + kairos_status_name(status) + ": " +
                                 kairos_last_error());
}

// Distance from a world point to a posed shape (0 inside).
double point_distance(const kairos_shape* shape, const kairos_pose& pose, const fcl::Vector3d& p) {
    static thread_local Shape point = [] {
        kairos_shape* s = nullptr;
        require(kairos_shape_point(&s), "kairos_shape_point");
        return Shape(s);
    }();
    const kairos_pose at{{p[0], p[1], p[2]}, {0, 0, 0, 1}};
    const kairos_query_settings s = reference_settings();
    kairos_distance_result r;
    require(kairos_distance(point.get(), &at, shape, &pose, &s, &r), "kairos_distance (point)");
    return r.distance;
}

}  // namespace

const char* to_string(Outcome outcome) {
    switch (outcome) {
        case Outcome::Agree:
            return "agree";
        case Outcome::FclOff:
            return "FCL off";
        case Outcome::NotJudged:
            return "not judged";
    }
    return "?";
}

std::string to_string(const Verdict& v) {
    std::string s = v.quantity + ": " + to_string(v.outcome);
    s += fmt(" (FCL %.17g, Kairos %.17g", v.fcl, v.kairos);
    if (!std::isnan(v.lower)) s += fmt(", truth in [%.17g, %.17g]", v.lower, v.upper);
    if (v.outcome == Outcome::FclOff) s += fmt(", off by %.6g beyond a band of %.3g", v.error, v.tolerance);
    s += ")";
    if (!v.detail.empty()) s += ": " + v.detail;
    return s;
}

// ---- Reference ------------------------------------------------------------------------------------

Reference::Reference(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                     const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b)
    : Reference(to_kairos(a), to_kairos(transform_a), to_kairos(b), to_kairos(transform_b)) {}

Reference::Reference(Shape a, const kairos_pose& pose_a, Shape b, const kairos_pose& pose_b)
    : a_(std::move(a)), b_(std::move(b)), pose_a_(pose_a), pose_b_(pose_b) {
    size_ = std::max(bounding_radius(a_.get()), bounding_radius(b_.get()));
}

void Reference::compute() const {
    if (computed_) return;
    const kairos_query_settings s = reference_settings();
    require(kairos_distance(a_.get(), &pose_a_, b_.get(), &pose_b_, &s, &distance_), "kairos_distance");
    if (distance_.intersecting) {
        kairos_distance_result sd;
        require(kairos_signed_distance(a_.get(), &pose_a_, b_.get(), &pose_b_, &s, &sd), "kairos_signed_distance");
        signed_ = std::min(sd.distance, 0.0);
        lower_ = upper_ = 0;
    } else {
        // The slab between the support planes normal to the axis separates the shapes: its width
        // is a lower bound, and two points of the shapes give an upper bound.
        const kairos_vec3 n = distance_.axis;
        lower_ = dot(n, world_support(b_.get(), pose_b_, neg(n))) - dot(n, world_support(a_.get(), pose_a_, n));
        upper_ = norm(sub(distance_.point_b, distance_.point_a));
        lower_ = std::max(0.0, std::min(lower_, upper_));
        signed_ = distance_.distance;
    }
    computed_ = true;
}

const kairos_distance_result& Reference::distance() const {
    compute();
    return distance_;
}
double Reference::signed_distance() const {
    compute();
    return signed_;
}
double Reference::lower_bound() const {
    compute();
    return lower_;
}
double Reference::upper_bound() const {
    compute();
    return upper_;
}

double Reference::band(double fcl_tolerance) const {
    return fcl_tolerance + 1e-14 * (norm(pose_a_) + norm(pose_b_) + size_);
}

Verdict Reference::check_distance(const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                                  const Tolerance& tolerance) const {
    compute();
    Verdict v;
    v.quantity = "distance";
    v.fcl = result.min_distance;
    const bool intersecting = distance_.intersecting != 0;
    v.kairos = intersecting ? (request.enable_signed_distance ? signed_ : 0.0) : distance_.distance;
    v.lower = lower_;
    v.upper = upper_;
    v.tolerance = tolerance.relative * size_ + tolerance.absolute +
                  band(request.distance_tolerance + request.abs_err + request.rel_err * upper_);
    if (!std::isfinite(v.fcl)) {
        v.outcome = Outcome::FclOff;
        v.error = std::numeric_limits<double>::infinity();
        v.detail = "FCL returned a non-finite distance";
        return v;
    }
    if (v.fcl < 0 && !request.enable_signed_distance) {
        // FCL's "the shapes intersect": the truth must be within the band of 0.
        v.error = lower_;
        v.detail = intersecting ? "both find the shapes intersecting"
                                : fmt("FCL reports intersection (%.6g) but the shapes are at least %.17g apart",
                                      v.fcl, lower_);
    } else if (v.fcl < 0 || (request.enable_signed_distance && intersecting)) {
        // A signed answer: Kairos's depth is not certified, its distance when apart is.
        if (intersecting) {
            v.lower = v.upper = kNaN;
            v.error = std::fabs(v.fcl - signed_);
            v.detail = fmt("signed distance: Kairos %.17g (expanding polytope, not certified)", signed_);
        } else {
            v.error = lower_ - v.fcl;
            v.detail = fmt("FCL reports a depth of %.6g but the shapes are at least %.17g apart", -v.fcl, lower_);
        }
    } else {
        v.error = std::max({0.0, lower_ - v.fcl, v.fcl - upper_});
        if (intersecting)
            v.detail = fmt("the shapes intersect (Kairos depth %.6g) but FCL reports a distance", -signed_);
    }
    v.outcome = v.error > v.tolerance ? Outcome::FclOff : Outcome::Agree;
    if (v.outcome == Outcome::Agree) v.error = 0;
    return v;
}

Verdict Reference::check_nearest_points(const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                                        const Tolerance& tolerance) const {
    compute();
    Verdict v;
    v.quantity = "nearest points";
    v.kairos = distance_.distance;
    v.lower = lower_;
    v.upper = upper_;
    v.tolerance = tolerance.relative * size_ + tolerance.absolute +
                  band(request.distance_tolerance + request.abs_err + request.rel_err * upper_);
    const fcl::Vector3d& p0 = result.nearest_points[0];
    const fcl::Vector3d& p1 = result.nearest_points[1];
    v.fcl = (p1 - p0).norm();
    if (!request.enable_nearest_points) {
        v.detail = "nearest points were not requested";
        return v;
    }
    if (!(result.min_distance >= 0) || distance_.intersecting || lower_ <= v.tolerance) {
        // FCL promises points on the surfaces only for separated shapes (DistanceRequest's table).
        v.detail = "touching or intersecting: FCL does not promise nearest points then";
        return v;
    }
    if (!p0.allFinite() || !p1.allFinite()) {
        v.outcome = Outcome::FclOff;
        v.error = std::numeric_limits<double>::infinity();
        v.detail = "FCL returned a non-finite nearest point";
        return v;
    }
    const double e0 = point_distance(a_.get(), pose_a_, p0);
    const double e1 = point_distance(b_.get(), pose_b_, p1);
    v.error = std::max({e0, e1, std::fabs(v.fcl - result.min_distance), v.fcl - upper_, lower_ - v.fcl, 0.0});
    v.outcome = v.error > v.tolerance ? Outcome::FclOff : Outcome::Agree;
    if (v.outcome == Outcome::FclOff) {
        v.detail = fmt("nearest_points[0] lies %.6g from A, nearest_points[1] %.6g from B; |p1 - p0| = %.17g, "
                       "min_distance %.17g",
                       e0, e1, v.fcl, result.min_distance);
    } else {
        v.error = 0;
    }
    return v;
}

Verdict Reference::check_collision(const fcl::CollisionRequestd& request, const fcl::CollisionResultd& result,
                                   const Tolerance& tolerance) const {
    compute();
    Verdict v;
    v.quantity = "collision";
    v.fcl = result.isCollision() ? 1 : 0;
    v.kairos = distance_.intersecting ? 1 : 0;
    v.tolerance = tolerance.relative * size_ + tolerance.absolute + band(request.gjk_tolerance);
    if (!distance_.intersecting) v.lower = lower_, v.upper = upper_;
    const bool apart = !distance_.intersecting && lower_ > v.tolerance;
    const bool overlapping = distance_.intersecting && -signed_ > v.tolerance;
    if (!apart && !overlapping) {
        v.detail = fmt("the shapes touch within the band (signed distance %.3g)", signed_);
        return v;
    }
    if (apart && v.fcl == 1) {
        v.outcome = Outcome::FclOff;
        v.error = lower_;
        v.detail = fmt("FCL reports a collision but the shapes are at least %.17g apart", lower_);
    } else if (overlapping && v.fcl == 0) {
        v.outcome = Outcome::FclOff;
        v.error = -signed_;
        v.detail = fmt("FCL reports no collision but the shapes overlap by %.17g", -signed_);
    } else {
        v.outcome = Outcome::Agree;
    }
    return v;
}

Verdict check_distance(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                       const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b,
                       const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                       const Tolerance& tolerance) {
    return Reference(a, transform_a, b, transform_b).check_distance(request, result, tolerance);
}
Verdict check_distance(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                       const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                       const Tolerance& tolerance) {
    return check_distance(*a.collisionGeometry(), a.getTransform(), *b.collisionGeometry(), b.getTransform(),
                          request, result, tolerance);
}
Verdict check_nearest_points(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                             const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b,
                             const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                             const Tolerance& tolerance) {
    return Reference(a, transform_a, b, transform_b).check_nearest_points(request, result, tolerance);
}
Verdict check_collision(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                        const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b,
                        const fcl::CollisionRequestd& request, const fcl::CollisionResultd& result,
                        const Tolerance& tolerance) {
    return Reference(a, transform_a, b, transform_b).check_collision(request, result, tolerance);
}
Verdict check_collision(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                        const fcl::CollisionRequestd& request, const fcl::CollisionResultd& result,
                        const Tolerance& tolerance) {
    return check_collision(*a.collisionGeometry(), a.getTransform(), *b.collisionGeometry(), b.getTransform(),
                           request, result, tolerance);
}

// ---- Continuous --------------------------------------------------------------------------------

namespace {

// Kairos's motion at time t: the origin on its line, the orientation on the shortest arc.
kairos_pose pose_at(const kairos_motion& m, double t) {
    kairos_pose p;
    const kairos_vec3 a = m.start.position, b = m.end.position;
    p.position = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    Eigen::Quaterniond q0(m.start.orientation.w, m.start.orientation.x, m.start.orientation.y, m.start.orientation.z);
    Eigen::Quaterniond q1(m.end.orientation.w, m.end.orientation.x, m.end.orientation.y, m.end.orientation.z);
    q0.normalize();
    q1.normalize();
    // Eigen's slerp takes the shorter arc itself.
    const Eigen::Quaterniond q = t == 0 ? q0 : q0.slerp(t, q1).normalized();
    p.orientation = {q.x(), q.y(), q.z(), q.w()};
    return p;
}

double turn_angle(const kairos_motion& m) {
    const kairos_quat a = m.start.orientation, b = m.end.orientation;
    const double c = std::fabs(a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w);
    return 2 * std::acos(std::min(1.0, c));
}

struct Path {
    const kairos_shape* a;
    const kairos_shape* b;
    kairos_motion ma, mb;
    bool convex;  // translation only: the signed distance is convex in t
    double signed_distance(double t) const {
        const kairos_pose pa = pose_at(ma, t), pb = pose_at(mb, t);
        const kairos_query_settings s = reference_settings();
        kairos_distance_result r;
        require(kairos_signed_distance(a, &pa, b, &pb, &s, &r), "kairos_signed_distance");
        return r.distance;
    }
    // Lower bound of the distance at t (0 when intersecting), certified by the separating axis.
    double gap(double t) const {
        const kairos_pose pa = pose_at(ma, t), pb = pose_at(mb, t);
        const kairos_query_settings s = reference_settings();
        kairos_distance_result r;
        require(kairos_distance(a, &pa, b, &pb, &s, &r), "kairos_distance");
        if (r.intersecting) return 0;
        const kairos_vec3 n = r.axis;
        return std::max(0.0, dot(n, world_support(b, pb, neg(n))) - dot(n, world_support(a, pa, n)));
    }
    // The earliest time in [lo, hi] at which the signed distance is below level, given that it is
    // at hi (bisection; for a turning path, an early such time rather than the earliest).
    double first_below(double lo, double hi, double level) const {
        for (int i = 0; i < 60 && hi - lo > 1e-15; ++i) {
            const double mid = (lo + hi) / 2;
            (signed_distance(mid) < level ? hi : lo) = mid;
        }
        return hi;
    }
    // The smallest signed distance over [lo, hi] and where: golden section for a convex path;
    // for a turning one, the least of 129 samples refined by golden section between its
    // neighbours (a witness, not a proof of the minimum).
    std::pair<double, double> minimum(double lo, double hi) const {
        if (!(hi > lo)) return {signed_distance(lo), lo};
        double a = lo, b = hi;
        std::pair<double, double> best{signed_distance(lo), lo};
        const double at_hi = signed_distance(hi);
        if (at_hi < best.first) best = {at_hi, hi};
        if (!convex) {
            constexpr int kSamples = 128;
            int best_i = 0;
            for (int i = 1; i < kSamples; ++i) {
                const double t = lo + (hi - lo) * i / kSamples;
                const double s = signed_distance(t);
                if (s < best.first) best = {s, t}, best_i = i;
            }
            a = lo + (hi - lo) * std::max(0, best_i - 1) / kSamples;
            b = lo + (hi - lo) * std::min(kSamples, best_i + 1) / kSamples;
        }
        const double g = (std::sqrt(5.0) - 1) / 2;
        double c = b - g * (b - a), d = a + g * (b - a);
        double fc = signed_distance(c), fd = signed_distance(d);
        for (int i = 0; i < 60 && b - a > 1e-13; ++i) {
            if (fc < fd) {
                b = d, d = c, fd = fc;
                c = b - g * (b - a);
                fc = signed_distance(c);
            } else {
                a = c, c = d, fc = fd;
                d = a + g * (b - a);
                fd = signed_distance(d);
            }
        }
        if (fc < best.first) best = {fc, c};
        if (fd < best.first) best = {fd, d};
        return best;
    }
};

}  // namespace

Verdict check_continuous(const fcl::CollisionGeometryd& a, const fcl::Transform3d& begin_a,
                         const fcl::Transform3d& end_a, const fcl::CollisionGeometryd& b,
                         const fcl::Transform3d& begin_b, const fcl::Transform3d& end_b,
                         const fcl::ContinuousCollisionRequestd& request,
                         const fcl::ContinuousCollisionResultd& result, const Tolerance& tolerance) {
    Verdict v;
    v.quantity = "time of contact";
    v.fcl = result.is_collide ? result.time_of_contact : 1.0;
    const Motion ma = map_motion(begin_a, end_a, request.ccd_motion_type);
    const Motion mb = map_motion(begin_b, end_b, request.ccd_motion_type);
    if (!ma.same || !mb.same) {
        v.detail = "not the same motion: " + (!ma.same ? ma.note : mb.note);
        return v;
    }
    const bool naive = request.ccd_solver_type == fcl::CCDC_NAIVE;
    if (!naive && request.ccd_solver_type != fcl::CCDC_CONSERVATIVE_ADVANCEMENT) {
        v.detail = "only CCDC_NAIVE and CCDC_CONSERVATIVE_ADVANCEMENT are judged (FCL's ray shooting and "
                   "polynomial solver do not handle primitives)";
        return v;
    }
    const Shape sa = to_kairos(a), sb = to_kairos(b);
    const double ra = bounding_radius(sa.get()), rb = bounding_radius(sb.get());
    const double size = std::max(ra, rb);
    const Path path{sa.get(), sb.get(), ma.motion, mb.motion, ma.translation_only && mb.translation_only};
    // FCL's narrow phase tolerances (1e-6 by default for both solvers) widen the band.
    const double reach_pos = norm(sub(sub(ma.motion.end.position, ma.motion.start.position),
                                      sub(mb.motion.end.position, mb.motion.start.position)));
    const double reach = reach_pos + turn_angle(ma.motion) * ra + turn_angle(mb.motion) * rb;
    const double magnitude = norm(ma.motion.start.position) + norm(mb.motion.start.position) + reach;
    const double band = tolerance.relative * size + tolerance.absolute + 1e-6 + 1e-14 * (magnitude + size);
    v.tolerance = band;

    // Kairos's time of impact.
    const kairos_query_settings s = reference_settings();
    kairos_cast_result cast;
    if (path.convex) {
        const kairos_vec3 ta = sub(ma.motion.end.position, ma.motion.start.position);
        const kairos_vec3 tb = sub(mb.motion.end.position, mb.motion.start.position);
        require(kairos_shape_cast(sa.get(), &ma.motion.start, ta, sb.get(), &mb.motion.start, tb, &s, &cast),
                "kairos_shape_cast");
    } else {
        require(kairos_motion_cast(sa.get(), &ma.motion, sb.get(), &mb.motion, &s, &cast), "kairos_motion_cast");
    }
    const double toi = cast.hit ? cast.toi : 1.0;
    v.kairos = toi;

    if (naive) {
        const double steps = std::ceil(1 / request.toc_err);
        const size_t n = std::min<size_t>(request.num_max_iterations, steps > 1e9 ? size_t(1e9) : size_t(steps));
        if (n < 2) {
            v.detail = "CCDC_NAIVE with fewer than 2 samples (FCL divides by n - 1 = 0)";
            return v;
        }
        // The expected answer: the first sample where the shapes clearly overlap.
        std::vector<double> sd(n);
        double expected = 1;
        size_t first_clear = n;
        for (size_t i = 0; i < n; ++i) {
            sd[i] = path.signed_distance(double(i) / double(n - 1));
            if (first_clear == n && sd[i] < -band) first_clear = i, expected = double(i) / double(n - 1);
        }
        v.kairos = v.lower = v.upper = expected;
        if (result.is_collide) {
            const size_t k = std::min(n - 1, size_t(std::llround(v.fcl * double(n - 1))));
            if (sd[k] > band) {
                v.outcome = Outcome::FclOff;
                v.error = std::fabs(v.fcl - expected);
                v.detail = fmt("FCL reports contact at sample t = %.17g where the shapes are %.6g apart", v.fcl, sd[k]);
                return v;
            }
            if (first_clear < k) {
                v.outcome = Outcome::FclOff;
                v.error = v.fcl - expected;
                v.detail = fmt("the shapes overlap by %.6g at the earlier sample t = %.17g", -sd[first_clear], expected);
                return v;
            }
        } else if (first_clear < n) {
            v.outcome = Outcome::FclOff;
            v.error = 1 - expected;
            v.detail = fmt("FCL reports no contact but the shapes overlap by %.6g at sample t = %.17g",
                           -sd[first_clear], expected);
            return v;
        }
        v.outcome = Outcome::Agree;
        if (toi < v.fcl - 1e-12 && cast.hit)
            v.detail = fmt("first contact at %.17g, between samples: missed by design", toi);
        return v;
    }

    // Conservative advancement.
    if (result.is_collide) {
        const double t = std::clamp(v.fcl, 0.0, 1.0);
        const double early_band = band + kFclAdvancementStop * reach;
        const double gap = path.gap(t);
        if (gap > early_band) {
            v.outcome = Outcome::FclOff;
            v.error = std::fabs(toi - t);
            // The window's lower end: the last time before Kairos's contact with a gap of early_band.
            if (cast.hit) {
                double lo = 0, hi = toi;
                if (path.gap(0) < early_band) {
                    hi = 0;
                } else {
                    for (int i = 0; i < 60 && hi - lo > 1e-15; ++i) {
                        const double mid = (lo + hi) / 2;
                        (path.gap(mid) >= early_band ? lo : hi) = mid;
                    }
                }
                v.lower = lo;
            }
            v.detail = fmt("FCL reports contact at t = %.17g but the shapes are at least %.6g apart there "
                           "(Kairos: first contact at %.17g%s)",
                           t, gap, toi, cast.hit ? "" : ", none");
            return v;
        }
        if (t > toi) {
            const auto [m, at] = path.minimum(toi, t);
            if (m < -band) {
                v.outcome = Outcome::FclOff;
                v.upper = path.first_below(toi, at, -band);
                v.error = t - v.upper;
                v.detail = fmt("the shapes already overlap by %.6g at t = %.17g, before FCL's contact (from t = %.17g)",
                               -m, at, v.upper);
                return v;
            }
        }
        v.outcome = Outcome::Agree;
        return v;
    }
    const auto [m, at] = path.minimum(cast.hit ? toi : 0.0, 1.0);
    if (m < -band) {
        v.outcome = Outcome::FclOff;
        v.upper = path.first_below(cast.hit ? toi : 0.0, at, -band);
        v.error = 1 - v.upper;
        v.detail = fmt("FCL reports no contact but the shapes overlap by %.6g at t = %.17g (from t = %.17g)", -m, at,
                       v.upper);
        return v;
    }
    v.outcome = m > band ? Outcome::Agree : Outcome::NotJudged;
    if (v.outcome == Outcome::NotJudged) v.detail = fmt("a graze within the band (closest %.3g)", m);
    return v;
}

}  // namespace kairos::fcl_check
