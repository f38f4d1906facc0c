// SPDX-License-Identifier: MIT
// Flat and lower-dimensional shapes (triangles, flat hull polygons, segments and points made as
// hulls) in every query, through the shared library, against closed forms computed here: point to
// triangle distance, ray against triangle, a box dropped onto a triangle, a world with a
// triangle floor, a rod spinning through a triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "kairos/kairos.h"

namespace {

struct V {
    double x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(V a) { return std::sqrt(dot(a, a)); }
kairos_vec3 c(V a) { return {a.x, a.y, a.z}; }
V v(kairos_vec3 a) { return {a.x, a.y, a.z}; }

using Rng = std::mt19937_64;
double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
V random_point(Rng& rng, double r) { return {uniform(rng, -r, r), uniform(rng, -r, r), uniform(rng, -r, r)}; }

kairos_pose at(V p) { return {c(p), {0, 0, 0, 1}}; }

// Distance from p to the segment a-b.
double segment_distance(V p, V a, V b) {
    const V ab = b - a;
    const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    return norm(p - (a + t * ab));
}
// Distance from p to the triangle a, b, c: the plane distance where p projects inside, else the
// nearest side.
double triangle_distance(V p, V a, V b, V cc) {
    const V n = cross(b - a, cc - a);
    const bool inside =
        dot(cross(b - a, p - a), n) >= 0 && dot(cross(cc - b, p - b), n) >= 0 && dot(cross(a - cc, p - cc), n) >= 0;
    if (inside) return std::fabs(dot(p - a, n)) / norm(n);
    return std::min({segment_distance(p, a, b), segment_distance(p, b, cc), segment_distance(p, cc, a)});
}
// Moller-Trumbore: the ray o + t d, t in [0, 1], against triangle a, b, c; t of the hit or -1.
double ray_triangle(V o, V d, V a, V b, V cc) {
    const V e1 = b - a, e2 = cc - a, p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::fabs(det) < 1e-300) return -1;
    const V s = o - a;
    const double u = dot(s, p) / det;
    const V q = cross(s, e1);
    const double w = dot(d, q) / det;
    const double t = dot(e2, q) / det;
    if (u < 0 || w < 0 || u + w > 1 || t < 0 || t > 1) return -1;
    return t;
}

struct Owned {
    kairos_shape* s = nullptr;
    ~Owned() { kairos_shape_release(s); }
};

kairos_query_settings tight() {
    kairos_query_settings q;
    kairos_query_settings_init(&q);
    q.tolerance = 1e-12;
    return q;
}

// Random triangles (from thin slivers to fat ones) against points and small spheres, the triangle
// posed and as either argument: the distance is the closed form's, the closest points are on
// the shapes and |point_b - point_a| is the distance.
TEST(FlatShapes, PointAndSphereToTriangleDistanceMatchesTheClosedForm) {
    const uint64_t seed = 11001;
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    Owned point, ball;
    ASSERT_EQ(kairos_shape_point(&point.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(0.25, &ball.s), KAIROS_OK);
    const kairos_query_settings q = tight();
    int inside_region = 0, touching = 0;
    double worst = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const V a = random_point(rng, 2), b = random_point(rng, 2);
        V cc = random_point(rng, 2);
        if (trial % 4 == 0) cc = 0.5 * (a + b) + uniform(rng, 1e-6, 1e-3) * random_point(rng, 1);  // slivers
        Owned tri;
        if (kairos_shape_triangle(c(a), c(b), c(cc), &tri.s) != KAIROS_OK) continue;
        const V offset = random_point(rng, 50);
        const V p = offset + random_point(rng, 3);
        const double expected = triangle_distance(p - offset, a, b, cc);
        const V n = cross(b - a, cc - a);
        const V rel = p - offset;
        inside_region += dot(cross(b - a, rel - a), n) >= 0 && dot(cross(cc - b, rel - b), n) >= 0 &&
                         dot(cross(a - cc, rel - cc), n) >= 0;
        for (int order = 0; order < 2; ++order) {
            const bool sphere = trial % 2 == 1;
            const kairos_shape* other = sphere ? ball.s : point.s;
            const double want = sphere ? std::max(0.0, expected - 0.25) : expected;
            kairos_pose tri_pose = at(offset), other_pose = at(p);
            kairos_distance_result r;
            const int32_t status = order == 0 ? kairos_distance(tri.s, &tri_pose, other, &other_pose, &q, &r)
                                              : kairos_distance(other, &other_pose, tri.s, &tri_pose, &q, &r);
            ASSERT_EQ(status, KAIROS_OK) << kairos_last_error();
            const double err = std::fabs(r.distance - want);
            worst = std::max(worst, err);
            ASSERT_LE(err, 1e-9) << "trial " << trial << " order " << order;
            touching += want == 0;
            if (want > 0) {
                ASSERT_NEAR(norm(v(r.point_b) - v(r.point_a)), r.distance, 1e-9);
            }
        }
    }
    std::printf("[   INFO   ] point/triangle distance: max error %.3g\n", worst);
    EXPECT_GT(inside_region, 100);  // both the face and the edge regions are exercised
    EXPECT_LT(inside_region, 3600);
    EXPECT_GT(touching, 10);
}

// Rays against random triangles: hit or miss as Moller-Trumbore says (rays within 1e-9 of an edge
// are not judged), the time within 1e-9, the normal the plane's, facing the ray.
TEST(FlatShapes, RayAgainstTriangleMatchesMollerTrumbore) {
    const uint64_t seed = 11002;
    SCOPED_TRACE("seed " + std::to_string(seed));
    Rng rng(seed);
    const kairos_query_settings q = tight();
    int hits = 0, judged = 0;
    for (int trial = 0; trial < 5000; ++trial) {
        const V a = random_point(rng, 1), b = random_point(rng, 1), cc = random_point(rng, 1);
        Owned tri;
        if (kairos_shape_triangle(c(a), c(b), c(cc), &tri.s) != KAIROS_OK) continue;
        const V o = random_point(rng, 3), target = random_point(rng, 0.8);
        const V d = 1.5 * (target - o);
        const double t = ray_triangle(o, d, a, b, cc);
        // Not judged: rays grazing an edge or the plane's boundary, where rounding decides.
        const V n = cross(b - a, cc - a);
        bool near_edge = false;
        if (std::fabs(dot(d, n)) > 1e-9 * norm(d) * norm(n)) {
            const double s = dot(a - o, n) / dot(d, n);
            const V x = o + s * d;
            near_edge =
                std::min({segment_distance(x, a, b), segment_distance(x, b, cc), segment_distance(x, cc, a)}) < 1e-9 ||
                std::fabs(s - 1) < 1e-9;
        } else {
            near_edge = true;
        }
        if (near_edge) continue;
        ++judged;
        kairos_cast_result r;
        ASSERT_EQ(kairos_ray_cast(tri.s, nullptr, c(o), c(d), &q, &r), KAIROS_OK);
        ASSERT_EQ(r.hit != 0, t >= 0) << "trial " << trial << ": expected t " << t;
        if (t < 0) continue;
        ++hits;
        ASSERT_NEAR(r.toi, t, 1e-9);
        const V unit_n = (1 / norm(n)) * n;
        ASSERT_NEAR(std::fabs(dot(v(r.normal), unit_n)), 1.0, 1e-6);
        ASSERT_LT(dot(v(r.normal), d), 0);
        ASSERT_LT(norm(v(r.point) - (o + t * d)), 1e-8);
    }
    EXPECT_GT(hits, judged / 10);
    EXPECT_LT(hits, judged * 9 / 10);
}

// A flat square made by kairos_shape_convex_hull from coplanar points (with one inside) is a floor:
// a box dropped onto it, tilted floor and all, hits when its lowest corner reaches the floor.
TEST(FlatShapes, BoxDroppedOntoAFlatHullSquare) {
    const kairos_vec3 square[5] = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, {0.3, 0.1, 0}};
    Owned floor, box;
    ASSERT_EQ(kairos_shape_convex_hull(square, 5, &floor.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box({0.5, 0.5, 0.5}, &box.s), KAIROS_OK);
    kairos_vec3 lo, hi;
    ASSERT_EQ(kairos_shape_bounds(floor.s, nullptr, &lo, &hi), KAIROS_OK);
    EXPECT_EQ(lo.z, 0);
    EXPECT_EQ(hi.z, 0);
    const kairos_query_settings q = tight();
    for (double height : {3.0, 1.0 + 1e-9, 0.5 + 1e-12}) {
        kairos_pose box_pose = at({0.7, -0.4, height}), floor_pose = at({0, 0, 0});
        kairos_cast_result r;
        // Box A falls by 4, the floor B stays: contact when the box's bottom (height - 0.5) is 0.
        ASSERT_EQ(kairos_shape_cast(box.s, &box_pose, {0, 0, -4}, floor.s, &floor_pose, {0, 0, 0}, &q, &r), KAIROS_OK);
        ASSERT_EQ(r.hit, 1);
        EXPECT_NEAR(r.toi, (height - 0.5) / 4, 1e-12);
        EXPECT_NEAR(r.normal.z, -1, 1e-9);  // from A (the box, above) toward B (the floor)
        // Either order.
        ASSERT_EQ(kairos_shape_cast(floor.s, &floor_pose, {0, 0, 0}, box.s, &box_pose, {0, 0, -4}, &q, &r), KAIROS_OK);
        ASSERT_EQ(r.hit, 1);
        EXPECT_NEAR(r.toi, (height - 0.5) / 4, 1e-12);
        EXPECT_NEAR(r.normal.z, 1, 1e-9);
    }
    // Past the edge of the square it misses.
    kairos_pose box_pose = at({3, 0, 3}), floor_pose = at({0, 0, 0});
    kairos_cast_result r;
    ASSERT_EQ(kairos_shape_cast(box.s, &box_pose, {0, 0, -4}, floor.s, &floor_pose, {0, 0, 0}, &q, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 0);
}

// Segments and points made as hulls measure like the segment and point primitives.
TEST(FlatShapes, CollinearAndSinglePointHullsAgainstClosedForms) {
    const kairos_vec3 line[4] = {{0, 0, -1}, {0, 0, 0.25}, {0, 0, 1}, {0, 0, 0.5}};
    const kairos_vec3 one[3] = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
    Owned seg, pt, probe;
    ASSERT_EQ(kairos_shape_convex_hull(line, 4, &seg.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_convex_hull(one, 3, &pt.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_point(&probe.s), KAIROS_OK);
    const kairos_query_settings q = tight();
    Rng rng(11003);
    for (int trial = 0; trial < 500; ++trial) {
        const V p = random_point(rng, 3);
        kairos_pose pp = at(p);
        kairos_distance_result r;
        ASSERT_EQ(kairos_distance(seg.s, nullptr, probe.s, &pp, &q, &r), KAIROS_OK);
        EXPECT_NEAR(r.distance, segment_distance(p, {0, 0, -1}, {0, 0, 1}), 1e-12);
        ASSERT_EQ(kairos_distance(probe.s, &pp, pt.s, nullptr, &q, &r), KAIROS_OK);
        EXPECT_NEAR(r.distance, norm(p - V{1, 2, 3}), 1e-12);
    }
}

// A world with a static triangle floor (and a flat hull polygon): a falling sphere reports its
// contact at the closed-form time, with the floor's normal; a rod spinning through a triangle
// (no translation at all) is found by the motion cast.
TEST(FlatShapes, TriangleFloorInAWorldAndASpinningRod) {
    Owned tri, ball, rod;
    ASSERT_EQ(kairos_shape_triangle({-5, -5, 0}, {5, -5, 0}, {0, 5, 0}, &tri.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(0.5, &ball.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_segment(1.0, &rod.s), KAIROS_OK);
    for (int32_t bp :
         {KAIROS_BROAD_PHASE_SPACETIME_SAP, KAIROS_BROAD_PHASE_ENCAPSULATING_SAP, KAIROS_BROAD_PHASE_BRUTE_FORCE}) {
        SCOPED_TRACE(bp);
        kairos_world_settings s;
        kairos_world_settings_init(&s);
        s.broad_phase = bp;
        s.query.tolerance = 1e-12;
        kairos_world* w = nullptr;
        ASSERT_EQ(kairos_world_create(&s, &w), KAIROS_OK);
        kairos_object_id floor_id = 0, ball_id = 0;
        kairos_pose p = at({0, 0, 0});
        ASSERT_EQ(kairos_world_add(w, tri.s, &p, 1, &floor_id), KAIROS_OK);
        p = at({0.5, 0.2, 2});
        ASSERT_EQ(kairos_world_add(w, ball.s, &p, 2, &ball_id), KAIROS_OK);
        p = at({0.5, 0.2, -2});  // straight through the floor within one step
        ASSERT_EQ(kairos_world_move(w, ball_id, &p), KAIROS_OK);
        ASSERT_EQ(kairos_world_step(w), KAIROS_OK);
        const kairos_contact* cs = nullptr;
        size_t n = 0;
        ASSERT_EQ(kairos_world_contacts(w, &cs, &n), KAIROS_OK);
        ASSERT_EQ(n, 1u);
        EXPECT_EQ(cs[0].a, floor_id);
        EXPECT_NEAR(cs[0].toi, 1.5 / 4, 1e-9);
        EXPECT_NEAR(cs[0].normal.z, 1, 1e-6);  // from the floor (a) toward the ball (b)
        kairos_world_destroy(w);
    }
    // The rod's centre sits 0.5 above the triangle's plane; a quarter turn about x brings its
    // lower end down through it at 30 degrees (sin 30 = 0.5): t = 1/3 of the turn.
    // The rod starts lying along y (a quarter turn about x) and ends upright.
    const kairos_motion rod_motion{{{0, 0, 0.5}, {std::sin(M_PI / 4), 0, 0, std::cos(M_PI / 4)}},
                                   {{0, 0, 0.5}, {0, 0, 0, 1}}};
    const kairos_motion still{{{0, 0, 0}, {0, 0, 0, 1}}, {{0, 0, 0}, {0, 0, 0, 1}}};
    const kairos_query_settings q = tight();
    kairos_cast_result r;
    ASSERT_EQ(kairos_motion_cast(tri.s, &still, rod.s, &rod_motion, &q, &r), KAIROS_OK);
    ASSERT_EQ(r.hit, 1);
    EXPECT_NEAR(r.toi, 1.0 / 3.0, 1e-6);
    EXPECT_LE(r.toi, 1.0 / 3.0 + 1e-12);  // never late
}

}  // namespace

namespace {

// Outside the axis-aligned box of centre cc and half extents h by how much (<= 0: inside).
double box_excess(V p, V cc, V h) {
    const V d = p - cc;
    return std::max({std::fabs(d.x) - h.x, std::fabs(d.y) - h.y, std::fabs(d.z) - h.z});
}

}  // namespace

// The fuzzer's finding of 2026-11-27 (tests/fuzz/findings/fuzz_queries-distance_flat_boxes_witness_point.bin):
// two boxes 1.7e-8 and 2e-9 thick lying in one plane, overlapping. A - B is a slab; Johnson's
// determinants accepted a sliver triangle of it whose plane passed through the origin while the
// triangle did not, so kairos_distance said touching (NEAR_CONTACT) with a contact point 10 outside
// B. Here: slabs 1e-10 .. 1e-6 thick (faces parallel, the thin axis z), B's footprint inside A's
// in x and y (half the cases with A's width and centre in y, as in the finding), their faces g
// apart (g = -(ta + tb): one mid-plane), both orders. Truth: the gap g. Checks: the distance
// within 1e-9 of the size (the band where touching may read either way), witness points in their
// boxes, a distance apart when apart, the contact point in both boxes when not.
TEST(FlatShapes, ThinSlabsInOnePlaneGiveWitnessPointsInTheBoxes) {
    const uint64_t seed = 20261127;
    Rng rng(seed);
    int intersecting = 0, separated = 0, cases = 0;
    for (int i = 0; i < 3000; ++i) {
        const double ta = std::pow(10.0, -uniform(rng, 6, 10)), tb = std::pow(10.0, -uniform(rng, 6, 10));
        // Every other six cases, equal widths in y and one y centre (the finding's support ties).
        const bool tied = (i / 6) % 2 == 0;
        const V ha{uniform(rng, 2, 10), uniform(rng, 0.5, 2), ta};
        const V hb{uniform(rng, 0.2, 1.5), tied ? ha.y : uniform(rng, 0.2, 0.5), tb};
        const double gaps[] = {-(ta + tb), -std::min(ta, tb), -1e-12, 1e-12, 1e-9, 1e-6};
        const double g = gaps[i % 6];
        const V ca = random_point(rng, 5);
        const V cb = ca + V{uniform(rng, hb.x - ha.x, ha.x - hb.x), tied ? 0.0 : uniform(rng, -0.1, 0.1),
                            (i & 1 ? 1 : -1) * (ta + tb + g)};
        kairos_shape *a = nullptr, *b = nullptr;
        ASSERT_EQ(kairos_shape_box(c(ha), &a), KAIROS_OK);
        ASSERT_EQ(kairos_shape_box(c(hb), &b), KAIROS_OK);
        const kairos_pose pa = at(ca), pb = at(cb);
        const double size = norm(ha) + norm(hb), tol = 1e-9 * size;
        for (int order = 0; order < 2; ++order) {
            SCOPED_TRACE(testing::Message() << "seed " << seed << " case " << i << " order " << order << " gap " << g);
            kairos_distance_result r{};
            ASSERT_EQ(order == 0 ? kairos_distance(a, &pa, b, &pb, nullptr, &r) : kairos_distance(b, &pb, a, &pa, nullptr, &r),
                      KAIROS_OK);
            ++cases;
            const V qa = v(order == 0 ? r.point_a : r.point_b), qb = v(order == 0 ? r.point_b : r.point_a);
            EXPECT_NEAR(r.distance, std::max(g, 0.0), tol) << "termination " << r.termination;
            EXPECT_LE(box_excess(qa, ca, ha), tol) << "termination " << r.termination;
            EXPECT_LE(box_excess(qb, cb, hb), tol) << "termination " << r.termination;
            if (r.intersecting) {
                ++intersecting;
                EXPECT_LE(box_excess(qa, cb, hb), tol) << "contact point outside B";
            } else {
                ++separated;
                EXPECT_NEAR(norm(qb - qa), r.distance, tol);
            }
        }
        kairos_shape_release(a);
        kairos_shape_release(b);
    }
    std::printf("[thin slabs] %d queries: %d intersecting, %d separated\n", cases, intersecting, separated);
    EXPECT_GT(intersecting, cases / 10);
    EXPECT_GT(separated, cases / 5);
}
