// SPDX-License-Identifier: MIT
// Contract regressions through the shared library (issue 11): finite inputs near the double range
// never give NaN (a refusal naming the input instead), and kairos_motion_cast keeps its documented
// gap bound at every tolerance, translation-only motions included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "kairos/kairos.h"

namespace {

bool finite3(kairos_vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

struct Owned {
    kairos_shape* s = nullptr;
    ~Owned() { kairos_shape_release(s); }
};

kairos_pose at(double x, double y, double z) { return {{x, y, z}, {0, 0, 0, 1}}; }

// The case: a hull cast with a huge, finite translation used to return hit, toi 0 and a
// NaN point. Now the translation is refused by name and the output is untouched.
TEST(Magnitudes, HugeTranslationIsRefusedByName) {
    const kairos_vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Owned hull;
    ASSERT_EQ(kairos_shape_convex_hull(corners, 4, &hull.s), KAIROS_OK);
    kairos_cast_result out;
    std::memset(&out, 0xAB, sizeof out);
    kairos_cast_result before;
    std::memcpy(&before, &out, sizeof out);
    const kairos_pose pa = at(0, 0, 0), pb = at(5, 0, 0);
    EXPECT_EQ(kairos_shape_cast(hull.s, &pa, {1e300, 0, 0}, hull.s, &pb, {0, 0, 0}, nullptr, &out),
              KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(kairos_last_error()).find("translation_a.x"), std::string::npos) << kairos_last_error();
    EXPECT_EQ(std::memcmp(&out, &before, sizeof out), 0);
    EXPECT_EQ(kairos_ray_cast(hull.s, nullptr, {0, 0, -1e200}, {0, 0, 1}, nullptr, &out),
              KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(kairos_last_error()).find("origin.z"), std::string::npos) << kairos_last_error();
    const kairos_pose far = at(0, -1e101, 0);
    kairos_distance_result d;
    EXPECT_EQ(kairos_distance(hull.s, &far, hull.s, nullptr, nullptr, &d), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(kairos_last_error()).find("pose_a.position.y"), std::string::npos) << kairos_last_error();
}

// Composites whose points reach beyond KAIROS_MAX_MAGNITUDE are refused, and no reference leaks.
TEST(Magnitudes, CompositesBeyondTheLimitAreRefused) {
    Owned big, small;
    ASSERT_EQ(kairos_shape_box({0.6e100, 1, 1}, &big.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(1, &small.s), KAIROS_OK);
    kairos_shape* out = nullptr;
    EXPECT_EQ(kairos_shape_minkowski_sum(big.s, big.s, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(kairos_last_error()).find("a + b"), std::string::npos);
    EXPECT_EQ(out, nullptr);
    const double scale[9] = {1e60, 0, 0, 0, 1e60, 0, 0, 0, 1e60};
    EXPECT_EQ(kairos_shape_transformed(big.s, scale, {0, 0, 0}, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(kairos_shape_transformed(small.s, scale, {0, 0, 0}, &out), KAIROS_OK);  // 1e60: fine
    kairos_shape_release(out);
    out = nullptr;
    EXPECT_EQ(kairos_shape_box({2e100, 1, 1}, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(out, nullptr);
}

// Every query at scales from 1e-100 to the limit, positions as far as the limit allows: status OK
// and every number finite (the distance query's and the casts'), or a refusal; never NaN.
TEST(Magnitudes, EveryQueryAtEveryScaleIsFinite) {
    const uint64_t seed = 12001;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(-1, 1);
    int ok = 0;
    for (int e = -100; e <= 99; e += 3) {
        const double s = std::pow(10.0, e);
        Owned box, ball, hull;
        ASSERT_EQ(kairos_shape_box({s, 0.5 * s, 0.25 * s}, &box.s), KAIROS_OK);
        ASSERT_EQ(kairos_shape_sphere(s, &ball.s), KAIROS_OK);
        std::vector<kairos_vec3> pts;
        for (int k = 0; k < 12; ++k) pts.push_back({s * unit(rng), s * unit(rng), s * unit(rng)});
        ASSERT_EQ(kairos_shape_convex_hull(pts.data(), pts.size(), &hull.s), KAIROS_OK);
        const kairos_shape* shapes[3] = {box.s, ball.s, hull.s};
        for (int trial = 0; trial < 20; ++trial) {
            const kairos_shape* a = shapes[trial % 3];
            const kairos_shape* b = shapes[(trial / 3) % 3];
            // Positions up to 4 s apart, offset from the origin by up to the limit / 4.
            const double off = trial % 2 ? 0.25 * KAIROS_MAX_MAGNITUDE * unit(rng) : 0;
            const kairos_pose pa = at(off + 4 * s * unit(rng), off, off);
            const kairos_pose pb = at(off + 4 * s * unit(rng), off + s * unit(rng), off);
            const kairos_vec3 ta{std::min(4 * s, 0.25 * KAIROS_MAX_MAGNITUDE) * unit(rng), 0, 0};
            kairos_distance_result d;
            int32_t status = kairos_distance(a, &pa, b, &pb, nullptr, &d);
            ASSERT_TRUE(status == KAIROS_OK || status == KAIROS_ERROR_INVALID_ARGUMENT) << kairos_status_name(status);
            if (status == KAIROS_OK) {
                ++ok;
                ASSERT_TRUE(std::isfinite(d.distance) && finite3(d.point_a) && finite3(d.point_b) && finite3(d.axis))
                    << "scale 1e" << e;
                ASSERT_GE(d.distance, 0);
            }
            kairos_cast_result r;
            status = kairos_shape_cast(a, &pa, ta, b, &pb, {0, 0, 0}, nullptr, &r);
            ASSERT_TRUE(status == KAIROS_OK || status == KAIROS_ERROR_INVALID_ARGUMENT);
            if (status == KAIROS_OK) {
                ASSERT_TRUE(std::isfinite(r.toi) && finite3(r.point) && finite3(r.normal)) << "scale 1e" << e;
            }
            const kairos_motion ma{
                pa, {{pa.position.x + ta.x, pa.position.y, pa.position.z}, {0, 0, std::sqrt(0.5), std::sqrt(0.5)}}};
            const kairos_motion mb{pb, pb};
            status = kairos_motion_cast(a, &ma, b, &mb, nullptr, &r);
            ASSERT_TRUE(status == KAIROS_OK || status == KAIROS_ERROR_INVALID_ARGUMENT);
            if (status == KAIROS_OK) {
                ASSERT_TRUE(std::isfinite(r.toi) && finite3(r.point) && finite3(r.normal)) << "scale 1e" << e;
            }
            status = kairos_ray_cast(a, &pa, pb.position, ta, nullptr, &r);
            ASSERT_TRUE(status == KAIROS_OK || status == KAIROS_ERROR_INVALID_ARGUMENT);
            if (status == KAIROS_OK) {
                ASSERT_TRUE(std::isfinite(r.toi) && finite3(r.point) && finite3(r.normal)) << "scale 1e" << e;
            }
        }
    }
    EXPECT_GT(ok, 1000);  // within the limits every query answers
}

// Regression (fuzzer): a triangle 4e-4 thick moved 1e15 away, at a slightly turned pose: the z
// range came back with min > max (two supports, each rounded at 1e15 with ulp 0.125).
TEST(Magnitudes, BoundsOfAFlatShapeFarAwayAreOrdered) {
    const kairos_vec3 corners[3] = {{1.7316338444847723, -72.489093712961605, 0.062259943263133145},
                                    {30.486359147260803, 89.340274662267035, 0.062640718247545968},
                                    {15.696015592689774, 10.428587958854427, 0.062455043690596505}};
    const double linear[9] = {1, 0, 0, 0, 1, 1.5609979400320384e-16, 1.17647058823529e-16, 0, 1};
    Owned triangle, moved;
    ASSERT_EQ(kairos_shape_convex_hull(corners, 3, &triangle.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_transformed(triangle.s, linear, {1e15, 1e15, 1e15}, &moved.s), KAIROS_OK);
    const kairos_pose pose = {{9.2941176470588236e-191, -3.5576409552147701e-191, 9.6078431372549014e-191},
                              {-0.0001, 0, 0, 1}};
    kairos_vec3 lo, hi;
    ASSERT_EQ(kairos_shape_bounds(moved.s, &pose, &lo, &hi), KAIROS_OK);
    EXPECT_LE(lo.x, hi.x);
    EXPECT_LE(lo.y, hi.y);
    EXPECT_LE(lo.z, hi.z);
}

// Regression (fuzzer): a rounded hull (hull + sphere) around a sphere's centre: GJK stopped on no
// progress with the cores a rounding inside the sum of the radii, and reported distance 0, not
// intersecting, with witness points 0.26 apart. Distance 0 now means intersecting with one point.
TEST(DistanceContract, ZeroDistanceIsAnIntersectionWithOnePoint) {
    const kairos_vec3 p[5] = {{-1, -2, -2}, {-2, -2, -1}, {-1, -2, 0}, {-2, -2, -2}, {-2, 0, -2}};
    Owned hull, ball, rounded;
    ASSERT_EQ(kairos_shape_convex_hull(p, 5, &hull.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(1, &ball.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_minkowski_sum(hull.s, ball.s, &rounded.s), KAIROS_OK);
    const kairos_pose pose = at(-4, -4, -4);
    for (int order = 0; order < 2; ++order) {
        kairos_distance_result r;
        ASSERT_EQ(order == 0 ? kairos_distance(rounded.s, &pose, ball.s, &pose, nullptr, &r)
                             : kairos_distance(ball.s, &pose, rounded.s, &pose, nullptr, &r),
                  KAIROS_OK);
        EXPECT_EQ(r.distance, 0) << "order " << order;
        EXPECT_EQ(r.intersecting, 1) << "order " << order;
        EXPECT_EQ(std::memcmp(&r.point_a, &r.point_b, sizeof r.point_a), 0) << "order " << order;
    }
}

// Regression (fuzzer): two spheres, the cast stopped by max_iterations = 2 short of contact, or by
// tolerance 0.25 far from it, reported a normal along the last search direction, not opposing
// the relative motion.
TEST(CastContract, GuardStoppedHitStillOpposesTheMotion) {
    Owned ball;
    ASSERT_EQ(kairos_shape_sphere(1, &ball.s), KAIROS_OK);
    const kairos_pose pa = {{-3.456656748302434, -3.988891432059205, -0.031189440756847375}, {0, 1, 0, 0}},
                      pb = at(0, 0, 0);
    const kairos_vec3 r{-2.4998855573357748, -9.9853513389791715, 2.5014114595254444};
    kairos_query_settings q;
    kairos_query_settings_init(&q);
    for (uint32_t m = 1; m <= 8; ++m) {
        q.max_iterations = m;
        kairos_cast_result c;
        ASSERT_EQ(kairos_shape_cast(ball.s, &pa, {0, 0, 0}, ball.s, &pb, r, &q, &c), KAIROS_OK);
        if (!c.hit) continue;
        EXPECT_LT(c.normal.x * r.x + c.normal.y * r.y + c.normal.z * r.z, 0) << "max_iterations " << m;
    }
    // The same at coarse tolerances: the cast stops far from contact (0.25 stopped at toi 0.448).
    q.max_iterations = 256;
    for (double tol : {0.9, 0.5, 0.25, 0.1}) {
        q.tolerance = tol;
        kairos_cast_result c;
        ASSERT_EQ(kairos_shape_cast(ball.s, &pa, {0, 0, 0}, ball.s, &pb, r, &q, &c), KAIROS_OK);
        if (!c.hit) continue;
        EXPECT_LT(c.normal.x * r.x + c.normal.y * r.y + c.normal.z * r.z, 0) << "tolerance " << tol;
    }
}

// ---- kairos_motion_cast: the gap at a reported hit ---------------------------------------------

struct Q {
    double x, y, z, w;
};
Q mul(Q a, Q b) {
    return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
// The orientation a fraction t along the shortest arc from a to b (constant angular velocity).
kairos_quat slerp(kairos_quat qa, kairos_quat qb, double t) {
    Q a{qa.x, qa.y, qa.z, qa.w}, b{qb.x, qb.y, qb.z, qb.w};
    if (a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w < 0) b = {-b.x, -b.y, -b.z, -b.w};
    const Q rel = mul({-a.x, -a.y, -a.z, a.w}, b);  // a^-1 b
    const double s = std::sqrt(rel.x * rel.x + rel.y * rel.y + rel.z * rel.z);
    const double angle = 2 * std::atan2(s, rel.w);
    if (s == 0) return qa;
    const double h = 0.5 * angle * t;
    const Q step{rel.x / s * std::sin(h), rel.y / s * std::sin(h), rel.z / s * std::sin(h), std::cos(h)};
    const Q q = mul(a, step);
    return {q.x, q.y, q.z, q.w};
}
kairos_pose pose_at(const kairos_motion& m, double t) {
    const kairos_vec3 p0 = m.start.position, p1 = m.end.position;
    return {{p0.x + t * (p1.x - p0.x), p0.y + t * (p1.y - p0.y), p0.z + t * (p1.z - p0.z)},
            slerp(m.start.orientation, m.end.orientation, t)};
}
kairos_quat random_quat(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    double q[4] = {g(rng), g(rng), g(rng), g(rng)};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    return {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
}
// The documented radius: origin to the farthest corner of the local bounding box.
double corner_radius(const kairos_shape* s) {
    kairos_vec3 lo, hi;
    EXPECT_EQ(kairos_shape_bounds(s, nullptr, &lo, &hi), KAIROS_OK);
    const double x = std::max(-lo.x, hi.x), y = std::max(-lo.y, hi.y), z = std::max(-lo.z, hi.z);
    return std::sqrt(x * x + y * y + z * z);
}

// Regression (issue 11, finding 6): a translation-only motion cast at tolerance 0.1 reported a hit
// with the shapes 0.1318 apart where the bound was 0.1146. Random polytope pairs, translating and
// turning, at every tolerance from 1e-1 to 1e-12: at a hit the shapes are within
// tolerance * min(rA, rB) (plus 1e-12 of the size for the final measurement).
TEST(MotionCastBound, GapAtAHitIsWithinToleranceTimesTheSmallerRadius) {
    const uint64_t seed = 12002;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(-1, 1);
    Owned box, slab, hull;
    ASSERT_EQ(kairos_shape_box({0.5, 0.3, 0.2}, &box.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box({2, 2, 0.05}, &slab.s), KAIROS_OK);
    std::vector<kairos_vec3> pts;
    for (int k = 0; k < 16; ++k) pts.push_back({0.7 * unit(rng), 0.7 * unit(rng), 0.7 * unit(rng)});
    ASSERT_EQ(kairos_shape_convex_hull(pts.data(), pts.size(), &hull.s), KAIROS_OK);
    const kairos_shape* shapes[3] = {box.s, slab.s, hull.s};
    kairos_query_settings exact;
    kairos_query_settings_init(&exact);
    exact.tolerance = 1e-13;
    for (int k = 1; k <= 12; ++k) {
        const double tol = std::pow(10.0, -k);
        kairos_query_settings q;
        kairos_query_settings_init(&q);
        q.tolerance = tol;
        int hits = 0, casts = 0;
        double worst_ratio = 0;
        for (int trial = 0; trial < 300; ++trial) {
            const kairos_shape* a = shapes[trial % 3];
            const kairos_shape* b = shapes[(trial / 3) % 3];
            const bool turning = trial % 2 == 1;
            const kairos_quat qa = random_quat(rng), qb = random_quat(rng);
            kairos_motion ma{{{0, 0, 0}, qa}, {{0, 0, 0}, turning ? random_quat(rng) : qa}};
            kairos_motion mb{{{4 * unit(rng), 4 * unit(rng), 4 * unit(rng)}, qb},
                             {{unit(rng), unit(rng), unit(rng)}, qb}};
            if (turning) mb.end.orientation = random_quat(rng);
            kairos_cast_result r;
            ASSERT_EQ(kairos_motion_cast(a, &ma, b, &mb, &q, &r), KAIROS_OK) << kairos_last_error();
            ++casts;
            if (!r.hit || r.toi == 0 || r.termination != KAIROS_TERMINATION_HIT) continue;
            ++hits;
            const kairos_pose pa = pose_at(ma, r.toi), pb = pose_at(mb, r.toi);
            kairos_distance_result d;
            ASSERT_EQ(kairos_distance(a, &pa, b, &pb, &exact, &d), KAIROS_OK);
            const double size = std::min(corner_radius(a), corner_radius(b));
            const double bound = tol * size;
            worst_ratio = std::max(worst_ratio, d.distance / bound);
            ASSERT_LE(d.distance, bound + 1e-12 * size)
                << "tolerance " << tol << ", trial " << trial << (turning ? " (turning)" : " (translating)") << ": gap "
                << d.distance << " > " << bound;
        }
        std::printf("[   INFO   ] tolerance %.0e: %d hits of %d casts, largest gap / bound %.3f\n", tol, hits, casts,
                    worst_ratio);
        EXPECT_GT(hits, casts / 5);
        EXPECT_LT(hits, casts);
    }
}

}  // namespace
