// SPDX-License-Identifier: MIT
// A ball (or a point) cast against a capsule, and a ray against a capsule, in closed form
// (casts/box_cast.hpp, ray_capsule: the segment as the box (0, 0, h) rounded by both radii), against
// truths it does not share: the long double oracle, the GJK cast on the same capsule given as a
// hull of its segment's two ends grown by a ball (another algorithm), and constructed entries
// whose time is known (the side head-on and off-centre, a cap along the axis, the rim between
// them). Radii from 1e-20 to 3 times the size (the smallest below the entry's rounding, declined
// to GJK), sizes 1e-3 to 1e3, up to 1e4 sizes from the origin, both argument orders.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "cast_four_ways.hpp"
#include "cast_test_support.hpp"
#include "casts/box_cast.hpp"
#include "casts/cast.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using namespace cast_test;

namespace {

constexpr uint32_t kMaxIt = 256;
constexpr double kTol = 1e-10;

// The capsule of half length h and radius rho as the hull of its segment's ends grown by a ball:
// shape_cast takes the GJK path for it.
struct HullCapsule {
    ShapePtr segment;
    SphereShape ball;
    MinkowskiSumShape rounded;
    HullCapsule(double h, double rho)
        : segment(hull_shape({{0, 0, -h}, {0, 0, h}})), ball(rho), rounded(*segment, ball) {}
};

// The distance from x (the capsule's frame) to the capsule's segment.
double to_segment(double h, Vec3 x) {
    const double z = x.z < -h ? -h : (x.z > h ? h : x.z);
    return length(x - Vec3{0, 0, z});
}

}  // namespace

// Random balls and points cast onto capsules: the time against the oracle, against the GJK cast on
// the hull capsule, in the swapped order and as a ray against the capsule grown by the ball's
// radius; the normal against the oracle's, opposite in the swapped order; the contact point on both
// shapes at toi.
TEST(CapsuleCast, BallsAndRaysOntoCapsulesMatchTheOracle) {
    const uint64_t seed = 56001;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1), len(0.05, 3);
    int cases = 0, closed = 0, hits = 0, caps = 0;
    double worst_toi = 0, worst_angle = 0;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e4}) {
            for (double rounding : {1e-20, 1e-6, 0.3, 3.0}) {
                for (int i = 0; i < 60; ++i) {
                    const double h = len(rng) * scale;
                    const double rho_capsule = rounding * scale * (0.5 + u(rng));
                    const double rho_ball = (i % 3 == 0 ? 0.0 : u(rng)) * scale;
                    // The oracle's pair: the capsule and the ball (a point at radius 0).
                    Solid capsule = make_solid(Kind::Capsule, rho_capsule, h, {});
                    Solid ball = make_solid(Kind::Sphere, rho_ball, 0, {});
                    const Vec3 base = far * scale * random_unit(rng);
                    Cast c = random_cast(rng, capsule, ball, base);
                    place(capsule.body, c.pa);
                    place(ball.body, c.pb);
                    const cast_oracle::Truth t = cast_oracle::toi(capsule.body, ball.body, p3(c.ta), p3(c.tb));
                    if (t.grazing || t.start_overlap) continue;
                    const SphereShape moving(rho_ball);
                    const PointShape point;
                    const Shape& b = rho_ball > 0 ? static_cast<const Shape&>(moving) : point;
                    const CapsuleShape cap(rho_capsule, h);
                    const HullCapsule hull(h, rho_capsule);
                    const CapsuleShape grown(rho_capsule + rho_ball, h);
                    const FourWays f{shape_cast(cap, c.pa, c.ta, b, c.pb, c.tb, kTol, kMaxIt),
                                     shape_cast(b, c.pb, c.tb, cap, c.pa, c.ta, kTol, kMaxIt),
                                     shape_cast(hull.rounded, c.pa, c.ta, b, c.pb, c.tb, kTol, kMaxIt),
                                     ray_cast(grown, c.pa, c.pb.translation, c.tb - c.ta, kTol, kMaxIt)};
                    const CastResult& r = f.r;
                    const auto [size, rlen, round_off, toi_slack] = slack_of(capsule.body, ball.body, c, base, kTol);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g rounding %g case %d",
                                  static_cast<unsigned long long>(seed), scale, far, rounding, i);
                    // A radius of 1e-20 has no normal of its own.
                    const double angle = expect_four_ways_agree(f, t, toi_slack, 4 * toi_slack, rounding > 1e-20, what);
                    worst_angle = std::fmax(worst_angle, angle);
                    ++cases;
                    // shape_cast's own call: the ball's centre as a ray against the grown capsule.
                    const bool answered =
                        cast_detail::ray_capsule(h, rho_capsule + rho_ball, c.pa.apply_inverse(c.pb.translation),
                                                 c.pa.to_local_direction(c.tb - c.ta))
                            .verdict != cast_detail::BoxCast::Verdict::Declined;
                    closed += answered;
                    if (answered) {
                        EXPECT_EQ(r.iterations, 1u) << what << ": the closed form's one iteration";
                    }
                    if (!t.hit || !r.hit) continue;
                    ++hits;
                    worst_toi = std::fmax(worst_toi, std::fabs(r.toi - static_cast<double>(t.toi)) * rlen / size);
                    // The contact point: on the capsule and on the ball at toi.
                    const Vec3 at_capsule = c.pa.apply_inverse(r.point - r.toi * c.ta);
                    EXPECT_NEAR(to_segment(h, at_capsule), rho_capsule, 1e-9 * size + 100 * round_off) << what;
                    const Vec3 centre = c.pb.translation + r.toi * c.tb;
                    EXPECT_NEAR(length(r.point - centre), rho_ball, 1e-9 * size + 100 * round_off) << what;
                    caps += std::fabs(at_capsule.z) > h;
                }
            }
        }
    }
    std::printf(
        "[balls onto capsules] %d casts, %d hits (%d on a cap), %d by the closed form; worst time %.2g of "
        "the size, normal %.2g rad\n",
        cases, hits, caps, closed, worst_toi, worst_angle);
    EXPECT_GT(hits, cases / 4);
    EXPECT_LT(hits, 3 * cases / 4);
    EXPECT_GT(caps, hits / 20);  // the caps are met, not only the side
    EXPECT_LT(caps, hits / 2);
    // All but the points cast at capsules of radius 1e-20 (below the entry's rounding: a twelfth of
    // the cases) are answered.
    EXPECT_GT(closed, 88 * cases / 100);
    EXPECT_LT(closed, 95 * cases / 100);
}

// Constructed entries with known times: the side head-on and off the axis's line, a cap along the
// axis, off it, and near the rim where the side meets it. Each at
// contact lambda 0.5, turned, 1e4 sizes from the origin, both argument orders, and as a ray.
TEST(CapsuleCast, SideCapAndRimAgainstTheirTimes) {
    const uint64_t seed = 56002;
    std::mt19937_64 rng(seed);
    const double h = 1.5, rho = 0.4, ball = 0.1, sum = rho + ball;
    struct Case {
        const char* name;
        Vec3 start, dir;  // capsule frame, dir unit
        double distance;  // how far the ball's centre travels to contact
    };
    const double off = 0.3, z = 0.7;
    const Case cases[] = {
        {"side head-on", {3, 0, z}, {-1, 0, 0}, 3 - sum},
        {"side off the axis's line", {3, off, z}, {-1, 0, 0}, 3 - std::sqrt(sum * sum - off * off)},
        {"cap along the axis", {0, 0, 4}, {0, 0, -1}, 4 - h - sum},
        {"cap off the axis", {off, 0, -4}, {0, 0, 1}, 4 - h - std::sqrt(sum * sum - off * off)},
        {"cap near the rim, along the axis",
         {0.95 * sum, 0, 4},
         {0, 0, -1},
         4 - h - std::sqrt(sum * sum - 0.95 * sum * 0.95 * sum)},
    };
    for (const Case& k : cases) {
        for (double far : {0.0, 1e4}) {
            const Quat q = random_quat(rng);
            const Transform pa = make_transform(far * random_unit(rng), q);
            const Transform pb = make_transform(pa.apply(k.start), Quat{});
            const double motion = k.distance / 0.5;
            const Vec3 tb = motion * (to_matrix(q) * k.dir);
            const CapsuleShape capsule(rho, h);
            const SphereShape b(ball);
            const double slack = 1e-13 * (1 + far) / motion;
            const CastResult r = shape_cast(capsule, pa, {}, b, pb, tb, kTol, kMaxIt);
            const CastResult s = shape_cast(b, pb, tb, capsule, pa, {}, kTol, kMaxIt);
            EXPECT_TRUE(r.hit && s.hit) << k.name << " far " << far;
            EXPECT_NEAR(r.toi, 0.5, slack) << k.name << " far " << far;
            EXPECT_NEAR(s.toi, 0.5, slack) << k.name << " far " << far << ": swapped";
            EXPECT_EQ(r.iterations, 1u) << k.name << ": the closed form";
            EXPECT_EQ(s.iterations, 1u) << k.name << ": the closed form, swapped";
            // The normal: from the segment's nearest point toward the ball's centre at contact.
            const Vec3 centre = k.start + 0.5 * motion * k.dir;
            const double cz = centre.z < -h ? -h : (centre.z > h ? h : centre.z);
            const Vec3 n = to_matrix(q) * ((1 / sum) * (centre - Vec3{0, 0, cz}));
            EXPECT_LE(angle_between(r.normal, n), 1e-12 * (1 + far)) << k.name << " far " << far;
            EXPECT_LE(angle_between(s.normal, -1.0 * n), 1e-12 * (1 + far)) << k.name << " far " << far;
            const CapsuleShape grown(sum, h);
            const CastResult ray = ray_cast(grown, pa, pb.translation, tb, kTol, kMaxIt);
            EXPECT_TRUE(ray.hit) << k.name;
            EXPECT_NEAR(ray.toi, 0.5, slack) << k.name << " far " << far << ": the ray";
            EXPECT_EQ(ray.iterations, 1u) << k.name << ": the ray's closed form";
        }
    }
}

// Near misses and near hits: a ball passing the side, a cap and the rim at gaps from 1e-12 to 1e-2
// of the size on either side of contact. Whatever the closed form answers or declines, the hit
// agrees with the sign of the gap (a graze within 1e-9 of the size may go either way), and a hit's
// time is the known one.
TEST(CapsuleCast, GapsFromOneEMinusTwelveToOneEMinusTwoOnBothSides) {
    const double h = 1.0, rho = 0.5;
    const CapsuleShape capsule(rho, h);
    const PointShape point;
    int hits = 0, misses = 0, cases = 0;
    for (double gap : {1e-12, 1e-9, 1e-6, 1e-4, 1e-2}) {
        for (double sign : {-1.0, 1.0}) {
            const double d = rho + sign * gap;  // the line's distance from the segment
            // Past the side across the axis, past a cap beside the axis's line, and along the
            // axis's direction beside the side.
            const struct {
                const char* name;
                Vec3 start, motion;
            } lines[] = {{"side", {-3, d, 0.2}, {6, 0, 0}},
                         {"cap", {-3, 0, h + d}, {6, 0, 0}},
                         {"along the side", {d, 0, -4}, {0, 0, 8}}};
            for (const auto& l : lines) {
                for (int order = 0; order < 2; ++order) {
                    const Transform pa = make_transform({0, 0, 0}, Quat{});
                    const Transform pb = make_transform(l.start, Quat{});
                    const CastResult r = order == 0 ? shape_cast(capsule, pa, {}, point, pb, l.motion, kTol, kMaxIt)
                                                    : shape_cast(point, pb, l.motion, capsule, pa, {}, kTol, kMaxIt);
                    char what[120];
                    std::snprintf(what, sizeof what, "%s gap %g sign %g order %d", l.name, gap, sign, order);
                    ++cases;
                    if (gap > 1e-9) {
                        EXPECT_EQ(r.hit, sign < 0) << what;
                    }
                    hits += r.hit;
                    misses += !r.hit;
                    if (r.hit && sign < 0) {
                        // The entry: where the line first comes within rho of the segment. The
                        // distance is convex along the line: its least point by ternary search,
                        // then the crossing before it by bisection.
                        auto dist = [&](double lambda) { return to_segment(h, l.start + lambda * l.motion); };
                        double a = 0, b = 1;
                        for (int it = 0; it < 200; ++it) {
                            const double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
                            (dist(m1) < dist(m2) ? b : a) = dist(m1) < dist(m2) ? m2 : m1;
                        }
                        double lo = 0, hi = a;
                        for (int it = 0; it < 200; ++it) {
                            const double mid = 0.5 * (lo + hi);
                            (dist(mid) <= rho ? hi : lo) = mid;
                        }
                        EXPECT_NEAR(r.toi, hi, 1e-9) << what;
                    }
                }
            }
        }
    }
    EXPECT_GT(hits, cases / 3);
    EXPECT_GT(misses, cases / 3);
}
