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

// Scaling a whole scene (every size, position and translation) by a power of two changes no
// rounding, so the queries must give the unit scale's answers, lengths scaled, bit for bit: an
// absolute threshold anywhere in a loop (a constant compared with a length, a square or a volume)
// shows up here as a difference. Eight shape kinds, every ordered pair, random sizes, poses and
// motions; scales 2^-90 .. 2^90 (the loops keep the caller's scale while their first points lie
// within 2^-100 .. 2^100). Beyond, down to 2^-300 and up to 2^300, the loops and the expansion
// each rescale by their own power of two from their first points: distances and casts that do not
// start in contact stay bit for bit; an overlap's depth (the signed distance, a cast's or a
// motion's normal at toi 0) may take another path through the expansion (at 2^-100 a hull in a
// ball took 15 support calls instead of 10 to the same answer), within its accuracy
// (docs/c-api.md).
TEST(Magnitudes, PowerOfTwoScalingGivesTheUnitScaleAnswers) {
    const uint64_t seed = 12002;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    auto u = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    auto quat = [&] {
        const double x = u(-1, 1), y = u(-1, 1), z = u(-1, 1), w = u(-1, 1),
                     n = std::sqrt(x * x + y * y + z * z + w * w);
        return kairos_quat{x / n, y / n, z / n, w / n};
    };
    // Kind k at scale s from the parameters p (sizes first, then hull points).
    auto make = [](int k, double s, const std::vector<double>& p) {
        kairos_shape* out = nullptr;
        Owned part1, part2;
        switch (k) {
            case 0:
                kairos_shape_sphere(s * p[0], &out);
                break;
            case 1:
                kairos_shape_box({s * p[0], s * p[1], s * p[2]}, &out);
                break;
            case 2:
                kairos_shape_capsule(s * p[0], s * p[1], &out);
                break;
            case 3:
                kairos_shape_cylinder(s * p[0], s * p[1], &out);
                break;
            case 4:
                kairos_shape_cone(s * p[0], s * p[1], &out);
                break;
            case 5: {
                std::vector<kairos_vec3> v;
                for (int i = 0; i < 12; ++i) v.push_back({s * p[4 + 3 * i], s * p[5 + 3 * i], s * p[6 + 3 * i]});
                kairos_shape_convex_hull(v.data(), v.size(), &out);
                break;
            }
            case 6:
                kairos_shape_box({s * p[0], s * p[1], s * p[2]}, &part1.s);
                kairos_shape_sphere(s * p[3], &part2.s);
                kairos_shape_minkowski_sum(part1.s, part2.s, &out);
                break;
            default:
                kairos_shape_segment(s * p[0], &out);
        }
        return out;
    };
    auto scaled = [](double s, kairos_vec3 v) { return kairos_vec3{s * v.x, s * v.y, s * v.z}; };
    auto same3 = [](kairos_vec3 a, kairos_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
    auto same_distance = [&](const kairos_distance_result& r, const kairos_distance_result& r0, double s) {
        return r.distance == s * r0.distance && same3(r.point_a, scaled(s, r0.point_a)) &&
               same3(r.point_b, scaled(s, r0.point_b)) && same3(r.axis, r0.axis) && r.intersecting == r0.intersecting &&
               r.iterations == r0.iterations && r.termination == r0.termination;
    };
    auto same_cast = [&](const kairos_cast_result& r, const kairos_cast_result& r0, double s) {
        return r.hit == r0.hit && r.toi == r0.toi && same3(r.point, scaled(s, r0.point)) &&
               same3(r.normal, r0.normal) && r.iterations == r0.iterations && r.termination == r0.termination;
    };
    const int exponents[] = {-90, -61, -7, 9, 60, 90, -300, -200, 200, 300};
    int compared = 0, different = 0, overlaps = 0, hits = 0, motion_hits = 0, off_accuracy = 0;
    for (int trial = 0; trial < 640; ++trial) {
        const int ka = trial % 8, kb = (trial / 8) % 8;
        std::vector<double> pa(40), pb(40);
        for (int i = 0; i < 40; ++i) pa[i] = i < 4 ? u(0.2, 1.5) : u(-1, 1), pb[i] = i < 4 ? u(0.2, 1.5) : u(-1, 1);
        const kairos_pose A{{u(-1, 1), u(-1, 1), u(-1, 1)}, quat()}, B{{u(-3, 3), u(-3, 3), u(-3, 3)}, quat()};
        const kairos_vec3 ta{u(-1, 1), u(-1, 1), u(-1, 1)};
        const kairos_vec3 tb{-B.position.x + u(-1, 1), -B.position.y + u(-1, 1), -B.position.z + u(-1, 1)};
        const kairos_quat turn = quat();
        kairos_distance_result d0{}, sd0{};
        kairos_cast_result c0{}, m0{}, ray0{};
        for (int k = -1; k < 10; ++k) {
            const int e = k < 0 ? 0 : exponents[k];
            const double s = std::ldexp(1.0, e);
            Owned a, b;
            a.s = make(ka, s, pa);
            b.s = make(kb, s, pb);
            ASSERT_TRUE(a.s != nullptr && b.s != nullptr) << kairos_last_error();
            const kairos_pose As{scaled(s, A.position), A.orientation}, Bs{scaled(s, B.position), B.orientation};
            const kairos_vec3 tas = scaled(s, ta), tbs = scaled(s, tb);
            const kairos_motion ma{As, {{As.position.x + tas.x, As.position.y + tas.y, As.position.z + tas.z}, turn}};
            const kairos_motion mb{
                Bs, {{Bs.position.x + tbs.x, Bs.position.y + tbs.y, Bs.position.z + tbs.z}, Bs.orientation}};
            kairos_distance_result d{}, sd{};
            kairos_cast_result c{}, m{}, ray{};
            ASSERT_EQ(kairos_distance(a.s, &As, b.s, &Bs, nullptr, &d), KAIROS_OK) << kairos_last_error();
            ASSERT_EQ(kairos_signed_distance(a.s, &As, b.s, &Bs, nullptr, &sd), KAIROS_OK) << kairos_last_error();
            ASSERT_EQ(kairos_shape_cast(a.s, &As, tas, b.s, &Bs, tbs, nullptr, &c), KAIROS_OK) << kairos_last_error();
            ASSERT_EQ(kairos_motion_cast(a.s, &ma, b.s, &mb, nullptr, &m), KAIROS_OK) << kairos_last_error();
            ASSERT_EQ(kairos_ray_cast(b.s, &Bs, As.position, tas, nullptr, &ray), KAIROS_OK) << kairos_last_error();
            if (k < 0) {
                d0 = d, sd0 = sd, c0 = c, m0 = m, ray0 = ray;
                overlaps += d.intersecting;
                hits += c.hit;
                motion_hits += m.hit;
                continue;
            }
            ++compared;
            const bool exact_range = std::abs(e) <= 90;
            const bool overlap_path = d0.intersecting != 0;
            bool ok = same_distance(d, d0, s) && same_cast(ray, ray0, s);
            if (exact_range || !overlap_path)
                ok = ok && same_distance(sd, sd0, s) && same_cast(c, c0, s) && same_cast(m, m0, s);
            if (!exact_range && overlap_path) {
                // Another path through the expansion: the same verdicts and times, the depth within
                // twice the tolerance of the unit scale's.
                ok = ok && c.hit == c0.hit && c.toi == c0.toi && m.hit == m0.hit && m.toi == m0.toi;
                const bool close = std::fabs(sd.distance / s - sd0.distance) <= 2e-10 * std::fabs(sd0.distance) + 1e-15;
                off_accuracy += !close;
                ok = ok && close;
            }
            if (!ok && ++different <= 10)
                ADD_FAILURE() << "kinds " << ka << "/" << kb << " trial " << trial << " scale 2^" << e << ": distance "
                              << d.distance / s << " vs " << d0.distance << ", signed " << sd.distance / s << " vs "
                              << sd0.distance << ", cast toi " << c.toi << " vs " << c0.toi << " normal.x "
                              << c.normal.x << " vs " << c0.normal.x << ", motion toi " << m.toi << " vs " << m0.toi
                              << " (same: distance " << same_distance(d, d0, s) << ", ray " << same_cast(ray, ray0, s)
                              << ", signed " << same_distance(sd, sd0, s) << ", cast " << same_cast(c, c0, s)
                              << ", motion " << same_cast(m, m0, s) << ")";
        }
    }
    std::printf(
        "power-of-two scaling: %d comparisons, %d differing (%d overlap depths beyond accuracy); at unit scale "
        "%d of 640 overlapping, %d cast hits, %d motion hits\n",
        compared, different, off_accuracy, overlaps, hits, motion_hits);
    EXPECT_EQ(different, 0);
    // Both paths are exercised: overlaps (the expansion) and separated pairs, hits and misses.
    EXPECT_GT(overlaps, 30);
    EXPECT_LT(overlaps, 400);
    EXPECT_GT(hits, 150);
    EXPECT_LT(hits, 620);
    EXPECT_GT(motion_hits, 150);
    EXPECT_LT(motion_hits, 620);
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
