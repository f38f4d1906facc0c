// SPDX-License-Identifier: MIT
// Rigidly transformed shapes (a TransformedShape whose linear part is a rotation) are their child
// at the composed pose in every query (shapes/shape.hpp, unwrap_rigid), so a placed ball gets the
// ball closed forms and a placed box the box kernel. Truths independent of that code: the balls'
// centres and the boxes' vertices mapped through the placement and the pose in long double, the
// ball/ball distance and cast in closed form from them, the boxes' distance and depth by the
// brute-force polytope oracle. Two placed balls 8 apart in balls of radius 481 once went to the
// expansion through the generic support: 135 us, the depth 1 % short and the axis 40 degrees off
// (a fuzz_world step of 1540 such pairs took 7.6 s under the fuzz build).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "casts/cast.hpp"
#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "gjk_test_support.hpp"
#include "rigid_placement_support.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using gjk_test::random_quat;
using gjk_test::random_unit;
using oracle::P3;
using oracle::Real;
using rigid_test::map;
using rigid_test::placement_rotation;

namespace {

P3 lift(Vec3 v) { return {v.x, v.y, v.z}; }
// A local point of a placement (linear l, translation o) at pose, in long double.
P3 world_point(const Mat3& l, Vec3 o, const Transform& pose, P3 local) {
    return map(pose.rotation, map(l, local, o), pose.translation);
}
double max_coord(const Transform& p) { return max_abs(p.translation); }

}  // namespace

// Two placed balls (one of them placed twice over, nested) against the ball truth: signed and
// unsigned distance, intersection, shape cast and ray cast, both argument orders, at gaps from
// -0.99 of the radii (the fuzz case) through touching and 1e-12 to 1 of them, sizes 1e-3 to 1e3,
// 1 to 1e4 of the size from the origin. Every answer must be the closed form's: one iteration.
TEST(RigidPlacement, PlacedBallsTakeTheBallClosedForms) {
    const uint64_t seed = 2711;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double gaps[] = {-0.99, -0.5, -1e-2, -1e-6, 0, 1e-12, 1e-9, 1e-6, 1e-2, 1};
    int cases = 0, failures = 0, overlapping = 0;
    double worst = 0;
    for (double size : {1e-3, 1.0, 1e3}) {
        for (double far : {1.0, 1e4}) {
            for (int i = 0; i < 200; ++i) {
                const double ra = size * (0.2 + std::fabs(u(rng))), rb = size * (0.2 + std::fabs(u(rng)));
                SphereShape ball_a(ra), ball_b(rb);
                const Mat3 la = placement_rotation(rng, i % 3), lb = placement_rotation(rng, i / 3 % 3);
                const Vec3 oa = size * Vec3{u(rng), u(rng), u(rng)}, ob = size * Vec3{u(rng), u(rng), u(rng)};
                TransformedShape inner(ball_b, lb, ob);
                const Mat3 lb2 = placement_rotation(rng, 2);
                const Vec3 ob2 = size * Vec3{u(rng), u(rng), u(rng)};
                TransformedShape a(ball_a, la, oa), nested(inner, lb2, ob2);
                const bool nest = i % 2 == 1;
                const Shape& b = nest ? static_cast<const Shape&>(nested) : static_cast<const Shape&>(inner);
                const Transform pa = make_transform(far * size * Vec3{u(rng), u(rng), u(rng)}, random_quat(rng));
                // B's pose: its ball's centre at the chosen gap from A's along a random direction.
                const Vec3 dir = random_unit(rng);
                const double gap = gaps[i % 10] * (ra + rb);
                const Quat qb = random_quat(rng);
                const Mat3 rb_m = to_matrix(qb);
                const Vec3 local_b = nest ? lb2 * ob + ob2 : ob;  // B's centre in B's frame
                const Vec3 ca_d = pa.apply(oa);
                const Transform pb{rb_m, ca_d + (ra + rb + gap) * dir - rb_m * local_b};
                // Truth from the doubles the queries see.
                const P3 ca = world_point(la, oa, pa, {0, 0, 0});
                const P3 cb = nest ? map(pb.rotation, map(lb2, map(lb, {0, 0, 0}, ob), ob2), pb.translation)
                                   : world_point(lb, ob, pb, {0, 0, 0});
                const Real centres = oracle::norm(cb - ca);
                const double truth = double(centres - Real(ra) - Real(rb));
                const P3 toward = (Real(1) / centres) * (cb - ca);
                const double tol = 1e-13 * (ra + rb + max_coord(pa) + max_coord(pb));
                ++cases;
                if (truth <= 0) ++overlapping;
                auto fail = [&](const char* rule, double got) {
                    if (++failures <= 8)
                        ADD_FAILURE() << rule << ": got " << got << ", truth " << truth << " (tol " << tol << "); size "
                                      << size << " far " << far << " case " << i << " seed " << seed;
                };
                for (int order = 0; order < 2; ++order) {
                    const Shape& x = order == 0 ? static_cast<const Shape&>(a) : b;
                    const Shape& y = order == 0 ? b : static_cast<const Shape&>(a);
                    const Transform& px = order == 0 ? pa : pb;
                    const Transform& py = order == 0 ? pb : pa;
                    const Real sign = order == 0 ? 1 : -1;
                    const DistanceResult s = signed_distance(x, px, y, py, 1e-10, 256);
                    worst = std::max(worst, std::fabs(s.distance - truth) / (ra + rb));
                    if (!(std::fabs(s.distance - truth) <= tol)) fail("signed distance", s.distance);
                    if (s.iterations != 1) fail("signed distance iterations", s.iterations);
                    const Real along =
                        sign * (Real(s.axis.x) * toward.x + Real(s.axis.y) * toward.y + Real(s.axis.z) * toward.z);
                    if (!(along > 1 - 1e-9L)) fail("signed distance axis . centre line", double(along));
                    const DistanceResult d = gjk_distance(x, px, y, py, 1e-10, 256);
                    if (!(std::fabs(d.distance - std::fmax(truth, 0.0)) <= tol)) fail("distance", d.distance);
                    if (d.iterations != 1) fail("distance iterations", d.iterations);
                    Vec3 axis{};
                    const bool hit = gjk_intersect(x, px, y, py, axis, nullptr);
                    if (std::fabs(truth) > tol && hit != (truth < 0)) fail("intersect", hit);
                    // B toward A: the gap closed at half the step.
                    if (truth > tol) {
                        const Vec3 step = double(-2 * sign * Real(truth)) *
                                          Vec3{double(toward.x), double(toward.y), double(toward.z)};
                        const CastResult c = shape_cast(x, px, {}, y, py, step, 1e-10, 256);
                        // The contact's place along the step to the distances' rounding.
                        const double off = std::fabs(c.toi - 0.5) * length(step);
                        if (!c.hit || !(off <= tol + 1e-9 * length(step))) fail("shape cast toi", c.hit ? c.toi : -1);
                        if (c.iterations != 1) fail("shape cast iterations", c.iterations);
                    }
                }
                // A ray from B's centre toward A's ball: it enters at the gap plus B's radius.
                if (truth > tol) {
                    const Vec3 origin{double(cb.x), double(cb.y), double(cb.z)};
                    const Vec3 ray = double(-2 * (Real(truth) + Real(rb))) *
                                     Vec3{double(toward.x), double(toward.y), double(toward.z)};
                    const CastResult r = ray_cast(a, pa, origin, ray, 1e-10, 256);
                    const double off = std::fabs(r.toi - 0.5) * length(ray);
                    if (!r.hit || !(off <= tol + 1e-9 * length(ray))) fail("ray cast toi", r.hit ? r.toi : -1);
                    if (r.iterations != 1) fail("ray cast iterations", r.iterations);
                }
            }
        }
    }
    std::printf("placed balls: %d cases, %d overlapping, worst signed distance error %.3g of the radii\n", cases,
                overlapping, worst);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(overlapping, cases / 3) << "seed " << seed;
    EXPECT_LT(overlapping, cases * 2 / 3) << "seed " << seed;
}

// Placed boxes against the polytope oracle (their vertices mapped through placement and pose in
// long double): distance and penetration depth, both orders. Spheres cannot show whether the
// placement's rotation is composed the right way round; boxes do.
TEST(RigidPlacement, PlacedBoxesMatchThePolytopeOracle) {
    const uint64_t seed = 2712;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    int cases = 0, failures = 0, overlapping = 0;
    double worst_distance = 0, worst_depth = 0;
    for (int i = 0; i < 600; ++i) {
        const Vec3 ha{0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng))};
        const Vec3 hb{0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng))};
        BoxShape box_a(ha), box_b(hb);
        const Mat3 la = placement_rotation(rng, i % 3), lb = placement_rotation(rng, 1 + i % 2);
        const Vec3 oa{u(rng), u(rng), u(rng)}, ob{u(rng), u(rng), u(rng)};
        TransformedShape a(box_a, la, oa), b(box_b, lb, ob);
        const Transform pa = make_transform(Vec3{u(rng), u(rng), u(rng)}, random_quat(rng));
        // B's placed centre 0.5 to 4 from A's.
        const Vec3 target = pa.apply(oa) + (0.5 + 3.5 * std::fabs(u(rng))) * random_unit(rng);
        const Mat3 rbm = to_matrix(random_quat(rng));
        const Transform pb{rbm, target - rbm * ob};
        std::vector<P3> va, vb;
        for (const auto& v : gjk_test::box_vertices(ha)) va.push_back(world_point(la, oa, pa, {v[0], v[1], v[2]}));
        for (const auto& v : gjk_test::box_vertices(hb)) vb.push_back(world_point(lb, ob, pb, {v[0], v[1], v[2]}));
        const oracle::Result o = oracle::distance(oracle::make_polytope(va), oracle::make_polytope(vb));
        ++cases;
        if (o.intersecting) ++overlapping;
        auto fail = [&](const char* rule, double got, double truth) {
            if (++failures <= 8)
                ADD_FAILURE() << rule << ": got " << got << ", truth " << truth << "; case " << i << " seed " << seed;
        };
        for (int order = 0; order < 2; ++order) {
            const Shape& x = order == 0 ? a : b;
            const Shape& y = order == 0 ? b : a;
            const Transform& px = order == 0 ? pa : pb;
            const Transform& py = order == 0 ? pb : pa;
            const DistanceResult d = gjk_distance(x, px, y, py, 1e-10, 256);
            const double err = std::fabs(d.distance - double(o.distance));
            worst_distance = std::max(worst_distance, err);
            if (!(err <= 1e-9)) fail("distance", d.distance, double(o.distance));
            const DistanceResult s = signed_distance(x, px, y, py, 1e-10, 256);
            const double truth = o.intersecting ? -double(o.depth) : double(o.distance);
            const double serr = std::fabs(s.distance - truth);
            if (o.intersecting) worst_depth = std::max(worst_depth, serr);
            if (!(serr <= 1e-9)) fail("signed distance", s.distance, truth);
        }
    }
    std::printf("placed boxes: %d cases, %d overlapping, worst distance error %.3g, depth %.3g\n", cases, overlapping,
                worst_distance, worst_depth);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(overlapping, cases / 5) << "seed " << seed;
    EXPECT_LT(overlapping, cases * 4 / 5) << "seed " << seed;
}

// Only rotations unwrap. A ball under 1.000001 times a rotation is a ball of radius 1.000001 r,
// and a reflected or sheared placement is no rotation either: their distances must be those of
// the shapes they are, within the generic path's tolerance, which a wrong unwrap (the child's
// radius) would miss by 1e-6 of it. Rotations of normalised quaternions must unwrap (the closed
// form's one iteration), as must a matrix one unit in the last place off a rotation.
TEST(RigidPlacement, OnlyRotationsUnwrap) {
    const uint64_t seed = 2713;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    int failures = 0, unwrapped = 0, generic = 0;
    for (int i = 0; i < 400; ++i) {
        const double r = 0.5 + std::fabs(u(rng));
        SphereShape ball(r), other(0.5);
        Mat3 l = to_matrix(random_quat(rng));
        double scale = 1;  // the placed shape is a ball of radius scale * r
        const int kind = i % 5;
        if (kind == 1) {  // scaled
            scale = 1 + 1e-6;
            for (auto& row : l.r) row = scale * row;
        } else if (kind == 2) {  // a reflection: still a ball of radius r
            l.r[2] = -1.0 * l.r[2];
        } else if (kind == 3) {  // one ulp off a rotation: unwraps
            l.r[0].x = std::nextafter(l.r[0].x, 2.0);
        } else if (kind == 4) {  // sheared by 1e-6 along z: no ball, so the distance is only bounded
            l.r[0].z += 1e-6;
        }
        const Vec3 o{u(rng), u(rng), u(rng)};
        TransformedShape placed(ball, l, o);
        const Transform pa = make_transform(Vec3{u(rng), u(rng), u(rng)}, random_quat(rng));
        const Vec3 centre = pa.apply(o);
        const Transform pb =
            make_transform(centre + (scale * r + 0.5 + 0.3 + std::fabs(u(rng))) * random_unit(rng), random_quat(rng));
        const P3 c = world_point(l, o, pa, {0, 0, 0});
        const double truth = double(oracle::norm(lift(pb.translation) - c) - Real(scale * r) - Real(0.5));
        const DistanceResult d = gjk_distance(placed, pa, other, pb, 1e-12, 256);
        const bool rotation = kind == 0 || kind == 3;
        if (d.iterations == 1)
            ++unwrapped;
        else
            ++generic;
        const double tol = kind == 4 ? 2e-6 : 1e-9;
        if (!(std::fabs(d.distance - truth) <= tol) || (d.iterations == 1) != rotation) {
            if (++failures <= 8)
                ADD_FAILURE() << "kind " << kind << ": distance " << d.distance << ", truth " << truth
                              << ", iterations " << d.iterations << "; case " << i << " seed " << seed;
        }
    }
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_EQ(unwrapped, 160) << "seed " << seed;
    EXPECT_EQ(generic, 240) << "seed " << seed;
}
