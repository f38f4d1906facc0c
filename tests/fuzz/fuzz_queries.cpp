// SPDX-License-Identifier: MIT
// Fuzz target: pair queries (distance, intersect, ray, shape and motion casts) on two fuzz-built
// shapes at fuzz poses, motions and settings, each result checked against the contract and
// against the shapes' support-function models (separating planes bound every distance).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_support.hpp"

namespace {

using namespace kfuzz;

// A shape at a pose; `null_pose` passes NULL (identity) instead.
struct Posed {
    const Built* shape = nullptr;
    PoseCase pose;
    bool null_pose = false;
    const kairos_pose* pose_arg() const { return null_pose ? nullptr : &pose.pose; }
    const Model& model() const { return *shape->model; }
};

Posed pose_shape(Input& in, const Built& shape) {
    Posed p;
    p.shape = &shape;
    if (in.rare(6))
        p.null_pose = true;
    else
        p.pose = make_transform(in);
    return p;
}

// Size of a pair query: both shapes, how far apart their origins are, how far they move.
real pair_size(const Posed& a, const Posed& b, const Vr& moves = {}) {
    return a.model().magnitude + b.model().magnitude +
           norm(to_real(a.pose.pose.position) - to_real(b.pose.pose.position)) + norm(moves);
}

// Slack of support-plane comparisons on a posed pair: the models' own, 1e-9 of the size (the
// library's rotation matrices and rounding), and ulps of the positions (far from the origin).
real pair_slack(const Posed& a, const Posed& b, real size) {
    return a.model().tolerance + b.model().tolerance + 1e-9L * size +
           32 * ulp(std::fmax(biggest(a.pose.pose.position), biggest(b.pose.pose.position))) + kFloor;
}

// The largest gap between the posed shapes along the 26 directions and `extra` (any length):
// a lower bound of their distance. Writes the direction that gave it.
real max_gap(const Placed& a, const Placed& b, const std::vector<Vr>& extra, Vr* where = nullptr) {
    real best = -INFINITY;
    auto consider = [&](const Vr& u) {
        const real g = gap(a, b, u);
        if (g > best) {
            best = g;
            if (where != nullptr) *where = u;
        }
    };
    for (const Vr& u : unit_directions()) consider(u);
    for (const Vr& d : extra) {
        const real n = norm(d);
        if (n > 0 && std::isfinite(n)) consider((1 / n) * d);
    }
    return best;
}

bool inputs_moderate(const Posed& a, const Posed& b) {
    return a.model().moderate && b.model().moderate && a.pose.moderate && b.pose.moderate;
}

// Widest width (h(d) + h(-d)) of a shape over the test directions, and its "middle" width: the
// narrowest among the directions well away (|cos| < 0.6) from the narrowest one. A flat shape
// has a zero narrowest width but a middle one like its size; a needle has both small.
void widths(const Model& m, real& out_widest, real& out_middle) {
    const std::vector<Vr>& dirs = unit_directions();
    std::vector<real> w;
    size_t narrowest = 0;
    for (size_t i = 0; i < dirs.size(); ++i) {
        w.push_back(support_value(m, dirs[i]) + support_value(m, -1 * dirs[i]));
        if (w[i] < w[narrowest]) narrowest = i;
    }
    out_widest = *std::max_element(w.begin(), w.end());
    out_middle = out_widest;
    const Vr n = dirs[narrowest];
    for (size_t i = 0; i < dirs.size(); ++i)
        if (std::fabs(dot(dirs[i], n)) < 0.6L * norm(dirs[i]) * norm(n)) out_middle = std::fmin(out_middle, w[i]);
}

// Counts the inputs, so that a cache never outlives the shapes of the input that filled it.
uint64_t input_serial = 0;

// Aspect of A - B at the pair's poses (width of A - B = width of A + width of B). Cached for the
// last pair asked: the checks of one input ask about the same pair many times.
real pair_aspect(const Posed& a, const Posed& b) {
    struct Key {
        uint64_t serial;
        const Model *ma, *mb;
        kairos_pose pa, pb;
    };
    static Key last{};
    static real last_aspect = 0;
    const Key k{input_serial, &a.model(), &b.model(), a.pose.pose, b.pose.pose};
    const Key k_swapped{input_serial, &b.model(), &a.model(), b.pose.pose, a.pose.pose};
    if (std::memcmp(&k, &last, sizeof k) == 0 || std::memcmp(&k_swapped, &last, sizeof k) == 0) return last_aspect;
    const Placed pa = place(a.model(), a.pose.pose), pb = place(b.model(), b.pose.pose);
    last_aspect = aspect_of([&](const Vr& d) {
        return support_value(pa, d) + support_value(pa, -1 * d) + support_value(pb, d) + support_value(pb, -1 * d);
    });
    last = k;
    return last_aspect;
}

// Each shape's own aspect counts too (own_aspect, fuzz_support.hpp), cached per model for the
// input: a needle across a disk hides in A - B's aspect. So does each part of a composite (a
// Minkowski sum, a hull of two, a transformed shape): a needle hull summed with a ball is fat by
// itself, while GJK's simplices still take the needle's nearly collinear support points (a
// signed distance 3e-5 too deep beside a unit ball, the needle 1500 long and 2e-6 thick;
// findings/README.md).
bool shape_within(const Model& m, real most) {
    static uint64_t serial = ~uint64_t(0);
    static std::vector<std::pair<const Model*, real>> cache;
    if (serial != input_serial) serial = input_serial, cache.clear();
    real aspect = -1;
    for (const auto& [model, known] : cache)
        if (model == &m) {
            aspect = known;
            break;
        }
    if (aspect < 0) {
        aspect = own_aspect(m);
        cache.emplace_back(&m, aspect);
    }
    if (!(aspect <= most || std::isinf(aspect))) return false;
    return (!m.left || shape_within(*m.left, most)) && (!m.right || shape_within(*m.right, most));
}

// Whether GJK's accuracy is checked on this pair (the closest points, the symmetry, the bounds
// from separating planes and inner balls, intersect against them): the accuracy contract of
// docs/c-api.md ("Where the accuracy holds"). Moderate magnitudes; A - B of aspect at most 1e6
// (a needle hull, a segment 1e7 times longer than the other shape is wide, or a slab 1e19 wide
// beside a unit ball do not pass; flat shapes do); no needle among the shapes themselves by the
// coarse widths below, sizes within 1e6 of each other and origins within 1e6 sizes. Beyond that,
// accuracy at the rounding limit is not claimed (findings/ holds what these targets found there);
// the rest of the contract (statuses, finite numbers, untouched outputs, ranges, unit vectors,
// casts never missing balls inside the shapes) is checked on every input.
bool conditioned(const Posed& a, const Posed& b) {
    if (!inputs_moderate(a, b)) return false;
    real wa, ma, wb, mb;
    widths(a.model(), wa, ma);
    widths(b.model(), wb, mb);
    if (!(wa <= 1e6L * ma) || !(wb <= 1e6L * mb)) return false;
    if (!(wa <= 1e6L * wb) || !(wb <= 1e6L * wa)) return false;
    const real apart = norm(to_real(b.pose.pose.position) - to_real(a.pose.pose.position));
    if (!(apart <= 1e6L * std::fmax(wa, wb))) return false;
    return pair_aspect(a, b) <= 1e6L && shape_within(a.model(), 1e6L) && shape_within(b.model(), 1e6L);
}

// Witness and contact points come from barycentric coordinates on a simplex of A - B, whose error
// grows with the simplex's aspect: they are checked on pairs of aspect at most 1e5 (docs/c-api.md).
constexpr real kPointsAspect = 1e5L;
bool points_conditioned(const Posed& a, const Posed& b) {
    return conditioned(a, b) && pair_aspect(a, b) <= kPointsAspect && shape_within(a.model(), kPointsAspect) &&
           shape_within(b.model(), kPointsAspect);
}

// Distance from the local origin to the farthest corner of the shape's local bounding box (the
// motion cast's rA, rB: kairos.h).
real corner_radius(const Model& m) {
    real sq = 0;
    const Vr axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const Vr& e : axes) {
        const real h = std::fmax(std::fabs(support_value(m, e)), std::fabs(support_value(m, -1 * e)));
        sq += h * h;
    }
    return std::sqrt(sq);
}

// Non-finite numbers in a successful result are a violation, unless the build tolerates them
// on inputs beyond the moderate range.
bool finite_or_report(bool ok, bool moderate_inputs, const char* what) {
    if (ok) return true;
    if (KAIROS_FUZZ_ALLOW_NONFINITE_ON_HUGE && !moderate_inputs) return false;
    violation("%s returned KAIROS_OK with a non-finite number in its result", what);
}

bool unit(const kairos_vec3& v) { return std::fabs(norm(to_real(v)) - 1) < 1e-6L; }

void check_termination(int32_t t, const char* what) {
    if (t < KAIROS_TERMINATION_NONE || t > KAIROS_TERMINATION_HIT) violation("%s: termination %d is unknown", what, t);
}

void expect_pair(const Posed& a, const Posed& b, Verdict& v) {
    expect_pose(a.pose, v);
    expect_pose(b.pose, v);
    if (!a.model().moderate || !b.model().moderate) v.unsure();
}

// "A <shape> at <pose>, B <shape> at <pose>" for reports.
const char* scene(const Posed& a, const Posed& b) {
    static std::string s;
    s = "A " + describe(a.model()) + " at " + show(a.pose.pose) + ", B " + describe(b.model()) + " at " +
        show(b.pose.pose);
    return s.c_str();
}

// ---- Distance ----------------------------------------------------------------------------------

struct DistanceCall {
    int32_t status;
    kairos_distance_result result;
};

// ---- Batches: the same query twice in one batch gives the single call's answer ----------------

// Field by field (the structs have padding, which neither call defines).
bool same_bits(const double& x, const double& y) { return std::memcmp(&x, &y, sizeof x) == 0; }
bool same_bits(const kairos_vec3& x, const kairos_vec3& y) {
    return same_bits(x.x, y.x) && same_bits(x.y, y.y) && same_bits(x.z, y.z);
}
bool same_result(const kairos_distance_result& x, const kairos_distance_result& y) {
    return same_bits(x.distance, y.distance) && same_bits(x.point_a, y.point_a) && same_bits(x.point_b, y.point_b) &&
           same_bits(x.axis, y.axis) && x.intersecting == y.intersecting && x.iterations == y.iterations &&
           x.termination == y.termination;
}
bool same_result(const kairos_cast_result& x, const kairos_cast_result& y) {
    return x.hit == y.hit && same_bits(x.toi, y.toi) && same_bits(x.point, y.point) && same_bits(x.normal, y.normal) &&
           x.iterations == y.iterations && x.termination == y.termination;
}

// A batch of the single query twice: it succeeds exactly when the single call did, then with the
// single call's result in both places; refused, it writes nothing. `call(out)` runs the batch.
template <class Result, class Call>
void check_batch_of_two(const char* function, int32_t single_status, const Result& single, Call&& call) {
    Result out[2];
    poison(out[0]);
    poison(out[1]);
    const int32_t status = observe(function, [&] { return call(out); });
    if ((status == KAIROS_OK) != (single_status == KAIROS_OK))
        violation("%s returned %s where the single call returned %s (%s)", function, kairos_status_name(status),
                  kairos_status_name(single_status), kairos_last_error());
    if (status != KAIROS_OK) {
        if (!poisoned(out[0]) || !poisoned(out[1])) violation("%s failed but wrote out", function);
        return;
    }
    for (const Result& r : out)
        if (!same_result(r, single)) violation("%s: a result differs from the single call's", function);
}

void check_distance_batch(const Posed& a, const Posed& b, const SettingsCase& s, int32_t status,
                          const kairos_distance_result& single) {
    const kairos_shape* sa[2] = {a.shape->shape.get(), a.shape->shape.get()};
    const kairos_shape* sb[2] = {b.shape->shape.get(), b.shape->shape.get()};
    const kairos_pose pa[2] = {a.pose.pose, a.pose.pose}, pb[2] = {b.pose.pose, b.pose.pose};
    check_batch_of_two("kairos_distance_batch", status, single, [&](kairos_distance_result* out) {
        return kairos_distance_batch(sa, a.null_pose ? nullptr : pa, sb, b.null_pose ? nullptr : pb, 2,
                                     s.use ? &s.settings : nullptr, nullptr, out);
    });
}

DistanceCall call_distance(const Posed& a, const Posed& b, const SettingsCase& s) {
    DistanceCall c;
    poison(c.result);
    c.status = observe("kairos_distance", [&] {
        return kairos_distance(a.shape->shape.get(), a.pose_arg(), b.shape->shape.get(), b.pose_arg(),
                               s.use ? &s.settings : nullptr, &c.result);
    });
    Verdict v;
    expect_pair(a, b, v);
    expect_settings(s, v);
    v.check(c.status, "kairos_distance");
    if (c.status != KAIROS_OK && !poisoned(c.result)) violation("kairos_distance failed but wrote *out");
    check_distance_batch(a, b, s, c.status, c.result);
    return c;
}

// Checks a successful distance result; false when it holds tolerated non-finite numbers.
bool check_distance(const Posed& a, const Posed& b, const SettingsCase& s, const kairos_distance_result& r) {
    char what[160];
    if (s.use)
        std::snprintf(what, sizeof what,
                      "kairos_distance(settings: struct_size %u, tolerance %.17g, max_iterations %u)",
                      s.settings.struct_size, s.settings.tolerance, s.settings.max_iterations);
    else
        std::snprintf(what, sizeof what, "kairos_distance(settings NULL)");
    const bool all_finite = std::isfinite(r.distance) && finite(r.point_a) && finite(r.point_b) && finite(r.axis);
    if (!finite_or_report(all_finite, inputs_moderate(a, b), what)) return false;
    check_termination(r.termination, what);
    if (!(r.distance >= 0)) violation("%s: distance %.17g < 0", what, r.distance);
    if (r.intersecting != 0 && r.intersecting != 1) violation("%s: intersecting is %d", what, r.intersecting);
    if (r.intersecting == 1 && r.distance != 0) violation("%s: intersecting with distance %.17g", what, r.distance);
    if (!unit(r.axis)) violation("%s: axis %s is not unit", what, show(r.axis));
    if (!conditioned(a, b)) return true;
    const Placed pa = place(a.model(), a.pose.pose), pb = place(b.model(), b.pose.pose);
    const real size = pair_size(a, b);
    const real slack = pair_slack(a, b, size);
    // A separating plane bounds the distance from below, whatever GJK did.
    const std::vector<Vr> extra = {to_real(r.axis), to_real(b.pose.pose.position) - to_real(a.pose.pose.position)};
    Vr u;
    const real g = max_gap(pa, pb, extra, &u);
    if (!(r.distance >= g - slack))
        violation(
            "%s = %.17g (intersecting %d, termination %d), but the shapes are %.17Lg apart along (%.6Lg %.6Lg "
            "%.6Lg); %s",
            what, r.distance, r.intersecting, r.termination, g, u.x, u.y, u.z, scene(a, b));
    // And the balls about the origins that lie inside the shapes bound it from above (the estimate
    // may exceed the distance by the requested relative tolerance; a guard-stopped one is rough).
    if (r.termination != KAIROS_TERMINATION_MAX_ITERATIONS && inner_radius(a.model()) >= 0 &&
        inner_radius(b.model()) >= 0) {
        const real apart = norm(to_real(b.pose.pose.position) - to_real(a.pose.pose.position)) -
                           inner_radius(a.model()) - inner_radius(b.model());
        const real t = s.use ? real(s.settings.tolerance) : 1e-10L;
        const real upper = std::fmax(real(0), apart) * (1 + 2 * t / (1 - t)) + slack;
        if (!(r.distance <= upper))
            violation("%s = %.17g (intersecting %d, termination %d), but balls inside the shapes are %.17Lg apart; %s",
                      what, r.distance, r.intersecting, r.termination, apart, scene(a, b));
    }
    if (!points_conditioned(a, b)) return true;
    // The closest points lie on their shapes.
    for (const Vr& d : unit_directions()) {
        if (!(dot(d, to_real(r.point_a)) <= support_value(pa, d) + slack))
            violation("%s: point_a %s lies outside A (distance %.17g, termination %d); %s", what, show(r.point_a),
                      r.distance, r.termination, scene(a, b));
        if (!(dot(d, to_real(r.point_b)) <= support_value(pb, d) + slack))
            violation("%s: point_b %s lies outside B (distance %.17g, termination %d); %s", what, show(r.point_b),
                      r.distance, r.termination, scene(a, b));
    }
    // The closest points agree with the distance within 1e-6 of the pair's size, as the two
    // argument orders must (a needle's simplex leaves its barycentric points a few 1e-8 off).
    const real between = norm(to_real(r.point_b) - to_real(r.point_a));
    if (!(std::fabs(between - r.distance) <= slack + 1e-6L * size))
        violation("%s = %.17g but |point_b - point_a| = %.17Lg (termination %d); %s", what, r.distance, between,
                  r.termination, scene(a, b));
    return true;
}

// kairos_signed_distance on the same pair and settings, given kairos_distance's successful result
// d (the same checks pass): apart, the same result bit for bit; overlapping, a negative distance
// whose axis is unit, whose points are distance * axis apart, and which no support plane beats
// (the depth is not too large); converged, the axis gives the depth (B moved by it touches).
// Returns the signed distance (NAN when not judged).
real check_signed_distance(const Posed& a, const Posed& b, const SettingsCase& s, const kairos_distance_result& d) {
    kairos_distance_result r;
    poison(r);
    const int32_t status = observe("kairos_signed_distance", [&] {
        return kairos_signed_distance(a.shape->shape.get(), a.pose_arg(), b.shape->shape.get(), b.pose_arg(),
                                      s.use ? &s.settings : nullptr, &r);
    });
    char what[160];
    std::snprintf(what, sizeof what, "kairos_signed_distance(tolerance %.3g, max_iterations %u)", double(s.tolerance),
                  s.use ? s.settings.max_iterations : 256u);
    if (status != KAIROS_OK) {
        // Only inputs near the magnitude limits may fail (no finite result) where kairos_distance
        // succeeded.
        if (status != KAIROS_ERROR_INVALID_ARGUMENT || inputs_moderate(a, b))
            violation("%s failed (%s: %s) where kairos_distance succeeded; %s", what, kairos_status_name(status),
                      kairos_last_error(), scene(a, b));
        if (!poisoned(r)) violation("%s failed but wrote *out", what);
        return NAN;
    }
    if (d.intersecting == 0) {
        if (std::memcmp(&r, &d, sizeof r) != 0)
            violation("%s: apart, but its result differs from kairos_distance's (%.17g, %.17g); %s", what, r.distance,
                      d.distance, scene(a, b));
        return r.distance;
    }
    const bool all_finite = std::isfinite(r.distance) && finite(r.point_a) && finite(r.point_b) && finite(r.axis);
    if (!finite_or_report(all_finite, inputs_moderate(a, b), what)) return NAN;
    check_termination(r.termination, what);
    if (r.intersecting != 1) violation("%s: kairos_distance says intersecting, but intersecting is %d", what, r.intersecting);
    if (!(r.distance <= 0)) violation("%s: overlapping with distance %.17g > 0; %s", what, r.distance, scene(a, b));
    if (!unit(r.axis)) violation("%s: axis %s is not unit; %s", what, show(r.axis), scene(a, b));
    if (!conditioned(a, b)) return NAN;
    const Placed pa = place(a.model(), a.pose.pose), pb = place(b.model(), b.pose.pose);
    const real size = pair_size(a, b);
    const real t = s.use ? real(s.settings.tolerance) : 1e-10L;
    const real slack = pair_slack(a, b, size) + 1e-9L * size;
    // No plane separates by more than the distance (the depth is not too large).
    Vr u;
    const real g = max_gap(pa, pb, {to_real(r.axis)}, &u);
    if (!(r.distance >= g - slack - t * size))
        violation("%s = %.17g (termination %d), but the shapes are %.17Lg apart along (%.6Lg %.6Lg %.6Lg); %s", what,
                  r.distance, r.termination, g, u.x, u.y, u.z, scene(a, b));
    const bool converged = r.termination == KAIROS_TERMINATION_RELATIVE_ERROR ||
                           r.termination == KAIROS_TERMINATION_REPEATED_SUPPORT ||
                           r.termination == KAIROS_TERMINATION_NEAR_CONTACT;
    // The axis gives the depth: the support planes along it overlap by the depth, within 1e-6 of
    // the size as the witness points (a sphere's centre 1e-9 from a needle core 20 long: the
    // cores' axis, the direction of a 1e-9 vector, is tilted by rounding 1e-7 toward the needle,
    // whose support moves by 1e-6 along it).
    const real along = gap(pa, pb, to_real(r.axis));
    if (converged && !(std::fabs(along - r.distance) <= slack + (t + 1e-6L) * size))
        violation("%s = %.17g (termination %d), but along its axis %s the shapes overlap by %.17Lg; %s", what,
                  r.distance, r.termination, show(r.axis), -along, scene(a, b));
    if (points_conditioned(a, b)) {
        const Vr between = to_real(r.point_b) - to_real(r.point_a) - real(r.distance) * to_real(r.axis);
        if (!(norm(between) <= slack + 1e-6L * size))
            violation("%s = %.17g but point_b - point_a is %.17Lg from distance * axis (termination %d); %s", what,
                      r.distance, norm(between), r.termination, scene(a, b));
    }
    return converged ? real(r.distance) : NAN;
}

void query_distance(Input& in, const Posed& a, const Posed& b) {
    const SettingsCase s = make_settings(in);
    const DistanceCall ab = call_distance(a, b, s);
    if (ab.status != KAIROS_OK || !check_distance(a, b, s, ab.result)) return;
    const DistanceCall ba = call_distance(b, a, s);
    if (ba.status != KAIROS_OK || !check_distance(b, a, s, ba.result)) return;
    {
        // The signed distance, both orders: the same depth within the tolerance.
        const real sab = check_signed_distance(a, b, s, ab.result), sba = check_signed_distance(b, a, s, ba.result);
        const real size = pair_size(a, b);
        if (sab < 0 && sba < 0 && !(std::fabs(sab - sba) <= pair_slack(a, b, size) + (1e-9L + 2 * s.tolerance) * size))
            violation("kairos_signed_distance(a, b) = %.17Lg but (b, a) = %.17Lg; %s", sab, sba, scene(a, b));
    }
    if (ab.result.termination == KAIROS_TERMINATION_MAX_ITERATIONS ||
        ba.result.termination == KAIROS_TERMINATION_MAX_ITERATIONS || !conditioned(a, b))
        return;
    // Symmetric within the requested relative accuracy (the estimate may exceed the true
    // distance by tolerance / (1 - tolerance) of it) and 1e-6 of the size.
    const real t = s.tolerance;
    const real d1 = ab.result.distance, d2 = ba.result.distance;
    const real slack = 1e-6L * pair_size(a, b) + 2 * t / (1 - t) * std::fmax(d1, d2) + pair_slack(a, b, 0);
    if (!(std::fabs(d1 - d2) <= slack))
        violation(
            "kairos_distance(a, b) = %.17Lg but kairos_distance(b, a) = %.17Lg (terminations %d, %d; "
            "tolerance %g): %s",
            d1, d2, ab.result.termination, ba.result.termination, s.tolerance, scene(a, b));
}

// ---- Intersect ---------------------------------------------------------------------------------

void query_intersect(Input& in, const Posed& a, const Posed& b) {
    kairos_vec3 cache{0, 0, 0};
    bool use_cache = true;
    switch (in.pick(4)) {
        case 0:
            break;
        case 1:
            use_cache = false;
            break;
        case 2:
            cache = direction(in);
            break;
        default: {
            const DistanceCall d = call_distance(a, b, SettingsCase{});
            if (d.status == KAIROS_OK) cache = d.result.axis;
            break;
        }
    }
    const kairos_vec3 cache_before = cache;
    int32_t out;
    poison(out);
    const bool null_out = in.rare(32);
    const int32_t status = observe("kairos_intersect", [&] {
        return kairos_intersect(a.shape->shape.get(), a.pose_arg(), b.shape->shape.get(), b.pose_arg(),
                                use_cache ? &cache : nullptr, null_out ? nullptr : &out);
    });
    Verdict v;
    expect_pair(a, b, v);
    if (null_out) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    v.check(status, "kairos_intersect");
    if (status != KAIROS_OK) {
        if (!poisoned(out) || std::memcmp(&cache, &cache_before, sizeof cache) != 0)
            violation("kairos_intersect failed but wrote *out or *axis_cache");
        return;
    }
    if (out != 0 && out != 1) violation("kairos_intersect: *out is %d", out);
    if (out == 0 && use_cache && !finite_or_report(finite(cache), inputs_moderate(a, b), "kairos_intersect")) return;
    if (!conditioned(a, b)) return;
    const Placed pa = place(a.model(), a.pose.pose), pb = place(b.model(), b.pose.pose);
    const real size = pair_size(a, b);
    const real slack = pair_slack(a, b, size);
    if (out == 1) {
        Vr u;
        const real g = max_gap(pa, pb, {to_real(b.pose.pose.position) - to_real(a.pose.pose.position)}, &u);
        if (g > slack)
            violation(
                "kairos_intersect = 1, but the shapes are %.17Lg apart along (%.6Lg %.6Lg %.6Lg) (slack %.3Lg); %s", g,
                u.x, u.y, u.z, slack, scene(a, b));
    } else if (inner_radius(a.model()) >= 0 && inner_radius(b.model()) >= 0 &&
               norm(to_real(b.pose.pose.position) - to_real(a.pose.pose.position)) <
                   inner_radius(a.model()) + inner_radius(b.model()) - slack) {
        violation(
            "kairos_intersect = 0, but balls inside the shapes overlap (origins %.17Lg apart, inner radii %.17Lg "
            "and %.17Lg); %s",
            norm(to_real(b.pose.pose.position) - to_real(a.pose.pose.position)), inner_radius(a.model()),
            inner_radius(b.model()), scene(a, b));
    }
    if (out == 0 && use_cache) {
        if (!finite_or_report(finite(cache), inputs_moderate(a, b), "kairos_intersect")) return;
        const Vr axis = to_real(cache);
        const real n = norm(axis);
        if (!(n > 0)) violation("kairos_intersect = 0 with a zero separating axis");
        const Vr u = (1 / n) * axis;
        const real g = std::fmax(gap(pa, pb, u), gap(pa, pb, -1 * u));
        // The axis is GJK's v, whose rounding (some eps of the size S) tilts it by that over the
        // distance d: along long faces the separation falls short by up to about eps S^2 / d, as
        // check_pair in tests/capi/test_capi_edges.cpp allows (1e-12 S^2 / d). Near contact any
        // axis is rounding (a needle 1.6e6 long 2.8e-6 from a box: 0.25 short).
        const DistanceCall dc = call_distance(a, b, SettingsCase{});
        const real d = dc.status == KAIROS_OK ? real(dc.result.distance) : 0;
        const real tilt = 1e-12L * size * size / std::fmax(d, 1e-300L);
        if (!(g >= -slack - tilt))
            violation(
                "kairos_intersect = 0 with axis %s, which does not separate the shapes (overlap %.17Lg, slack "
                "%.3Lg, distance %.17Lg); %s",
                show(cache), -g, slack, d, scene(a, b));
    }
    // Consistent with the distance: shapes farther apart than 1e-6 of their size do not intersect.
    const DistanceCall d = call_distance(a, b, SettingsCase{});
    if (d.status != KAIROS_OK || !check_distance(a, b, SettingsCase{}, d.result)) return;
    if (d.result.termination == KAIROS_TERMINATION_MAX_ITERATIONS) return;
    if (out == 1 && d.result.distance > 1e-6L * size + slack)
        violation("kairos_intersect = 1 but kairos_distance = %.17g (size %.3Lg); %s", d.result.distance, size,
                  scene(a, b));
}

// ---- Casts -------------------------------------------------------------------------------------

// Fields every successful cast result must have; false when non-finite numbers are tolerated.
// where(): the inputs, for the report (a std::string), built only on a violation.
template <class Where>
bool check_cast_fields(const kairos_cast_result& r, bool moderate_inputs, const char* what, Where&& where) {
    check_termination(r.termination, what);
    if (r.hit != 0 && r.hit != 1) violation("%s: hit is %d", what, r.hit);
    if (!finite_or_report(std::isfinite(r.toi), moderate_inputs, what)) return false;
    if (!(r.toi >= 0 && r.toi <= 1)) violation("%s: toi %.17g outside [0, 1]", what, r.toi);
    if (r.hit == 0) {
        if (r.toi != 1) violation("%s: no hit but toi %.17g (must be 1)", what, r.toi);
        return true;
    }
    if (!finite_or_report(finite(r.point) && finite(r.normal), moderate_inputs, what)) return false;
    if (!unit(r.normal)) violation("%s: hit with normal %s, not unit; %s", what, show(r.normal), where().c_str());
    return true;
}

// Never a missed contact: balls inside the shapes about their origins, which move linearly over
// the step whatever the turn, first meet at `enter` (negative: never); the cast must hit by then,
// up to its tolerance (a fraction of the step).
void check_not_missed(const char* what, const kairos_cast_result& r, real enter, real tolerance,
                      const std::string& where) {
    if (enter < 0) return;
    if (r.hit != 1)
        violation("%s: no hit, but balls inside the shapes meet at t = %.17Lg; %s", what, enter, where.c_str());
    if (!(r.toi <= enter + tolerance + 1e-9L))
        violation("%s: hit at toi %.17g, but balls inside the shapes meet at t = %.17Lg already; %s", what, r.toi,
                  enter, where.c_str());
}

kairos_vec3 translation(Input& in, const kairos_vec3& aim) {
    switch (in.pick(5)) {
        case 0:
            return {0, 0, 0};
        case 1:
            return small_vec(in, 8);
        case 2: {
            // Toward `aim`, stopping short, reaching it, or going past.
            static const double reach[6] = {1.0, 0.5, 2.0, 0.999999, 1.000001, 10.0};
            const double k = reach[in.pick(6)];
            return {aim.x * k, aim.y * k, aim.z * k};
        }
        case 3:
            return small_vec(in, power_of_ten(in));
        default:
            return direction(in);
    }
}

kairos_vec3 minus(const kairos_vec3& a, const kairos_vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

void query_ray(Input& in, const Posed& s) {
    const kairos_vec3 origin = in.pick(2) == 0 ? position(in) : [&] {
        const kairos_vec3 d = small_vec(in, 4 * static_cast<double>(s.model().magnitude) + 1);
        const kairos_vec3& p = s.pose.pose.position;
        return kairos_vec3{p.x + d.x, p.y + d.y, p.z + d.z};
    }();
    const kairos_vec3 t = translation(in, minus(s.pose.pose.position, origin));
    const SettingsCase settings = make_settings(in);
    kairos_cast_result r;
    poison(r);
    const int32_t status = observe("kairos_ray_cast", [&] {
        return kairos_ray_cast(s.shape->shape.get(), s.pose_arg(), origin, t,
                               settings.use ? &settings.settings : nullptr, &r);
    });
    Verdict v;
    expect_pose(s.pose, v);
    expect_settings(settings, v);
    if (!finite(origin) || !finite(t))
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    else if (!moderate(origin) || !moderate(t) || !s.model().moderate)
        v.unsure();
    v.check(status, "kairos_ray_cast");
    if (status != KAIROS_OK) {
        if (!poisoned(r)) violation("kairos_ray_cast failed but wrote *out");
        return;
    }
    const bool moderate_inputs = s.model().moderate && s.pose.moderate && moderate(origin) && moderate(t);
    if (!check_cast_fields(r, moderate_inputs, "kairos_ray_cast", [&] {
            return std::string("origin ") + show(origin) + ", translation " + show(t) + ", " + describe(s.model()) +
                   " at " + show(s.pose.pose);
        }))
        return;
    {
        const real reach = inner_radius(s.model()) < 0
                               ? -1
                               : inner_radius(s.model()) * (1 - 1e-9L) -
                                     32 * ulp(std::fmax(biggest(origin) + biggest(t), biggest(s.pose.pose.position)));
        const std::string where = std::string("origin ") + show(origin) + ", translation " + show(t) + ", " +
                                  describe(s.model()) + " at " + show(s.pose.pose);
        check_not_missed("kairos_ray_cast", r,
                         first_within(to_real(origin) - to_real(s.pose.pose.position), to_real(t), reach),
                         settings.tolerance, where);
    }
    if (r.hit == 0) return;
    const Placed placed = place(s.model(), s.pose.pose);
    const Vr o = to_real(origin), tr = to_real(t);
    const Vr at = o + real(r.toi) * tr;
    const real size = s.model().magnitude + norm(o - to_real(s.pose.pose.position)) + norm(tr);
    const real slack = (2 * real(settings.tolerance) + 1e-6L) * size + s.model().tolerance +
                       32 * ulp(std::fmax(biggest(origin), biggest(s.pose.pose.position))) + kFloor;
    // A ray starting inside reports a point of the surface, not its origin: only later hits are
    // where the ray is. A hit ended by the iteration guard is a proven lower bound of the time
    // only (the header): its point is not checked, the never-late plane still is.
    // Its point is checked only within the accuracy contract (the shape's aspect at most 1e5).
    const bool guard = r.termination == KAIROS_TERMINATION_MAX_ITERATIONS ||
                       !(s.pose.moderate && s.model().moderate) ||
                       !(aspect_of([&](const Vr& d) { return support_value(placed, d) + support_value(placed, -1 * d); }) <=
                         kPointsAspect);
    if (r.toi > 0 && !guard && !(norm(to_real(r.point) - at) <= slack))
        violation(
            "kairos_ray_cast: hit point %s is %.17Lg from the ray point at toi %.17g (slack %.3Lg); origin %s, "
            "translation %s, %s at %s",
            show(r.point), norm(to_real(r.point) - at), r.toi, slack, show(origin), show(t),
            describe(s.model()).c_str(), show(s.pose.pose));
    if (r.toi > 0) {
        for (const Vr& d : unit_directions())
            if (!guard && !(dot(d, to_real(r.point)) <= support_value(placed, d) + slack))
                violation(
                    "kairos_ray_cast: hit point %s at toi %.17g lies outside the shape; origin %s, translation %s, "
                    "%s at %s",
                    show(r.point), r.toi, show(origin), show(t), describe(s.model()).c_str(), show(s.pose.pose));
        // Never late: at toi the ray point has not crossed the plane of the reported normal.
        const Vr n = to_real(r.normal);
        const real h = support_value(placed, n);
        if (!(dot(n, at) >= h - slack))
            violation(
                "kairos_ray_cast: at toi %.17g the ray point is %.17Lg past the support plane of normal %s; "
                "origin %s, translation %s, %s at %s",
                r.toi, h - dot(n, at), show(r.normal), show(origin), show(t), describe(s.model()).c_str(),
                show(s.pose.pose));
    }
}

void query_shape_cast(Input& in, const Posed& a, const Posed& b) {
    const kairos_vec3 ta =
        in.pick(2) == 0 ? kairos_vec3{0, 0, 0} : translation(in, minus(b.pose.pose.position, a.pose.pose.position));
    const kairos_vec3 tb = translation(in, minus(a.pose.pose.position, b.pose.pose.position));
    const SettingsCase settings = make_settings(in);
    kairos_cast_result r;
    poison(r);
    const int32_t status = observe("kairos_shape_cast", [&] {
        return kairos_shape_cast(a.shape->shape.get(), a.pose_arg(), ta, b.shape->shape.get(), b.pose_arg(), tb,
                                 settings.use ? &settings.settings : nullptr, &r);
    });
    {
        const kairos_shape* sa[2] = {a.shape->shape.get(), a.shape->shape.get()};
        const kairos_shape* sb[2] = {b.shape->shape.get(), b.shape->shape.get()};
        const kairos_pose pa[2] = {a.pose.pose, a.pose.pose}, pb[2] = {b.pose.pose, b.pose.pose};
        const kairos_vec3 tra[2] = {ta, ta}, trb[2] = {tb, tb};
        check_batch_of_two("kairos_shape_cast_batch", status, r, [&](kairos_cast_result* out) {
            return kairos_shape_cast_batch(sa, a.null_pose ? nullptr : pa, tra, sb, b.null_pose ? nullptr : pb, trb, 2,
                                           settings.use ? &settings.settings : nullptr, nullptr, out);
        });
    }
    Verdict v;
    expect_pair(a, b, v);
    expect_settings(settings, v);
    if (!finite(ta) || !finite(tb))
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    else if (!moderate(ta) || !moderate(tb))
        v.unsure();
    v.check(status, "kairos_shape_cast");
    if (status != KAIROS_OK) {
        if (!poisoned(r)) violation("kairos_shape_cast failed but wrote *out");
        return;
    }
    const bool moderate_inputs = inputs_moderate(a, b) && moderate(ta) && moderate(tb);
    if (!check_cast_fields(r, moderate_inputs, "kairos_shape_cast", [&] {
            return std::string("A moves ") + show(ta) + ", B moves " + show(tb) + "; " + scene(a, b);
        }))
        return;
    const Vr rel = to_real(tb) - to_real(ta);
    const real size = pair_size(a, b, to_real(ta)) + norm(to_real(tb));
    const real slack = (2 * real(settings.tolerance) + 1e-6L) * size + pair_slack(a, b, size);
    {
        const real ra = inner_radius(a.model()), rb = inner_radius(b.model());
        const real reach =
            ra < 0 || rb < 0 ? -1 : (ra + rb) * (1 - 1e-9L) - pair_slack(a, b, 0) - 32 * ulp(biggest(ta) + biggest(tb));
        const Vr p0 = to_real(b.pose.pose.position) - to_real(a.pose.pose.position);
        check_not_missed("kairos_shape_cast", r, first_within(p0, rel, reach), settings.tolerance,
                         std::string("A moves ") + show(ta) + ", B moves " + show(tb) + "; " + scene(a, b));
    }
    const Placed pa0 = place(a.model(), a.pose.pose), pb0 = place(b.model(), b.pose.pose);
    if (r.hit == 0 || r.toi == 0) {
        // A hit at toi 0 means touching at the start: no plane may separate them by more (unless
        // the iteration guard ended the cast there: a lower bound only).
        if (r.hit == 1 && r.termination != KAIROS_TERMINATION_MAX_ITERATIONS) {
            Vr u;
            const real g = max_gap(pa0, pb0, {to_real(b.pose.pose.position) - to_real(a.pose.pose.position)}, &u);
            if (g > slack)
                violation(
                    "kairos_shape_cast: hit at toi 0 but at the start the shapes are %.17Lg apart along "
                    "(%.6Lg %.6Lg %.6Lg) (slack %.3Lg); A moves %s, B moves %s; %s",
                    g, u.x, u.y, u.z, slack, show(ta), show(tb), scene(a, b));
        }
        return;
    }
    // A contact opposes the relative motion.
    if (norm(rel) > 0 && !(dot(to_real(r.normal), rel) <= 1e-6L * norm(rel)))
        violation(
            "kairos_shape_cast: normal %s does not oppose the relative motion %s (toi %.17g, termination %d, "
            "tolerance %.17g, max_iterations %u); A moves %s; %s",
            show(r.normal), show(minus(tb, ta)), r.toi, r.termination,
            settings.use ? settings.settings.tolerance : 1e-10, settings.use ? settings.settings.max_iterations : 256u,
            show(ta), scene(a, b));
    // At toi: the point lies on both shapes, and the normal's plane still separates them (never late).
    Placed pa = pa0, pb = pb0;
    pa.position = pa0.position + real(r.toi) * to_real(ta);
    pb.position = pb0.position + real(r.toi) * to_real(tb);
    const Vr n = to_real(r.normal);
    const real overlap = -gap(pa, pb, n);
    if (!(overlap <= slack))
        violation(
            "kairos_shape_cast: at toi %.17g the shapes overlap by %.17Lg along the normal %s (slack %.3Lg); "
            "A moves %s, B moves %s; %s",
            r.toi, overlap, show(r.normal), slack, show(ta), show(tb), scene(a, b));
    // A guard-ended hit is a lower bound of the time only (see the ray cast): its point is not checked.
    for (const Vr& d : unit_directions()) {
        if (r.termination == KAIROS_TERMINATION_MAX_ITERATIONS || !points_conditioned(a, b)) break;
        const real x = dot(d, to_real(r.point));
        if (!(x <= support_value(pa, d) + slack) || !(x <= support_value(pb, d) + slack))
            violation(
                "kairos_shape_cast: contact point %s at toi %.17g lies outside A or B; A moves %s, B moves %s; %s",
                show(r.point), r.toi, show(ta), show(tb), scene(a, b));
    }
}

// ---- Motion cast -------------------------------------------------------------------------------

void query_motion_cast(Input& in, const Posed& a, const Posed& b) {
    kairos_motion ma{a.pose.pose, a.pose.pose}, mb{b.pose.pose, b.pose.pose};
    const PoseCase a1 = make_pose_near(in, a.pose.pose), b1 = make_pose_near(in, b.pose.pose);
    ma.end = a1.pose;
    mb.end = b1.pose;
    if (in.pick(3) == 1) {
        // B heads for where A is.
        mb.end.position = {a.pose.pose.position.x + 0.1 * in.symmetric(), a.pose.pose.position.y,
                           a.pose.pose.position.z};
    }
    const PoseCase b_end = classify(mb.end);
    const SettingsCase settings = make_settings(in);
    kairos_cast_result r;
    poison(r);
    const bool null_motion = in.rare(32);
    const int32_t status = observe("kairos_motion_cast", [&] {
        return kairos_motion_cast(a.shape->shape.get(), &ma, b.shape->shape.get(), null_motion ? nullptr : &mb,
                                  settings.use ? &settings.settings : nullptr, &r);
    });
    if (!null_motion) {
        const kairos_shape* sa[2] = {a.shape->shape.get(), a.shape->shape.get()};
        const kairos_shape* sb[2] = {b.shape->shape.get(), b.shape->shape.get()};
        const kairos_motion mas[2] = {ma, ma}, mbs[2] = {mb, mb};
        check_batch_of_two("kairos_motion_cast_batch", status, r, [&](kairos_cast_result* out) {
            return kairos_motion_cast_batch(sa, mas, sb, mbs, 2, settings.use ? &settings.settings : nullptr, nullptr,
                                            out);
        });
    }
    Verdict v;
    expect_pair(a, b, v);
    expect_pose(a1, v);
    expect_pose(b_end, v);
    expect_settings(settings, v);
    if (null_motion) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    v.check(status, "kairos_motion_cast");
    if (status != KAIROS_OK) {
        if (!poisoned(r)) violation("kairos_motion_cast failed but wrote *out");
        return;
    }
    const bool moderate_inputs = inputs_moderate(a, b) && a1.moderate && b_end.moderate;
    if (!check_cast_fields(r, moderate_inputs, "kairos_motion_cast", [&] {
            return "A " + describe(a.model()) + " " + show(ma.start) + " -> " + show(ma.end) + ", B " +
                   describe(b.model()) + " " + show(mb.start) + " -> " + show(mb.end);
        }))
        return;
    {
        const Vr p0 = to_real(mb.start.position) - to_real(ma.start.position);
        const Vr dv = (to_real(mb.end.position) - to_real(mb.start.position)) -
                      (to_real(ma.end.position) - to_real(ma.start.position));
        const real ra = inner_radius(a.model()), rb = inner_radius(b.model());
        const real reach = ra < 0 || rb < 0 ? -1
                                            : (ra + rb) * (1 - 1e-9L) - pair_slack(a, b, 0) -
                                                  32 * ulp(biggest(ma.end.position) + biggest(mb.end.position));
        const std::string where = "A " + describe(a.model()) + " " + show(ma.start) + " -> " + show(ma.end) + ", B " +
                                  describe(b.model()) + " " + show(mb.start) + " -> " + show(mb.end);
        check_not_missed("kairos_motion_cast", r, first_within(p0, dv, reach), settings.tolerance, where);
    }
    if (r.hit == 0) return;
    const Vr moves = (to_real(ma.end.position) - to_real(ma.start.position)) -
                     (to_real(mb.end.position) - to_real(mb.start.position));
    const real size = pair_size(a, b, moves) + norm(to_real(ma.end.position) - to_real(ma.start.position));
    const real t = settings.tolerance;
    // A hit is a time at which the shapes are within tolerance * min(rA, rB) of each other, rA and
    // rB the corners of the local bounding boxes (the larger when one is 0), as the header says.
    const real ca = corner_radius(a.model()), cb = corner_radius(b.model());
    const real radius = ca > 0 && cb > 0 ? std::fmin(ca, cb) : std::fmax(ca, cb);
    const real near = t * radius + 1e-6L * size + pair_slack(a, b, size);
    // A guard stopped the search (MAX_ITERATIONS, NO_PROGRESS): a hit before which there is no
    // contact, but the shapes may be apart there (the header), at toi 0 too (max_iterations 1
    // ends before the first advance; found by fuzzing).
    if (r.termination != KAIROS_TERMINATION_HIT) return;
    kairos_quat qa, qb;
    Vr pa_at, pb_at;
    motion_at(ma, r.toi, qa, pa_at);
    motion_at(mb, r.toi, qb, pb_at);
    const Placed pa = place(a.model(), qa, pa_at), pb = place(b.model(), qb, pb_at);
    Vr u;
    const real g = max_gap(pa, pb, {pb_at - pa_at, to_real(r.normal)}, &u);
    if (g > near)
        violation(
            "kairos_motion_cast: hit at toi %.17g (termination %d) but the shapes are %.17Lg apart there along "
            "(%.6Lg %.6Lg %.6Lg) (allowed %.3Lg); A %s %s -> %s, B %s %s -> %s, tolerance %g",
            r.toi, r.termination, g, u.x, u.y, u.z, near, describe(a.model()).c_str(), show(ma.start), show(ma.end),
            describe(b.model()).c_str(), show(mb.start), show(mb.end), settings.tolerance);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    ++input_serial;
    Input in(data, size);
    ShapeBuilder builder(in, /*max_depth=*/1, /*thorough=*/false);
    const Built a = builder.build_or_sphere();
    const Built b = builder.build_or_sphere();
    for (int i = 0; i < 6 && (i == 0 || in.remaining() > 0); ++i) {
        const Posed pa = pose_shape(in, a), pb = pose_shape(in, b);
        switch (in.pick(5)) {
            case 0:
                query_distance(in, pa, pb);
                break;
            case 1:
                query_intersect(in, pa, pb);
                break;
            case 2:
                query_ray(in, in.pick(2) == 0 ? pa : pb);
                break;
            case 3:
                query_shape_cast(in, pa, pb);
                break;
            default:
                query_motion_cast(in, pa, pb);
                break;
        }
    }
    return 0;
}
