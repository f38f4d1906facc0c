// SPDX-License-Identifier: MIT
// Shared by the motion cast tests, the peer checks and the benchmark: random rotating pairs with
// their reference, and the judgement of a motion cast result against it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "cast_test_support.hpp"
#include "motion/motion.hpp"
#include "motion/motion_cast.hpp"
#include "oracle/motion_reference.hpp"
#include "shapes/shape.hpp"

namespace motion_test {

using cast_test::Kind;
using cast_test::Solid;
using kairos::Pose;
using kairos::Quat;
using kairos::Vec3;

// Rotation by `angle` about unit `axis` applied after q (world frame), written out here.
inline Quat turn(Quat q, Vec3 axis, double angle) {
    const double s = std::sin(0.5 * angle), c = std::cos(0.5 * angle);
    const Quat r{axis.x * s, axis.y * s, axis.z * s, c};
    return kairos::normalized(r * q);
}

struct MotionCase {
    Pose a0, a1, b0, b1;
};

// Options of a random motion case.
struct CaseShape {
    double max_angle = 1.5 * std::numbers::pi;  // per body, uniform in [0, max_angle] (beyond pi too)
    bool translate = true;                      // B (and a little A) translate
    bool both_rotate = true;                    // else only A rotates
    double gap_lo = 0.6, gap_hi = 1.6;          // B's start distance from A, in sums of radii
};

// A random case: A near the origin, B some radii away; each body turns about a random axis by a
// random angle (the end quaternion is negated half of the time: the same orientation); B's
// translation (when asked for) is aimed at A with a jitter.
inline MotionCase random_case(std::mt19937_64& rng, const Solid& a, const Solid& b, const CaseShape& cs) {
    std::uniform_real_distribution<double> u01(0, 1), gap(cs.gap_lo, cs.gap_hi), angle(0, cs.max_angle),
        small(-0.3, 0.3), reach(0.3, 1.6), jitter(0, 1.2);
    MotionCase c;
    const double sum = std::fmax(a.radius + b.radius, 0.5);  // two points: still apart
    c.a0.position = small(rng) * sum * cast_test::random_unit(rng);
    c.a0.orientation = cast_test::random_quat(rng);
    c.b0.position = c.a0.position + gap(rng) * sum * cast_test::random_unit(rng);
    c.b0.orientation = cast_test::random_quat(rng);
    c.a1 = c.a0;
    c.b1 = c.b0;
    c.a1.orientation = turn(c.a0.orientation, cast_test::random_unit(rng), angle(rng));
    if (cs.both_rotate && u01(rng) < 0.7)
        c.b1.orientation = turn(c.b0.orientation, cast_test::random_unit(rng), angle(rng));
    auto maybe_negate = [&](Quat& q) {
        if (u01(rng) < 0.5) q = {-q.x, -q.y, -q.z, -q.w};
    };
    maybe_negate(c.a1.orientation);
    maybe_negate(c.b1.orientation);
    if (cs.translate) {
        const Vec3 aim = (c.a0.position - c.b0.position) * reach(rng) + jitter(rng) * sum * cast_test::random_unit(rng);
        const Vec3 ta = small(rng) * sum * cast_test::random_unit(rng);
        c.a1.position = c.a0.position + ta;
        c.b1.position = c.b0.position + ta + aim;
    }
    return c;
}

inline motion_ref::Pair reference_pair(const Solid& a, const Solid& b, const MotionCase& c) {
    return motion_ref::Pair(*a.shape, a.body, c.a0, c.a1, *b.shape, b.body, c.b0, c.b1);
}

// The library's contact distance: tolerance times the smaller bounding radius (motion_cast.hpp).
inline double contact_distance(const kairos::Shape& a, const kairos::Shape& b, double tolerance) {
    auto radius = [](const kairos::Shape& s) {
        Vec3 lo, hi;
        kairos::bounds(s, kairos::Transform{}, lo, hi);
        return kairos::length(Vec3{std::fmax(std::fabs(lo.x), std::fabs(hi.x)),
                                   std::fmax(std::fabs(lo.y), std::fabs(hi.y)),
                                   std::fmax(std::fabs(lo.z), std::fabs(hi.z))});
    };
    const double ra = radius(a), rb = radius(b);
    return tolerance * (ra > 0 && rb > 0 ? std::fmin(ra, rb) : std::fmax(ra, rb));
}

// The verdict on one motion cast.
struct Verdict {
    bool undecided = false;  // the reference ran out of steps
    bool ref_hit = false;
    bool miss = false;      // the reference proves a contact, the cast reports none
    bool late = false;      // toi later than the reference time by more than the tolerance
    bool far = false;       // a hit (termination Hit) where the shapes are farther apart than allowed
    double early = 0;       // reference time - toi, both hitting (>= 0 when conservative)
    double gap_at_toi = 0;  // true distance at toi / size
};

// allowance: how far apart the shapes may be at a reported hit, beyond the contact distance
// (relative to the size): rounding, and GJK's stall on curved surfaces.
inline Verdict judge(const motion_ref::Pair& p, const motion_ref::Pair::Contact& ref, const kairos::CastResult& r,
                     double tolerance, double delta, double allowance) {
    Verdict v;
    v.undecided = !ref.decided;
    if (v.undecided) return v;
    v.ref_hit = ref.hit;
    if (ref.hit && !r.hit) v.miss = true;
    if (ref.hit && r.hit) {
        v.early = static_cast<double>(ref.toi - motion_ref::Real(r.toi));
        if (motion_ref::Real(r.toi) > ref.toi + tolerance) v.late = true;
    }
    if (r.hit) {
        const motion_ref::Real d = p.distance(r.toi);
        v.gap_at_toi = static_cast<double>(d / std::max(p.size, motion_ref::Real(1e-300)));
        if (r.termination == kairos::Termination::Hit && d > delta + allowance * p.size) v.far = true;
    }
    return v;
}

}  // namespace motion_test
