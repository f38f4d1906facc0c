// GJK distance and intersection loops, instantiated per pair of support kinds (no virtual call and
// no allocation per iteration). All work happens in A's local frame; results go back to the world.
#include "gjk.hpp"
#include "support_kernels.hpp"

#include <cmath>

namespace kairos {
namespace {

using gjk_detail::Simplex;
using namespace kernels;

// ---- The distance loop -------------------------------------------------------------------------

struct LocalDistance {
    double core_norm_sq;  // ||v||^2 of the final estimate (cores)
    Vec3 v, point_a, point_b;
    bool intersecting;
    uint32_t iterations;
    Termination termination;
};

// True when sqrt(nv) < sqrt(lower_sq) - E, with E = 16 eps ||w|| the rounding allowance of the bound
// (v.w carries an absolute error of a few eps ||v|| ||w||). Squares only: lower_sq - nv =
// (L - |v|)(L + |v|) and L + |v| <= 2L, so (lower_sq - nv)^2 > 4 lower_sq E^2 implies L - |v| > E.
inline bool below_lower_bound(double nv, double lower_sq, double w_norm_sq) {
    constexpr double k = 16 * 2.220446049250313e-16;
    const double d = lower_sq - nv;
    return d > 0 && d * d > 4 * lower_sq * (k * k * w_norm_sq);
}

// margin: sum of the radii folded out of the shapes (0 for polytopes). The distance of the
// rounded shapes is ||v|| - margin.
template <class Pair>
LocalDistance distance_loop(const Pair& pair, double margin, double tolerance, uint32_t max_iterations) {
    Simplex s;
    s.want_lambda = false;  // coordinates once, at the end
    // First direction: B lies roughly along t from A, so the closest points are near A's support
    // toward t and B's support toward -t; v is a guess at a point of A - B (about -t).
    Vec3 v = -pair.t;
    if (!(dot(v, v) > 0)) v = {1, 0, 0};
    double vv = 0;  // ||v||^2 of the simplex's point, once there is one
    const double margin_sq = margin * margin;
    // Squared lower bound on the cores' distance: max over iterations of (v.w)^2 / ||v||^2 with
    // v.w > 0 (every point x of A - B has v.x >= v.w). No point of A - B is closer to the origin,
    // so an estimate below it is a rounding artefact (see below).
    // Kept as a fraction lower_num / lower_den (no division in the loop), with the w that gave it
    // (its norm scales the rounding of v.w).
    double lower_num = 0, lower_den = 1;
    Vec3 lower_w{};

    LocalDistance out{};
    out.termination = Termination::MaxIterations;
    uint32_t it = 0;
    while (it < max_iterations) {
        Vec3 a, b;
        const Vec3 w = pair(-v, a, b);
        ++it;
        if (s.bits != 0) {
            const double vw = dot(v, w);
            if (vw > 0 && vw * vw * lower_den > lower_num * vv) {
                lower_num = vw * vw;
                lower_den = vv;
                lower_w = w;
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
                out.termination = Termination::RepeatedSupport;
                break;
            }
        }
        const unsigned prev_bits = s.bits;
        const Simplex::Outcome o = s.add(w, a, b, s.bits != 0 ? vv : INFINITY);
        if (o == Simplex::Outcome::Full) {
            out.termination = Termination::FullSimplex;
            vv = 0;
            break;
        }
        if (o == Simplex::Outcome::Failed) {
            out.termination = Termination::JohnsonFailed;  // s keeps the previous estimate
            break;
        }
        const double nv = dot(s.v, s.v);
        // An estimate below the lower bound by more than the rounding of v.w cannot be a point of
        // A - B: Johnson's determinants accepted a sub-simplex they could not resolve (a sliver
        // triangle of support points a few ulps apart on a curved surface, whose plane passes
        // nearer the origin than any of its points). Trusting it would end the query on rules 2
        // or "cores within the radii" with shapes still apart. The previous estimate is kept.
        if (nv * lower_den < lower_num && below_lower_bound(nv, lower_num / lower_den, dot(lower_w, lower_w))) {
            s.restore(prev_bits);
            out.termination = Termination::JohnsonFailed;
            break;
        }
        // Rule 2: v is within rounding of the origin relative to the simplex's size.
        if (nv <= gjk_detail::kNearContact * s.max_norm_sq()) {
            out.termination = Termination::NearContact;
            vv = nv;
            break;
        }
        // Rounded shapes: the cores are within the sum of the radii, so the shapes overlap.
        if (nv <= margin_sq) {
            out.termination = Termination::FullSimplex;
            vv = nv;
            break;
        }
        // Rule 6: no progress. The new estimate is kept only if it is not worse.
        if (it > 1 && vv - nv <= gjk_detail::kNoProgress * vv) {
            out.termination = Termination::NoProgress;
            if (nv <= vv) vv = nv;
            // A worse estimate was produced by rounding: s.v is still the point found, and it is
            // within machine epsilon of the previous one.
            break;
        }
        vv = nv;
        v = s.v;
    }
    out.iterations = it;
    out.v = s.v;
    out.core_norm_sq = dot(s.v, s.v);
    s.update_lambda();
    s.closest_points(out.point_a, out.point_b);
    switch (out.termination) {
        case Termination::FullSimplex:
        case Termination::NearContact:
            out.intersecting = true;
            break;
        default:
            out.intersecting = out.core_norm_sq <= margin_sq;
            break;
    }
    return out;
}

// ---- The intersection loop ---------------------------------------------------------------------

template <class Pair>
bool intersect_loop(const Pair& pair, double margin, Vec3& io_v, uint32_t max_iterations, uint32_t& out_iterations) {
    Simplex s;
    s.want_lambda = false;
    Vec3 v = io_v;
    double vv = 0;
    const double margin_sq = margin * margin;
    uint32_t it = 0;
    bool result = true;
    while (it < max_iterations) {
        Vec3 a, b;
        const Vec3 w = pair(-v, a, b);
        ++it;
        const double vw = dot(v, w);
        // Separating axis: every point of A - B lies beyond the plane v.x = vw > margin * ||v||.
        if (vw > 0 && vw * vw > margin_sq * dot(v, v)) {
            io_v = v;
            result = false;
            break;
        }
        // w seen before, with vw <= 0: the closest point is within rounding of the origin.
        if (s.bits != 0 && s.contains(w)) break;
        const Simplex::Outcome o = s.add(w, a, b, s.bits != 0 ? vv : INFINITY);
        if (o == Simplex::Outcome::Full || o == Simplex::Outcome::Failed) break;
        const double nv = dot(s.v, s.v);
        if (nv <= gjk_detail::kNearContact * s.max_norm_sq() || nv <= margin_sq) break;
        if (s.bits != 0 && it > 1 && vv - nv <= gjk_detail::kNoProgress * vv) break;
        vv = nv;
        v = s.v;
    }
    out_iterations = it;
    return result;
}

// Calls fn(pair_support, margin) with the pair's support of A - B in A's frame.
template <class Fn>
auto with_pair(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, Fn&& fn) {
    const CoreOf ca = classify(a), cb = classify(b);
    const RelativeFrame frame = relative_frame(pose_a, pose_b);
    const Mat3& r = frame.r;
    const Vec3 t = frame.t;
    const double margin = ca.radius + cb.radius;
    return with_support(a, ca.core, [&](auto sa) {
        return with_support(b, cb.core, [&](auto sb) {
            return fn(PairSupport<decltype(sa), decltype(sb)>{sa, sb, r, t}, margin);
        });
    });
}

Vec3 world_direction(const Pose& pose, Vec3 local) { return pose.rotation * local; }

// a / |a| given |a|^2 (one square root, one division); when a is zero or its square under- or
// overflows, the careful normalisation of a, then of `fallback`, then +x.
inline Vec3 unit_or(Vec3 a, double norm_sq, Vec3 fallback) {
    if (norm_sq > 1e-200 && norm_sq < 1e200) return (1 / std::sqrt(norm_sq)) * a;
    return normalized_or(a, normalized_or(fallback, {1, 0, 0}));
}

}  // namespace

DistanceResult gjk_distance(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, double tolerance,
                            uint32_t max_iterations) {
    if (max_iterations == 0) max_iterations = 1;
    const double radius_a = classify(a).radius, radius_b = classify(b).radius;
    Vec3 center_offset;
    const LocalDistance l = with_pair(a, pose_a, b, pose_b, [&](const auto& pair, double margin) {
        center_offset = pair.t;
        return distance_loop(pair, margin, tolerance, max_iterations);
    });

    DistanceResult r;
    r.iterations = l.iterations;
    r.termination = l.termination;
    // Axis from A toward B: -v (v = a - b). Without a usable v (intersecting at the origin), the
    // direction between the local origins, or +x.
    const double core = std::sqrt(l.core_norm_sq);
    const Vec3 n = unit_or(-l.v, l.core_norm_sq, center_offset);
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
    r.axis = world_direction(pose_a, n);
    return r;
}

bool gjk_intersect(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b, Vec3& io_axis,
                   uint32_t* out_iterations) {
    uint32_t it = 0;
    Vec3 v_local = -pose_a.to_local_direction(io_axis);
    const bool usable = is_finite(v_local) && dot(v_local, v_local) > 0 && std::isfinite(dot(v_local, v_local));
    bool hit = with_pair(a, pose_a, b, pose_b, [&](const auto& pair, double margin) {
        if (!usable) {
            v_local = -pair.t;
            if (!(dot(v_local, v_local) > 0)) v_local = {1, 0, 0};
        }
        return intersect_loop(pair, margin, v_local, 256, it);
    });
    if (!hit) io_axis = world_direction(pose_a, unit_or(-v_local, dot(v_local, v_local), {1, 0, 0}));
    if (out_iterations) *out_iterations = it;
    return hit;
}

}  // namespace kairos
