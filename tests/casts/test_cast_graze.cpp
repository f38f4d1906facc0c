// SPDX-License-Identifier: MIT
// Shape casts that pass a hair beside a shape, where A - B is flat or a point stands still: the
// truth is known by construction (a plane separates the two all along the motion, by a gap g from
// 1e-8 to 1e-3 of their size), and both argument orders must say "no hit". The loop's rounding
// rules once stopped on such pairs (support points tied along the plane's normal) and the stop was
// read as a contact in one order only (a hard-input sweep found it: a segment gliding 1.3e-6 over
// another, a point 4e-9 from a segment with no motion). With g = 0 the pairs touch: a hit, the
// control that the placements do meet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "cast_test_support.hpp"
#include "casts/cast.hpp"
#include "shapes/shape.hpp"

using namespace kairos;

namespace {

constexpr double kTol = 1e-10;  // the public default
constexpr uint32_t kMaxIt = 256;

using cast_test::random_quat;
using cast_test::random_unit;

struct Tally {
    int casts = 0, wrong = 0;
    void check(bool hit, bool want, uint64_t seed, int trial, const char* what, double gap, int order) {
        ++casts;
        if (hit != want && ++wrong <= 10)
            ADD_FAILURE() << "seed " << seed << " trial " << trial << " " << what << " gap " << gap << " order "
                          << order << ": hit " << hit << ", expected " << want;
    }
};

// A point inside the hull of `pts` (a solid one): every point weighted by floor + [0, 1). A point
// of an edge would be grazed, and rounding may miss it.
Vec3 interior_point(const std::vector<Vec3>& pts, double floor, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    Vec3 sum{};
    double total = 0;
    for (const Vec3& p : pts) {
        const double w = floor + u(rng);
        sum = sum + w * p;
        total += w;
    }
    return (1 / total) * sum;
}

}  // namespace

// Two segments in parallel planes g apart (normal n = da x db), B sliding across A along the
// planes so that their projections cross: their distance is g all along (0: they touch).
TEST(ShapeCastGraze, SegmentsGlidingOverEachOthersPlane) {
    const uint64_t seed = 7301;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Tally tally;
    for (int trial = 0; trial < 600; ++trial) {
        const double ha = 0.5 + 1.5 * u(rng), hb = 0.5 + 1.5 * u(rng);
        const SegmentShape a(ha), b(hb);
        const Quat qa = random_quat(rng), qb = random_quat(rng);
        const Vec3 da = to_matrix(qa) * Vec3{0, 0, 1}, db = to_matrix(qb) * Vec3{0, 0, 1};
        const Vec3 n = normalized_or(cross(da, db), Vec3{});
        if (!(dot(n, n) > 0.5) || std::fabs(dot(da, db)) > 0.99) continue;
        const Vec3 m = normalized_or(cross(n, random_unit(rng)), Vec3{});  // the motion's direction
        if (!(dot(m, m) > 0.5)) continue;
        const double size = std::fmax(ha, hb);
        const double gap = trial % 6 == 0 ? 0.0 : size * std::pow(10.0, -8 + 5 * u(rng));
        const Vec3 ca{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
        const double reach = 3 * size;  // B starts and ends this far to the side
        const Vec3 start = ca + gap * n - reach * m;
        const Vec3 motion = 2 * reach * m;
        const Transform pa = make_transform(ca, qa), pb = make_transform(start, qb);
        const bool want = gap == 0;
        tally.check(shape_cast(a, pa, {}, b, pb, motion, kTol, kMaxIt).hit, want, seed, trial, "segments", gap, 0);
        tally.check(shape_cast(b, pb, motion, a, pa, {}, kTol, kMaxIt).hit, want, seed, trial, "segments", gap, 1);
    }
    std::printf("segments gliding over each other's plane: %d casts\n", tally.casts);
    EXPECT_EQ(tally.wrong, 0);
    EXPECT_GT(tally.casts, 1000);
}

// A point beside a segment (off its middle, perpendicular) or above a box's face, with no motion
// or moving along the face: the gap stays g. Both orders.
TEST(ShapeCastGraze, APointBesideASegmentOrOverABoxFace) {
    const uint64_t seed = 7302;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Tally tally;
    const PointShape point;
    for (int trial = 0; trial < 600; ++trial) {
        const Quat q = random_quat(rng);
        const Vec3 c{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
        const Transform pose = make_transform(c, q);
        const bool touching = trial % 6 == 0;
        if (trial % 2 == 0) {
            const double h = 0.5 + 1.5 * u(rng);
            const SegmentShape seg(h);
            const double gap = touching ? 0.0 : h * std::pow(10.0, -8 + 5 * u(rng));
            // Beside the segment at height z in (-h, h), along a direction perpendicular to it.
            const double phi = 6.283185307179586 * u(rng), z = h * (1.6 * u(rng) - 0.8);
            const Vec3 side{std::cos(phi), std::sin(phi), 0};
            const Vec3 p = pose.apply(Vec3{0, 0, z} + gap * side);
            const Transform pp = make_transform(p, {});
            tally.check(shape_cast(point, pp, {}, seg, pose, {}, kTol, kMaxIt).hit, touching, seed, trial,
                        "point by segment", gap, 0);
            tally.check(shape_cast(seg, pose, {}, point, pp, {}, kTol, kMaxIt).hit, touching, seed, trial,
                        "point by segment", gap, 1);
        } else {
            const Vec3 h{0.5 + u(rng), 0.5 + u(rng), 0.5 + u(rng)};
            const BoxShape box(h);
            const double size = std::fmax(h.x, std::fmax(h.y, h.z));
            const double gap = touching ? 0.0 : size * std::pow(10.0, -8 + 5 * u(rng));
            // Above the top face, crossing it along a line through its inside.
            const double phi = 6.283185307179586 * u(rng);
            const Vec3 along{std::cos(phi), std::sin(phi), 0};
            const Vec3 mid{0.5 * h.x * (2 * u(rng) - 1), 0.5 * h.y * (2 * u(rng) - 1), h.z + gap};
            const double reach = 3 * size;
            const Transform pp = make_transform(pose.apply(mid - reach * along), {});
            const Vec3 motion = pose.rotation * (2 * reach * along);
            tally.check(shape_cast(point, pp, motion, box, pose, {}, kTol, kMaxIt).hit, touching, seed, trial,
                        "point over box", gap, 0);
            tally.check(shape_cast(box, pose, {}, point, pp, motion, kTol, kMaxIt).hit, touching, seed, trial,
                        "point over box", gap, 1);
        }
    }
    std::printf("points beside segments and over box faces: %d casts\n", tally.casts);
    EXPECT_EQ(tally.wrong, 0);
    EXPECT_EQ(tally.casts, 1200);
}

// A prism of 40 vertices (a large hull: its support climbs, a general support to the cast loop,
// which gives curved shapes more slack) with a point or a segment gliding over its top face,
// parallel to it, g above. Both orders.
TEST(ShapeCastGraze, OverALargeHullsFace) {
    const uint64_t seed = 7303;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> corners;
    const double radius = 1.3, half_height = 0.4;
    for (int k = 0; k < 20; ++k) {
        const double phi = 0.3141592653589793 * k;
        corners.push_back({radius * std::cos(phi), radius * std::sin(phi), -half_height});
        corners.push_back({radius * std::cos(phi), radius * std::sin(phi), half_height});
    }
    const cast_test::ShapePtr prism = cast_test::hull_shape(corners);
    ASSERT_EQ(prism->kind(), ShapeKind::ConvexHull);
    ASSERT_GT(static_cast<const ConvexHullShape&>(*prism).vertices.size(), ConvexHullShape::kHillClimbThreshold);
    const PointShape point;
    const SegmentShape segment(0.5);
    Tally tally;
    for (int trial = 0; trial < 400; ++trial) {
        const Quat q = random_quat(rng);
        const Transform pose = make_transform({u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5}, q);
        const bool touching = trial % 6 == 0;
        const double gap = touching ? 0.0 : radius * std::pow(10.0, -8 + 5 * u(rng));
        const double phi = 6.283185307179586 * u(rng);
        const Vec3 along{std::cos(phi), std::sin(phi), 0};
        // Through the face's middle region; the segment lies flat, turned about z.
        const Vec3 mid{0.3 * (u(rng) - 0.5), 0.3 * (u(rng) - 0.5), half_height + gap};
        const double reach = 4;
        const Quat flat = normalized(q * Quat{0, std::sin(0.7853981633974483), 0, std::cos(0.7853981633974483)} *
                                     Quat{0, 0, std::sin(phi), std::cos(phi)});
        const bool use_segment = trial % 2 == 1;
        const Shape& mover = use_segment ? static_cast<const Shape&>(segment) : static_cast<const Shape&>(point);
        const Transform pm = make_transform(pose.apply(mid - reach * along), use_segment ? flat : Quat{});
        const Vec3 motion = pose.rotation * (2 * reach * along);
        const char* what = use_segment ? "segment over prism" : "point over prism";
        tally.check(shape_cast(mover, pm, motion, *prism, pose, {}, kTol, kMaxIt).hit, touching, seed, trial, what, gap,
                    0);
        tally.check(shape_cast(*prism, pose, {}, mover, pm, motion, kTol, kMaxIt).hit, touching, seed, trial, what, gap,
                    1);
    }
    std::printf("points and segments over a large hull's face: %d casts\n", tally.casts);
    EXPECT_EQ(tally.wrong, 0);
    EXPECT_EQ(tally.casts, 800);
}

// Rays gliding over a triangle's plane, parallel to it, g above (0: in the plane, crossing the
// triangle: a hit). The ray cast's loop stopped on a stall over the flat shape and read it as a
// hit on 51 of 9,769 such rays (gaps 1e-8 to 1e-3; a sweep).
TEST(RayCastGraze, RaysGlidingOverATrianglesPlane) {
    const uint64_t seed = 7304;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    int rays = 0, wrong = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const Vec3 e1 = random_unit(rng), e2 = random_unit(rng);
        const Vec3 normal = normalized_or(cross(e1, e2), Vec3{});
        if (!(length(cross(e1, e2)) > 0.2)) continue;
        const Vec3 c{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
        const cast_test::ShapePtr triangle = cast_test::hull_shape({c, c + e1, c + e2});
        const bool touching = trial % 6 == 0;
        const double gap = touching ? 0.0 : std::pow(10.0, -8 + 5 * u(rng));
        const Vec3 centroid = c + (1.0 / 3) * (e1 + e2);
        const Vec3 along = normalized_or(cross(normal, e1), Vec3{});
        const Transform pose = make_transform({}, Quat{});
        const CastResult r = ray_cast(*triangle, pose, centroid + gap * normal - 3 * along, 6 * along, kTol, kMaxIt);
        ++rays;
        if (r.hit != touching && ++wrong <= 10)
            ADD_FAILURE() << "seed " << seed << " trial " << trial << " gap " << gap << ": hit " << r.hit << " toi "
                          << r.toi << " termination " << int(r.termination);
    }
    std::printf("rays gliding over a triangle's plane: %d\n", rays);
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(rays, 2000);
}

// Rays and moving points through needles: hulls of seven points along x (length about 1.2) whose
// other coordinates are jittered by 1e-10 to 1e-8. The ray passes through a point of the hull (a
// mix of two of its points), so it must hit no later than there, and never late: at toi the ray
// point is not behind the plane of the reported normal, h(n) = max over the points of n . p (long
// double). A stop on a rounding rule beside the needle resumes the loop from the distance at toi;
// a resumed loop that hit without clipping reported the start-inside normal -r, whose plane cut
// the needle 0.18 deep (fuzzing: tests/fuzz/corpus/fuzz_queries/df6dd997...); the distance's axis
// in its place lay up to 4.5e-9 past the ray point (the needles' aspect, 1e8 to 1e10, is beyond
// the distance's accuracy range); the last clip's plane holds it to rounding.
TEST(RayCastGraze, ThroughNeedlesNeverBehindTheNormalsPlane) {
    const uint64_t seed = 7305;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double kPlaneSlack = 1e-9;  // of the length; the distance's axis as the plane reached 4.5e-9
    long double worst = 0;
    int casts = 0, bad = 0, rounding_stops = 0;
    auto check = [&](int trial, const char* what, const CastResult& r, const std::vector<Vec3>& pts, Vec3 from,
                     Vec3 motion, double toi_through, Vec3 normal) {
        ++casts;
        const long double lx = from.x + static_cast<long double>(r.toi) * motion.x;
        const long double ly = from.y + static_cast<long double>(r.toi) * motion.y;
        const long double lz = from.z + static_cast<long double>(r.toi) * motion.z;
        long double h = -INFINITY;
        for (const Vec3& p : pts)
            h = std::fmax(h, static_cast<long double>(normal.x) * p.x + static_cast<long double>(normal.y) * p.y +
                                 static_cast<long double>(normal.z) * p.z);
        const long double behind = h - (normal.x * lx + normal.y * ly + normal.z * lz);
        worst = std::fmax(worst, behind);
        if (cast_test::rounding_stop(r.termination)) ++rounding_stops;
        const bool ok = r.hit && r.toi <= toi_through + 1e-9 && behind <= kPlaneSlack && length(normal) > 0.5;
        if (!ok && ++bad <= 10)
            ADD_FAILURE() << "seed " << seed << " trial " << trial << " " << what << ": hit " << r.hit << " toi "
                          << r.toi << " (through the needle at " << toi_through << ") termination "
                          << int(r.termination) << ", the ray point " << static_cast<double>(behind)
                          << " behind the normal's plane";
    };
    for (int trial = 0; trial < 400; ++trial) {
        const double jitter = std::pow(10.0, -10 + 2 * u(rng));
        std::vector<Vec3> pts;
        for (int k = 0; k < 7; ++k)
            pts.push_back({-0.9 + 1.2 * u(rng), jitter * (2 * u(rng) - 1), jitter * (2 * u(rng) - 1)});
        const cast_test::ShapePtr needle = cast_test::hull_shape(pts);
        const Vec3 through = interior_point(pts, 0.05, rng);
        // From any side, often nearly along the needle's cross-section.
        Vec3 d = random_unit(rng);
        if (trial % 2 == 0) d.x *= 1e-3;
        d = normalized_or(d, Vec3{0, 1, 0});
        const double toi_through = 0.5 + 0.5 * u(rng);
        const Vec3 from = through + 0.6 * d;
        const Vec3 motion = (-0.6 / toi_through) * d;
        const CastResult r = ray_cast(*needle, make_transform({}, Quat{}), from, motion, kTol, kMaxIt);
        check(trial, "ray", r, pts, from, motion, toi_through, r.normal);
        // A point moving the same way, both orders (normal from A toward B).
        const PointShape point;
        const Transform pf = make_transform(from, Quat{});
        const CastResult ab = shape_cast(*needle, make_transform({}, Quat{}), {}, point, pf, motion, kTol, kMaxIt);
        check(trial, "needle, point", ab, pts, from, motion, toi_through, ab.normal);
        const CastResult ba = shape_cast(point, pf, motion, *needle, make_transform({}, Quat{}), {}, kTol, kMaxIt);
        check(trial, "point, needle", ba, pts, from, motion, toi_through, -ba.normal);
    }
    std::printf("rays and points through needles: %d casts, %d ended on a rounding rule, worst %.3g behind the plane\n",
                casts, rounding_stops, static_cast<double>(worst));
    EXPECT_EQ(bad, 0);
    EXPECT_EQ(casts, 1200);
    // The cases reach the loop's rounding stops beside the needle (where the resume acts).
    EXPECT_GT(rounding_stops, 20);
    EXPECT_LT(rounding_stops, 1000);
}

// Rays through needles within the points' accuracy range (aspect 1e3 to 1e5), turned and scaled
// at random: a hit no later than the interior point the ray passes, whose point is the ray point at
// toi within (2 tolerance + 1e-6) of the size (the fuzz target's check). After a rounding stop the
// final simplex can lie off the ray point though the shape does not: on a needle of aspect 9e4
// (found by a stress run, the first case) its point was 2.4e-3, 2.3e-6 of the size, from the ray
// point, at a toi where the shape's distance is 0. That case is kept as found; since the loop goes
// on from the hull of its last points after a Johnson failure near the rounding limit
// (cast_loop.hpp) it no longer stops on a rounding rule. Such stops are rare on these needles
// (about 3 in 100,000 rays): the random rays' seed and count take in one (trial 8324, a Johnson
// failure).
TEST(RayCastGraze, HitPointsOnModerateNeedlesAreTheRayPoint) {
    int rays = 0, bad = 0, rounding_stops = 0;
    double worst = 0;
    auto check = [&](const char* what, int trial, const Shape& needle, const Transform& pose, Vec3 from, Vec3 motion,
                     double toi_through, double size) {
        const CastResult r = ray_cast(needle, pose, from, motion, kTol, kMaxIt);
        ++rays;
        if (cast_test::rounding_stop(r.termination)) ++rounding_stops;
        const double off = r.hit ? length(r.point - (from + r.toi * motion)) / size : INFINITY;
        worst = std::fmax(worst, off);
        if (!(r.hit && r.toi <= toi_through + 1e-9 && off <= 2 * kTol + 1e-6) && ++bad <= 10)
            ADD_FAILURE() << what << " " << trial << ": hit " << r.hit << " toi " << r.toi << " (through the needle at "
                          << toi_through << ") termination " << int(r.termination) << ", the point " << off
                          << " of the size from the ray point";
    };
    {
        const std::vector<Vec3> pts = {{-0x1.04454a8b16e16p+7, -0x1.0524f9b931a96p+5, 0x1.0dcf7a68502ffp+8},
                                       {-0x1.c5a406e7e4745p+3, -0x1.c6e77e7de2b47p+1, 0x1.d63ff1edbe225p+4},
                                       {-0x1.163c5ce0c4541p+7, -0x1.172bd217ffffap+5, 0x1.206e6a3b47b4cp+8},
                                       {0x1.cd4584559db73p+6, 0x1.ced2a8072fb8fp+4, -0x1.de299420a0f51p+7},
                                       {-0x1.407c307d3cd63p+6, -0x1.4188dc4440b3ap+4, 0x1.4c382c0aef291p+7},
                                       {-0x1.1accc6ce3f036p+7, -0x1.1bc68bdf5cee6p+5, 0x1.2526608ab0a96p+8},
                                       {-0x1.88a55c83bd56bp+6, -0x1.89f0e0a7e75dcp+4, 0x1.970362038464bp+7},
                                       {0x1.1d67d539695f1p+7, 0x1.1e67306591e8fp+5, -0x1.27dc1c4efc574p+8},
                                       {-0x1.1cda7b735d8aep+7, -0x1.1dd923c11ecaep+5, 0x1.2749bbfa26606p+8},
                                       {-0x1.000880a978679p+5, -0x1.00ecdf976dc72p+3, 0x1.0972fec96d978p+6},
                                       {-0x1.801ac322ca492p+5, -0x1.814a66712eeddp+3, 0x1.8e20c2026e3b7p+6}};
        const Transform pose = make_transform(
            {-0x1.13f08ebeb5aadp+8, 0x1.4e3cc4399347ep+8, 0x1.9bf9b3984d4a1p+6},
            normalized(Quat{-0x1.78e2c6b5a5f8p-1, 0x1.6c7c11047218ep-2, 0x1.4ead9c2f74e77p-2, -0x1.e5549d409d76dp-2}));
        // The ray passes an interior point (a weighted mean of the points) at 0.94114376640525507.
        check("found case", 0, *cast_test::hull_shape(pts), pose,
              {-0x1.a4c6daf071acep+8, 0x1.0f5b58226dc68p+9, -0x1.11e7fc9f3d5c8p+7},
              {0x1.3cb6e6564651dp+5, -0x1.c0e4d1b870785p+7, 0x1.ab145ff0d8ebap+7}, 0.94114376640525507, 1000);
    }
    const uint64_t seed = 1;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 8400; ++trial) {
        const double thin = std::pow(10.0, -5 + 2 * u(rng)), scale = std::pow(10.0, -3 + 6 * u(rng));
        const Vec3 axis = random_unit(rng);
        std::vector<Vec3> pts;
        const int count = 7 + trial % 6;
        for (int k = 0; k < count; ++k) {
            const Vec3 jitter{2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1};
            pts.push_back(scale * (2 * u(rng) - 1) * axis + thin * scale * jitter);
        }
        const Vec3 local_through = interior_point(pts, 0.2, rng);
        const Vec3 offset = scale * Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
        const Transform pose = make_transform(offset, random_quat(rng));
        const Vec3 through = pose.apply(local_through);
        const Vec3 d = random_unit(rng);
        const double reach = scale * (0.5 + 2 * u(rng)), toi_through = 0.3 + 0.7 * u(rng);
        check("seed 1 trial", trial, *cast_test::hull_shape(pts), pose, through + reach * d, (-reach / toi_through) * d,
              toi_through, 2 * scale + reach);
    }
    std::printf("rays through moderate needles: %d, %d ended on a rounding rule, worst point %.3g of the size\n", rays,
                rounding_stops, worst);
    EXPECT_EQ(bad, 0);
    EXPECT_EQ(rays, 8401);
    EXPECT_GE(rounding_stops, 1) << "no ray ends on a rounding rule: the check after one is not exercised";
}
