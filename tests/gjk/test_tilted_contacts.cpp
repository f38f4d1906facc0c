// SPDX-License-Identifier: MIT
// Flat bottoms on a box's face, tilted by 0 to 1e-3 rad about random axes: a box, a cylinder and a
// cone standing on a large box, a capsule lying on it, a box rounded by a ball and a box as a hull
// (with points in its bottom face's edges), and a rounded box on a rounded base with their box cores
// at the gap (the rounded shapes then overlap by the radii: the cores decide), their lowest
// point at gaps from -1e-2 to 1e-2 of the size, touching, 1e-12 apart or inside, shifted sideways
// on the face, with their edges parallel to the face's or turned, sizes 1e-4 to 1e4, 1 or 1e4 of
// the size from the origin, both argument orders. Nearly parallel faces make A - B a slab of nearly coplanar facets,
// where GJK's rounding stops live: boxes tilted by 1e-9, 1e-12 apart at one end, were reported
// 2e-11 apart while a vertex lay 1.2e-10 inside (algorithms.md §2). Truth, in long double from
// the doubles the queries see: the height of the standing shape's lowest point over the face (a
// box's lowest vertex; the lowest point of a cylinder's or a cone's bottom rim; the capsule's lower
// end, the rounded box's lowest vertex, less the radius; for the rounded pair, the core's lowest
// vertex less both radii). The lowest point stays well inside the
// face, so the distance is that height when positive, and when negative the depth is minus it
// along the face's normal: tilting the axis by phi adds about phi times the face's half width to
// A's extent and removes at most phi times the lowest point's offset.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "../support/gjk_test_support.hpp"
#include "../support/oracle/polytope_oracle.hpp"
#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using gjk_test::random_quat;
using gjk_test::random_unit;
using oracle::P3;
using oracle::Real;

namespace {

P3 lift(Vec3 v) { return {v.x, v.y, v.z}; }
// pose applied to a local point, in long double.
P3 place(const Transform& pose, P3 x) {
    const Vec3* r = pose.rotation.r;
    return {Real(r[0].x) * x.x + Real(r[0].y) * x.y + Real(r[0].z) * x.z + Real(pose.translation.x),
            Real(r[1].x) * x.x + Real(r[1].y) * x.y + Real(r[1].z) * x.z + Real(pose.translation.y),
            Real(r[2].x) * x.x + Real(r[2].y) * x.y + Real(r[2].z) * x.z + Real(pose.translation.z)};
}

}  // namespace

TEST(TiltedContacts, FlatBottomsOnABoxFaceAtEveryTilt) {
    const uint64_t seed = 2821;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double tilts[] = {0, 1e-12, 1e-9, 1e-6, 1e-3};
    const double gaps[] = {-1e-2, -1e-6, -1e-9, -1e-12, 0, 1e-12, 1e-9, 1e-6, 1e-2};
    const char* names[] = {"box", "cylinder", "cone", "capsule", "rounded box", "hull", "rounded pair"};
    constexpr int kinds = 7;
    int cases = 0, failures = 0, overlapping = 0, core_overlapping = 0;
    double worst[kinds] = {};
    for (const double size : {1e-4, 1.0, 1e4})
        for (double far : {1.0, 1e4}) {
            for (int i = 0; i < kinds * 5 * 9 * 8; ++i) {
                const int kind = i % kinds;
                const double tilt = tilts[i / kinds % 5], gap = size * gaps[i / (kinds * 5) % 9];
                const Vec3 base_half = size * Vec3{3, 3, 0.5};
                BoxShape base_box(base_half);
                // The rounded pair's base: the box rounded by a ball (its core's face is the face).
                SphereShape base_ball(0.25 * size);
                MinkowskiSumShape rounded_base(base_box, base_ball);
                const Shape& base = kind == 6 ? static_cast<const Shape&>(rounded_base) : base_box;
                const Vec3 half = size * Vec3{0.2 + 0.8 * std::fabs(u(rng)), 0.2 + 0.8 * std::fabs(u(rng)),
                                              0.2 + 0.8 * std::fabs(u(rng))};
                BoxShape box(half);
                CylinderShape cylinder(half.x, half.z);
                ConeShape cone(half.x, half.z);
                // A capsule lying on the face (its axis across the normal), a box rounded by a ball.
                const double radius = 0.3 * std::min({half.x, half.y, half.z});
                CapsuleShape capsule(radius, half.z);
                BoxShape core(half);
                SphereShape ball(radius);
                MinkowskiSumShape rounded(core, ball);
                // The box as a hull, with the midpoints of its bottom edges: coplanar points on the face.
                gjk_test::Verts points = gjk_test::box_vertices(half);
                for (const auto& m : {std::array<double, 3>{0, -half.y, -half.z},
                                      {0, half.y, -half.z},
                                      {-half.x, 0, -half.z},
                                      {half.x, 0, -half.z}})
                    points.push_back(m);
                const gjk_test::ShapePtr hull = gjk_test::hull(points);
                const Shape* tops[] = {&box, &cylinder, &cone, &capsule, &rounded, hull.get(), &rounded};
                const Shape& top = *tops[kind];
                const Transform pa = make_transform(far * size * Vec3{u(rng), u(rng), u(rng)}, random_quat(rng));
                const Vec3 n = pa.rotation.col(2);  // the base's top face normal (world)
                // The top's frame: the base's (edges parallel to the base's: the more nearly coplanar
                // facets), or turned about its normal, then tilted about a random axis.
                const double turn = i / (kinds * 45) % 2 == 0 ? 0.0 : 3.0 * u(rng);
                const Mat3 spin = to_matrix(axis_angle(n, turn));
                const Mat3 lying = to_matrix(axis_angle({1, 0, 0}, kind == 3 ? 1.5707963267948966 : 0.0));
                const Mat3 rt = to_matrix(axis_angle(random_unit(rng), tilt)) * spin * pa.rotation * lying;
                // Place it with its origin over a point of the face, then lift it so that its lowest
                // point is at the gap (in double: the truth below is recomputed from what results); the
                // rounded pair's core's lowest vertex.
                const Vec3 face_point = pa.apply(Vec3{1.2 * size * u(rng), 1.2 * size * u(rng), base_half.z});
                Vec3 low_local;  // the top's lowest point along -n, in its frame
                const Vec3 down = transpose(rt) * (-1.0 * n);
                if (kind == 0 || kind == 4 || kind == 5 || kind == 6) {
                    low_local = {down.x < 0 ? -half.x : half.x, down.y < 0 ? -half.y : half.y,
                                 down.z < 0 ? -half.z : half.z};
                    if (kind == 4) low_local = low_local + radius * down;
                } else if (kind == 3) {
                    low_local = Vec3{0, 0, down.z < 0 ? -half.z : half.z} + radius * down;
                } else {
                    const double rho = std::hypot(down.x, down.y);
                    low_local = {rho > 0 ? half.x * down.x / rho : 0, rho > 0 ? half.x * down.y / rho : 0, -half.z};
                }
                const Vec3 offset = rt * low_local;
                const double lift_by = gap - dot(n, offset);
                const Transform pb{rt, face_point + lift_by * n};
                // Truth: the lowest point's height over the face plane, long double.
                const P3 face_centre = place(pa, {0, 0, base_half.z});
                const P3 nn = lift(n);
                Real low = INFINITY;
                if (kind == 0 || kind == 4 || kind == 5 || kind == 6) {  // the lowest vertex, less the radii
                    for (const auto& v : gjk_test::box_vertices(half))
                        low = std::min(low, oracle::dot(nn, place(pb, {v[0], v[1], v[2]}) - face_centre));
                    if (kind == 6 && low < 0) ++core_overlapping;
                    if (kind == 4 || kind == 6) low -= Real(radius);
                    if (kind == 6) low -= Real(base_ball.radius);
                } else if (kind == 3) {  // the lower end of the segment, less the radius
                    for (double z : {-half.z, half.z})
                        low = std::min(low, oracle::dot(nn, place(pb, {0, 0, z}) - face_centre));
                    low -= Real(radius);
                } else {
                    // The rim's lowest point: the bottom cap's centre less the radius along the part of
                    // n across the axis (the whole cap when the axis is along n).
                    const P3 axis = lift(pb.rotation.col(2));
                    const P3 centre = place(pb, {0, 0, -Real(half.z)});
                    const Real along = oracle::dot(nn, axis);
                    const P3 across = nn - along * axis;
                    const Real width = oracle::norm(across);
                    low = oracle::dot(nn, centre - face_centre) - Real(half.x) * width;
                }
                const double truth = double(low);
                const double coords = max_abs(pa.translation) + max_abs(pb.translation);
                // Boxes: rounding of the placed vertices. Curved: GJK's and the expansion's accuracy on
                // a rim, 1e-9 of the size, as for the other curved contacts.
                const bool curved = kind == 1 || kind == 2;
                const double tol = curved ? 1e-9 * size + 1e-13 * coords : 1e-13 * (size + coords);
                ++cases;
                if (truth < 0 && kind != 6) ++overlapping;  // the rounded pair always overlaps
                auto fail = [&](const char* rule, double got) {
                    if (++failures <= 10)
                        ADD_FAILURE() << names[kind] << " " << rule << ": got " << got << ", truth " << truth
                                      << " (tilt " << tilt << ", gap " << gap << ", tol " << tol << "); size " << size
                                      << " far " << far << " case " << i << " seed " << seed;
                };
                for (int order = 0; order < 2; ++order) {
                    const Shape& x = order == 0 ? static_cast<const Shape&>(base) : top;
                    const Shape& y = order == 0 ? top : static_cast<const Shape&>(base);
                    const Transform& px = order == 0 ? pa : pb;
                    const Transform& py = order == 0 ? pb : pa;
                    const DistanceResult s = signed_distance(x, px, y, py, 1e-12, 256);
                    const double err = std::fabs(s.distance - truth);
                    worst[kind] = std::max(worst[kind], err / size);
                    if (!(err <= tol)) fail("signed distance", s.distance);
                    if (std::fabs(truth) > tol) {
                        const double facing = dot(s.axis, order == 0 ? n : -1.0 * n);
                        if (!(facing > 1 - 1e-6)) fail("signed distance axis . face normal", facing);
                    }
                    const DistanceResult d = gjk_distance(x, px, y, py, 1e-12, 256);
                    if (!(std::fabs(d.distance - std::fmax(truth, 0.0)) <= tol)) fail("distance", d.distance);
                    if (std::fabs(truth) > tol && d.intersecting != (truth < 0))
                        fail("distance's verdict", d.intersecting);
                    Vec3 sep{};
                    const bool hit = gjk_intersect(x, px, y, py, sep, nullptr);
                    if (std::fabs(truth) > tol && hit != (truth < 0)) fail("intersect", hit);
                }
            }
        }
    std::printf(
        "tilted flat contacts: %d cases, %d overlapping (rounded pairs aside), %d rounded pairs' cores overlapping; "
        "worst signed distance error: box %.3g, cylinder %.3g, cone %.3g, capsule %.3g, rounded box %.3g, hull %.3g, "
        "rounded pair %.3g of the size\n",
        cases, overlapping, core_overlapping, worst[0], worst[1], worst[2], worst[3], worst[4], worst[5], worst[6]);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    const int plain = cases * (kinds - 1) / kinds, pairs = cases - plain;
    EXPECT_GT(overlapping, plain / 3) << "seed " << seed;
    EXPECT_LT(overlapping, plain * 2 / 3) << "seed " << seed;
    EXPECT_GT(core_overlapping, pairs / 3) << "seed " << seed;
    EXPECT_LT(core_overlapping, pairs * 2 / 3) << "seed " << seed;
}
