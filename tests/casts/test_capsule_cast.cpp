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
#include "gjk/support_kernels.hpp"
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

// ---- Two capsules (capsule_pair_cast) --------------------------------------------------------------

namespace {

// Whether shape_cast's closed form answers this capsule pair itself.
bool pair_closed_form_answers(double ha, double ra, const Transform& pa, Vec3 ta, double hb, double rb,
                              const Transform& pb, Vec3 tb) {
    const kernels::RelativeFrame f = kernels::relative_frame(pa, pb);
    return cast_detail::capsule_pair_cast(ha, hb, f.r, f.t, pa.to_local_direction(tb - ta), ra, rb, kTol).verdict !=
           cast_detail::BoxCast::Verdict::Declined;
}

// The distance from world point x to capsule (h, rho) placed at pose, moved by lambda * motion.
double off_capsule(Vec3 x, const Transform& pose, Vec3 motion, double lambda, double h, double rho) {
    return to_segment(h, pose.apply_inverse(x - lambda * motion)) - rho;
}

}  // namespace

// Random capsule pairs against the oracle, the GJK cast of the same capsules as hulls of their
// segments' ends grown by balls, and the swapped order: the verdict, the time, the normal (opposite
// in the swapped order, within 1e-6 rad of the oracle's), the contact point on both surfaces. Radii
// from 1e-20 (below the entry's rounding: declined) to 3 sizes, half lengths 0.05 to 3, a third of the
// pairs turned so that their axes are parallel (the parallelogram a segment) and a twelfth within
// 1e-6 rad of it (declined), sizes 1e-3 to 1e3, up to 1e4 sizes from the origin.
TEST(CapsuleCast, CapsulePairsMatchTheOracleAndTheGjkCast) {
    const uint64_t seed = 56003;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1), len(0.05, 3);
    int cases = 0, closed = 0, hits = 0, parallel_hits = 0, closed_hits = 0;
    double worst_toi = 0, worst_angle = 0, worst_point = 0, worst_closed_toi = 0;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e4}) {
            for (double rounding : {1e-20, 1e-3, 0.3, 3.0}) {
                for (int i = 0; i < 60; ++i) {
                    const double ha = len(rng) * scale, hb = len(rng) * scale;
                    const double ra = rounding * scale * (0.5 + u(rng)), rb = rounding * scale * (0.5 + u(rng));
                    Solid a = make_solid(Kind::Capsule, ra, ha, {});
                    Solid b = make_solid(Kind::Capsule, rb, hb, {});
                    Cast c = random_cast(rng, a, b, far * scale * random_unit(rng));
                    // Parallel: B turned as A about A's axis (exactly, a quarter turn), or 1e-6 rad off it.
                    const int kind = i % 12;
                    if (kind < 4 || kind == 11) {
                        const double off = kind == 11 ? 1e-6 : 0.0;
                        c.pb.rotation =
                            c.pa.rotation *
                            to_matrix(axis_angle({1, 0, 0}, off) *
                                      (kind % 2 ? Quat{0, 0, 0.7071067811865476, 0.7071067811865476} : Quat{}));
                    }
                    place(a.body, c.pa);
                    place(b.body, c.pb);
                    const cast_oracle::Truth t = cast_oracle::toi(a.body, b.body, p3(c.ta), p3(c.tb));
                    if (t.grazing || t.start_overlap) continue;
                    const CapsuleShape ca(ra, ha), cb(rb, hb);
                    const HullCapsule ga(ha, ra), gb(hb, rb);
                    const CastResult r = shape_cast(ca, c.pa, c.ta, cb, c.pb, c.tb, kTol, kMaxIt);
                    const CastResult s = shape_cast(cb, c.pb, c.tb, ca, c.pa, c.ta, kTol, kMaxIt);
                    const CastResult g = shape_cast(ga.rounded, c.pa, c.ta, gb.rounded, c.pb, c.tb, kTol, kMaxIt);
                    const auto [size, rlen, round_off, toi_slack] = slack_of(a.body, b.body, c, c.pa.translation, kTol);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g rounding %g case %d",
                                  static_cast<unsigned long long>(seed), scale, far, rounding, i);
                    ++cases;
                    EXPECT_EQ(r.hit, t.hit) << what;
                    EXPECT_EQ(s.hit, t.hit) << what << ": the swapped order";
                    EXPECT_EQ(g.hit, t.hit) << what << ": the GJK cast";
                    const bool answered = pair_closed_form_answers(ha, ra, c.pa, c.ta, hb, rb, c.pb, c.tb);
                    closed += answered;
                    if (answered) {
                        EXPECT_EQ(r.iterations, 1u) << what << ": the closed form's one iteration";
                        EXPECT_NE(kind, 11) << what << ": axes 1e-6 rad from parallel are declined";
                    }
                    if (!t.hit || !r.hit) continue;
                    ++hits;
                    parallel_hits += kind < 4;
                    const double truth = static_cast<double>(t.toi);
                    EXPECT_NEAR(r.toi, truth, toi_slack) << what;
                    EXPECT_NEAR(s.toi, truth, toi_slack) << what << ": the swapped order";
                    EXPECT_NEAR(g.toi, truth, 4 * toi_slack) << what << ": the GJK cast";
                    worst_toi = std::fmax(worst_toi, std::fabs(r.toi - truth) * rlen / size);
                    if (answered) {
                        ++closed_hits;
                        worst_closed_toi = std::fmax(worst_closed_toi, std::fabs(r.toi - truth) * rlen / size);
                    }
                    EXPECT_LE(length(r.normal + s.normal), 1e-9) << what << ": the swapped order's normal";
                    const Vec3 tn{static_cast<double>(t.normal.x), static_cast<double>(t.normal.y),
                                  static_cast<double>(t.normal.z)};
                    // The oracle has no normal where parallel sides touch along a segment; radii of 1e-20
                    // make segments, declined to GJK, whose normal carries the tolerance's tilt.
                    if (length(tn) > 0.5 && rounding > 1e-20) {
                        worst_angle = std::fmax(worst_angle, angle_between(r.normal, tn));
                        EXPECT_LE(angle_between(r.normal, tn), 1e-6) << what;
                    }
                    const double on_a = std::fabs(off_capsule(r.point, c.pa, c.ta, r.toi, ha, ra));
                    const double on_b = std::fabs(off_capsule(r.point, c.pb, c.tb, r.toi, hb, rb));
                    worst_point = std::fmax(worst_point, std::fmax(on_a, on_b) / size);
                    EXPECT_LE(on_a, 1e-9 * size + 100 * round_off) << what << ": the point off A";
                    EXPECT_LE(on_b, 1e-9 * size + 100 * round_off) << what << ": the point off B";
                }
            }
        }
    }
    std::printf(
        "[capsule pairs] %d casts, %d hits (%d of parallel axes), %d answers by the closed form (%d hits); "
        "worst time %.2g of the size (closed form %.2g), normal %.2g rad, point %.2g of the size\n",
        cases, hits, parallel_hits, closed, closed_hits, worst_toi, worst_closed_toi, worst_angle, worst_point);
    EXPECT_GT(hits, cases / 4);
    EXPECT_LT(hits, 3 * cases / 4);
    EXPECT_GT(parallel_hits, hits / 5);
    // Declined: the hits and the near misses at radii of 1e-20 (a quarter of the casts), and
    // everything with axes 1e-6 rad from parallel (a twelfth).
    EXPECT_GT(closed, 7 * cases / 10);
    EXPECT_LT(closed, 9 * cases / 10);
    EXPECT_GT(closed_hits, hits / 2);
}

// Constructed contacts with known times, both orders, turned and 1e4 sizes from the origin: two
// upright capsules side by side closing across their axes, stacked closing along them (cap onto
// cap), crossed at right angles closing along their common perpendicular (side onto side), and a
// cap onto the other's side.
TEST(CapsuleCast, SideSideCapCapCrossedAndCapSideTimes) {
    const uint64_t seed = 56004;
    std::mt19937_64 rng(seed);
    const double ha = 1.2, hb = 0.7, ra = 0.3, rb = 0.2, sum = ra + rb;
    struct Case {
        const char* name;
        Quat qb;          // B's turn in A's frame
        Vec3 start, dir;  // B's centre and unit motion, A's frame
        double distance;  // how far B travels to contact
    };
    const Quat upright{}, across = axis_angle({1, 0, 0}, 1.5707963267948966);  // B's axis along -y
    const Case cases[] = {
        {"side by side", upright, {3, 0, 0.4}, {-1, 0, 0}, 3 - sum},
        {"cap onto cap", upright, {0, 0, 5}, {0, 0, -1}, 5 - ha - hb - sum},
        {"crossed", across, {4, 0.3, 0.5}, {-1, 0, 0}, 4 - sum},
        {"cap onto side", across, {0, hb + 3, 0.6}, {0, -1, 0}, 3 - sum},
    };
    for (const Case& k : cases) {
        for (double far : {0.0, 1e4}) {
            const Quat q = random_quat(rng);
            const Transform pa = make_transform(far * random_unit(rng), q);
            const Transform pb = make_transform(pa.apply(k.start), q * k.qb);
            const double motion = k.distance / 0.5;
            const Vec3 tb = motion * (to_matrix(q) * k.dir);
            const CapsuleShape a(ra, ha), b(rb, hb);
            const double slack = 1e-13 * (1 + far) / motion;
            const CastResult r = shape_cast(a, pa, {}, b, pb, tb, kTol, kMaxIt);
            const CastResult s = shape_cast(b, pb, tb, a, pa, {}, kTol, kMaxIt);
            EXPECT_TRUE(r.hit && s.hit) << k.name << " far " << far;
            EXPECT_NEAR(r.toi, 0.5, slack) << k.name << " far " << far;
            EXPECT_NEAR(s.toi, 0.5, slack) << k.name << " far " << far << ": swapped";
            EXPECT_EQ(r.iterations, 1u) << k.name << ": the closed form";
            EXPECT_EQ(s.iterations, 1u) << k.name << ": the closed form, swapped";
            const Vec3 n = to_matrix(q) * (-1.0 * k.dir);  // each contact's normal opposes the motion
            EXPECT_LE(angle_between(r.normal, n), 1e-12 * (1 + far)) << k.name << " far " << far;
            EXPECT_LE(angle_between(s.normal, -1.0 * n), 1e-12 * (1 + far)) << k.name << " far " << far;
            EXPECT_LE(std::fabs(off_capsule(r.point, pa, {}, r.toi, ha, ra)), 1e-12 * (1 + far)) << k.name;
            EXPECT_LE(std::fabs(off_capsule(r.point, pb, tb, r.toi, hb, rb)), 1e-12 * (1 + far)) << k.name;
        }
    }
}

// Capsule pairs passing each other at gaps from 1e-12 to 1e-2 of the size on either side of
// contact: crossed at right angles, parallel side by side, and 1e-3 rad from parallel (declined
// to GJK). The hit agrees with the sign of the gap above 1e-9 of the size, and the swapped order
// with it. A hit's time: crossed and parallel, where B's nearest point to A's axis comes within
// the radii's sum of it, y = -sqrt(sum^2 - d^2) (exact in long double; near a graze the time moves
// by the chord, sqrt(sum gap) over the motion); tilted, the GJK cast's on the same capsules as
// hulls, within what its tolerance allows at a graze.
TEST(CapsuleCast, CapsulePairsAtGapsFromOneEMinusTwelveToOneEMinusTwo) {
    const double ha = 1.0, hb = 0.8, ra = 0.25, rb = 0.25, sum = ra + rb;
    const CapsuleShape a(ra, ha), b(rb, hb);
    const HullCapsule ga(ha, ra), gb(hb, rb);
    int cases = 0, hits = 0, misses = 0, exact = 0;
    for (double gap : {1e-12, 1e-9, 1e-6, 1e-4, 1e-2}) {
        for (double sign : {-1.0, 1.0}) {
            const double d = sum + sign * gap;  // the closest approach of the two cores
            const struct {
                const char* name;
                Quat qb;
                double front;  // B's nearest point to A's axis, ahead of its centre along y
            } lines[] = {
                {"crossed", axis_angle({1, 0, 0}, 1.5707963267948966), hb},
                {"parallel", Quat{}, 0},
                {"1e-3 rad from parallel", axis_angle({1, 0, 0}, 1e-3), -1},
            };
            for (const auto& l : lines) {
                const Transform pa = make_transform({0, 0, 0}, Quat{});
                const Transform pb = make_transform({d, -4, 0.3}, l.qb);
                const Vec3 motion{0, 8, 0};
                const CastResult r = shape_cast(a, pa, {}, b, pb, motion, kTol, kMaxIt);
                const CastResult s = shape_cast(b, pb, motion, a, pa, {}, kTol, kMaxIt);
                char what[120];
                std::snprintf(what, sizeof what, "%s gap %g sign %g", l.name, gap, sign);
                ++cases;
                if (gap > 1e-9) {
                    EXPECT_EQ(r.hit, sign < 0) << what;
                    EXPECT_EQ(s.hit, sign < 0) << what << ": swapped";
                }
                hits += r.hit;
                misses += !r.hit;
                if (!r.hit || sign > 0) continue;
                if (l.front >= 0) {
                    using R = long double;
                    const R y = -std::sqrt(R(sum) * R(sum) - R(d) * R(d));
                    const double truth = double((y - R(l.front) + 4) / 8);
                    EXPECT_NEAR(r.toi, truth, 1e-13) << what;
                    EXPECT_NEAR(s.toi, truth, 1e-13) << what << ": swapped";
                    ++exact;
                } else {
                    const CastResult g = shape_cast(ga.rounded, pa, {}, gb.rounded, pb, motion, kTol, kMaxIt);
                    EXPECT_TRUE(g.hit) << what;
                    EXPECT_NEAR(r.toi, g.toi, 1e-5) << what;
                }
            }
        }
    }
    EXPECT_GT(hits, cases / 3);
    EXPECT_GT(misses, cases / 3);
    EXPECT_EQ(exact, 10);
}

// Offsets and motions beyond the closed form's range (1e100; products of coordinates there
// overflow and a slab test would read a miss): declined, and the GJK cast answers. B starts 1e120
// away and passes through A, or 10 beside it; the same at 1e-120 sizes for the range's other end.
TEST(CapsuleCast, CapsulePairsBeyondTheClosedFormsRangeGoToGjk) {
    for (const double scale : {1e120, 1e-120}) {
        const double far = scale > 1 ? scale : 1.0;
        const double unit = scale > 1 ? 1.0 : scale;
        const CapsuleShape a(0.3 * unit, 1.0 * unit), b(0.2 * unit, 0.7 * unit);
        for (const double beside : {0.0, 10.0}) {
            const Transform pa = make_transform({0, 0, 0}, Quat{});
            const Transform pb = make_transform({far, beside * unit, 0}, axis_angle({1, 0, 0}, 1.0));
            const Vec3 motion{-2 * far, 0, 0};
            const kernels::RelativeFrame f = kernels::relative_frame(pa, pb);
            const cast_detail::BoxCast bc =
                cast_detail::capsule_pair_cast(1.0 * unit, 0.7 * unit, f.r, f.t, motion, 0.3 * unit, 0.2 * unit, kTol);
            if (scale > 1) {
                EXPECT_EQ(bc.verdict, cast_detail::BoxCast::Verdict::Declined) << "beside " << beside;
            }
            const CastResult r = shape_cast(a, pa, {}, b, pb, motion, kTol, kMaxIt);
            EXPECT_EQ(r.hit, beside == 0) << "scale " << scale << " beside " << beside;
            if (r.hit) {
                EXPECT_NEAR(r.toi, 0.5, 1e-9) << "scale " << scale;
            }
        }
    }
}

// Capsules of half length 0 (balls) as A, as B and as both: the parallelogram is a segment or a
// point, and its edges' capsules coincide. Random casts against the oracle and in both orders.
// Then pairs touching or overlapping at the start (gaps -0.1 to +1e-12 of the size along a random
// direction, closing): the closed form declines them (the GJK cast's conventions for a start in
// contact), and both orders hit at once.
TEST(CapsuleCast, CapsulePairsOfZeroLengthAndTouchingAtTheStart) {
    const uint64_t seed = 57001;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double lengths[3][2] = {{0, 0.7}, {1.2, 0}, {0, 0}};
    int cases = 0, hits = 0, closed = 0;
    for (const auto& hl : lengths) {
        const double ha = hl[0], hb = hl[1];
        for (int i = 0; i < 120; ++i) {
            const double ra = 0.2 + u(rng), rb = 0.2 + u(rng);
            Solid a = make_solid(Kind::Capsule, ra, ha, {});
            Solid b = make_solid(Kind::Capsule, rb, hb, {});
            const Cast c = random_cast(rng, a, b, (i % 2 ? 1e3 : 0.0) * random_unit(rng));
            place(a.body, c.pa);
            place(b.body, c.pb);
            const cast_oracle::Truth t = cast_oracle::toi(a.body, b.body, p3(c.ta), p3(c.tb));
            if (t.grazing || t.start_overlap) continue;
            const CapsuleShape ca(ra, ha), cb(rb, hb);
            const CastResult r = shape_cast(ca, c.pa, c.ta, cb, c.pb, c.tb, kTol, kMaxIt);
            const CastResult s = shape_cast(cb, c.pb, c.tb, ca, c.pa, c.ta, kTol, kMaxIt);
            const auto [size, rlen, round_off, toi_slack] = slack_of(a.body, b.body, c, c.pa.translation, kTol);
            char what[120];
            std::snprintf(what, sizeof what, "seed %llu ha %g hb %g case %d", static_cast<unsigned long long>(seed), ha,
                          hb, i);
            ++cases;
            closed += pair_closed_form_answers(ha, ra, c.pa, c.ta, hb, rb, c.pb, c.tb);
            EXPECT_EQ(r.hit, t.hit) << what;
            EXPECT_EQ(s.hit, t.hit) << what << ": the swapped order";
            if (!t.hit || !r.hit || !s.hit) continue;
            ++hits;
            EXPECT_NEAR(r.toi, static_cast<double>(t.toi), toi_slack) << what;
            EXPECT_NEAR(s.toi, static_cast<double>(t.toi), toi_slack) << what << ": the swapped order";
            EXPECT_LE(length(r.normal + s.normal), 1e-9) << what << ": the swapped order's normal";
            EXPECT_LE(std::fabs(off_capsule(r.point, c.pa, c.ta, r.toi, ha, ra)), 1e-9 * size + 100 * round_off)
                << what << ": the point off A";
            EXPECT_LE(std::fabs(off_capsule(r.point, c.pb, c.tb, r.toi, hb, rb)), 1e-9 * size + 100 * round_off)
                << what << ": the point off B";
        }
    }
    std::printf("[zero-length capsules] %d casts, %d hits, %d answered by the closed form\n", cases, hits, closed);
    EXPECT_GT(hits, cases / 4);
    EXPECT_LT(hits, 3 * cases / 4);
    EXPECT_GT(closed, cases / 2);  // the pieces are balls and capsules: answered, not declined

    // Touching or overlapping at the start: B's segment placed so that the cores' closest points lie
    // sum + gap apart along a direction normal to both axes, B closing along it.
    int touching = 0;
    for (const double gap : {-0.1, -1e-9, 0.0, 1e-12}) {
        for (int i = 0; i < 40; ++i) {
            const double ha = i % 4 == 0 ? 0.0 : 1.2, hb = i % 4 == 1 ? 0.0 : 0.7, ra = 0.3, rb = 0.2;
            const Quat qa = random_quat(rng);
            const Mat3 ma = to_matrix(qa);
            // B turned about the x axis of A's frame: both axes lie in A's yz plane, x is normal to both.
            const Quat qb = qa * axis_angle({1, 0, 0}, 3.0 * u(rng));
            const Vec3 side = ma * Vec3{1, 0, 0};
            const Vec3 base = (i % 2 ? 1e3 : 0.0) * random_unit(rng);
            const Transform pa = make_transform(base, qa);
            const Transform pb = make_transform(base + (ra + rb + gap) * side, qb);
            const Vec3 tb = -2.0 * side + 0.5 * random_unit(rng);
            const CapsuleShape ca(ra, ha), cb(rb, hb);
            char what[120];
            std::snprintf(what, sizeof what, "seed %llu gap %g case %d", static_cast<unsigned long long>(seed), gap, i);
            ++touching;
            EXPECT_FALSE(pair_closed_form_answers(ha, ra, pa, {}, hb, rb, pb, tb)) << what;
            const CastResult r = shape_cast(ca, pa, {}, cb, pb, tb, kTol, kMaxIt);
            const CastResult s = shape_cast(cb, pb, tb, ca, pa, {}, kTol, kMaxIt);
            EXPECT_TRUE(r.hit && s.hit) << what;
            EXPECT_LE(r.toi, 1e-9) << what;
            EXPECT_LE(s.toi, 1e-9) << what << ": the swapped order";
        }
    }
    EXPECT_EQ(touching, 160);
}
