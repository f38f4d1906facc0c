// SPDX-License-Identifier: MIT
// Rounded shapes whose cores have no closed form (an ellipsoid, a capsule, a rounded box or
// cylinder against a sphere or a turned box; rays against rounded cylinders and hulls) cast at
// loose tolerances: the plane of the reported normal must still hold the shapes (or the ray
// point) apart at toi, within the fuzz target's slack of (2 tolerance + 1e-6) of the size. The
// cast's final v tilts by about the square root of the tolerance, and its plane cut an ellipsoid
// 306 wide and a unit sphere by 1.72 at tolerance 1e-3 (fuzzing; fuzz/findings/
// cast_ellipsoid_sphere_tilted_normal.c). Support values are written here, apart from the library.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "cast_test_support.hpp"
#include "casts/cast.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using cast_test::ShapePtr;

namespace {

// A convex body for the test: its support value h(n) = max over the body of n . x (world frame,
// unit or not n), from its own formula, and the library's shape.
struct Body {
    enum Type { Ellipsoid, Capsule, RoundedBox, RoundedCylinder, RoundedHull, Sphere, Box } type;
    Vec3 dims;         // ellipsoid: radii; capsule (radius, half length, -); boxes: half extents; cylinder (r, h, -)
    double round = 0;  // the radius a core is grown by (capsule: dims.x)
    std::vector<Vec3> points;  // hull
    Transform pose;
    ShapePtr shape;
    double size = 0;  // bounding radius about the origin of the local frame

    double h(Vec3 n) const { return h(n, pose); }
    double h(Vec3 n, const Transform& at) const {
        const Vec3 m = mul_transpose(at.rotation, n);  // local direction
        double local = 0;
        switch (type) {
            case Ellipsoid:
                local =
                    std::sqrt(dims.x * dims.x * m.x * m.x + dims.y * dims.y * m.y * m.y + dims.z * dims.z * m.z * m.z);
                break;
            case Capsule:
                local = dims.y * std::fabs(m.z) + dims.x * length(m);
                break;
            case RoundedBox:
            case Box:
                local = dims.x * std::fabs(m.x) + dims.y * std::fabs(m.y) + dims.z * std::fabs(m.z) + round * length(m);
                break;
            case RoundedCylinder:
                local = dims.x * std::hypot(m.x, m.y) + dims.y * std::fabs(m.z) + round * length(m);
                break;
            case RoundedHull: {
                double best = -INFINITY;
                for (const Vec3& p : points) best = std::max(best, dot(p, m));
                local = best + round * length(m);
                break;
            }
            case Sphere:
                local = dims.x * length(m);
                break;
        }
        return local + dot(n, at.translation);
    }
};

Body make_body(std::mt19937_64& rng, Body::Type type) {
    std::uniform_real_distribution<double> u(0, 1);
    Body b;
    b.type = type;
    switch (type) {
        case Body::Ellipsoid: {
            // A sphere under a diagonal map: flat (one radius 1e-2 .. 1 of the others) or long.
            const double r = 0.5 + u(rng), big = std::pow(10.0, 2 * u(rng)), small = 0.01 + u(rng);
            const bool flat = u(rng) < 0.5;
            const Vec3 scale = flat ? Vec3{small, big, big} : Vec3{big, small, small};
            b.dims = r * scale;
            Mat3 lin{};
            lin.r[0] = {scale.x, 0, 0};
            lin.r[1] = {0, scale.y, 0};
            lin.r[2] = {0, 0, scale.z};
            const ShapePtr ball(new SphereShape(r));
            b.shape.reset(new TransformedShape(*ball, lin, Vec3{}));
            b.size = std::max({b.dims.x, b.dims.y, b.dims.z});
            break;
        }
        case Body::Capsule:
            b.dims = {0.1 + u(rng), 0.2 + 3 * u(rng), 0};
            b.round = b.dims.x;
            b.shape.reset(new CapsuleShape(b.dims.x, b.dims.y));
            b.size = b.dims.x + b.dims.y;
            break;
        case Body::RoundedBox:
        case Body::RoundedCylinder: {
            b.round = 0.05 + 0.5 * u(rng);
            const ShapePtr ball(new SphereShape(b.round));
            ShapePtr core;
            if (type == Body::RoundedBox) {
                b.dims = {0.2 + 2 * u(rng), 0.2 + 2 * u(rng), 0.05 + u(rng)};
                core.reset(new BoxShape(b.dims));
                b.size = length(b.dims) + b.round;
            } else {
                b.dims = {0.2 + 2 * u(rng), 0.1 + 2 * u(rng), 0};
                core.reset(new CylinderShape(b.dims.x, b.dims.y));
                b.size = std::hypot(b.dims.x, b.dims.y) + b.round;
            }
            b.shape.reset(new MinkowskiSumShape(*core, *ball));
            break;
        }
        case Body::RoundedHull: {
            b.round = 0.05 + 0.5 * u(rng);
            const Vec3 radii{0.5 + u(rng), 0.3 + u(rng), 0.1 + u(rng)};
            b.points = cast_test::ellipsoid_points(rng, 12, radii);
            const ShapePtr core = cast_test::hull_shape(b.points);
            const ShapePtr ball(new SphereShape(b.round));
            b.shape.reset(new MinkowskiSumShape(*core, *ball));
            b.size = std::max({radii.x, radii.y, radii.z}) + b.round;
            break;
        }
        case Body::Sphere:
            b.dims = {0.2 + 2 * u(rng), 0, 0};
            b.shape.reset(new SphereShape(b.dims.x));
            b.size = b.dims.x;
            break;
        case Body::Box:
            b.dims = {0.1 + u(rng), 0.1 + u(rng), 0.1 + u(rng)};
            b.shape.reset(new BoxShape(b.dims));
            b.size = length(b.dims);
            break;
    }
    b.pose = make_transform(Vec3{}, cast_test::random_quat(rng));
    return b;
}

}  // namespace

TEST(CastRoundedLoose, NormalsPlaneHoldsTheShapesApartAtToi) {
    const uint32_t seed = 3016;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double tolerances[] = {1e-1, 3e-2, 1e-2, 1e-3, 1e-4, 1e-6, 1e-10};
    const Body::Type movers[] = {Body::Sphere, Body::Box};
    const Body::Type fixed[] = {Body::Ellipsoid, Body::Capsule, Body::RoundedBox, Body::RoundedCylinder,
                                Body::RoundedHull};
    int casts = 0, hits = 0, rays = 0, ray_hits = 0, failures = 0;
    double worst = 0, worst_ray = 0;
    for (int trial = 0; trial < 600; ++trial) {
        Body a = make_body(rng, fixed[trial % 5]);
        Body b = make_body(rng, movers[(trial / 5) % 2]);
        // B starts 3 to 6 sizes away and heads for a point of A's core region: a hit.
        const Vec3 dir = cast_test::random_unit(rng);
        const double reach = a.size + b.size;
        const Vec3 start = (3 + 3 * u(rng)) * reach * dir;
        const Vec3 target = 0.2 * a.size * cast_test::random_unit(rng);
        b.pose.translation = start;
        a.pose.translation = Vec3{};
        const Vec3 motion = target - start;
        const double split = u(rng);  // A takes part of the motion, the other way
        const Vec3 ta = -split * 0.5 * motion, tb = (1 - split * 0.5) * motion;
        for (double tol : tolerances) {
            for (int order = 0; order < 2; ++order) {
                const Body& p = order == 0 ? a : b;
                const Body& q = order == 0 ? b : a;
                const Vec3 tp = order == 0 ? ta : tb, tq = order == 0 ? tb : ta;
                const CastResult r = shape_cast(*p.shape, p.pose, tp, *q.shape, q.pose, tq, tol, 256);
                ++casts;
                if (!r.hit || !(r.toi > 0)) continue;
                ++hits;
                // At toi: P's support along n and Q's lowest point along n.
                Transform at_p = p.pose, at_q = q.pose;
                at_p.translation = p.pose.translation + r.toi * tp;
                at_q.translation = q.pose.translation + r.toi * tq;
                const double overlap = p.h(r.normal, at_p) + q.h(-1.0 * r.normal, at_q);
                const double size = a.size + b.size;
                worst = std::max(worst, overlap / size);
                if (!(overlap <= (2 * tol + 1e-6) * size) && ++failures <= 10)
                    ADD_FAILURE() << "seed " << seed << " trial " << trial << " tolerance " << tol << " order " << order
                                  << ": at toi " << r.toi << " the shapes overlap by " << overlap / size
                                  << " of the size along the normal (termination " << static_cast<int>(r.termination)
                                  << ")";
            }
        }
        // A ray from B's start toward the target, against A (rounded cores: cylinders and hulls).
        if (a.type == Body::RoundedCylinder || a.type == Body::RoundedHull) {
            for (double tol : tolerances) {
                const CastResult r = ray_cast(*a.shape, a.pose, start, motion, tol, 256);
                ++rays;
                if (!r.hit || !(r.toi > 0)) continue;
                ++ray_hits;
                const Vec3 x = start + r.toi * motion;
                const double behind = a.h(r.normal) - dot(r.normal, x);
                worst_ray = std::max(worst_ray, behind / a.size);
                if (!(behind <= (2 * tol + 1e-6) * a.size) && ++failures <= 10)
                    ADD_FAILURE() << "seed " << seed << " trial " << trial << " tolerance " << tol
                                  << ": the ray point at toi " << r.toi << " lies " << behind / a.size
                                  << " of the size behind the normal's plane";
            }
        }
    }
    std::printf(
        "rounded pairs at loose tolerances: %d shape casts (%d hits), %d rays (%d hits); worst overlap along the "
        "normal %.3g of the size (rays %.3g)\n",
        casts, hits, rays, ray_hits, worst, worst_ray);
    // Every cast aims through A: nearly all hit.
    EXPECT_GT(hits, casts * 9 / 10);
    EXPECT_GT(ray_hits, rays * 9 / 10);
}

// A fuzz finding of the rule above: a unit ball cast against a capsule stretched to 1.3e5 by a
// transform stops on a rounding rule; v's plane cut the shapes, the clip's normal was taken, and
// beside it the distance at toi no longer won the comparison that also brings its point: the
// simplex's point stayed, 0.28 outside the ball. The point must lie in both shapes at toi within
// (2 tolerance + 1e-6) of the size (the fuzz target's slack), from support values written here.
TEST(CastRoundedLoose, StretchedCapsuleRoundingStopKeepsThePointOnTheShapes) {
    const ShapePtr ball(new SphereShape(1));
    const ShapePtr capsule(new CapsuleShape(10.002746623941405, 100));
    Mat3 lin;
    lin.r[0] = {0.11595635919737544, 0, 0};
    lin.r[1] = {0, 13.925841128186804, 0.081388187946859439};
    lin.r[2] = {0, -0.00084101158262596181, 1347.6615524367273};
    const Vec3 offset{-3.9372549019607845, -0.85932707713435574, 3.9374990463111317};
    const ShapePtr stretched(new TransformedShape(*capsule, lin, offset));
    const Transform pose = make_transform({-1.7098039215686276, -1.7098039215686276, -1.7098039215686276}, Quat{0, 1, 0, 0});
    const Vec3 ta{-42.745098039215691, -42.745098039215691, -42.745098039215691};
    const Vec3 tb{-93.527122911421372, -30.467689021133747, -30.196078431372552};
    const CastResult r = shape_cast(*ball, pose, ta, *stretched, pose, tb, 1e-10, 256);
    ASSERT_TRUE(r.hit);
    const Vec3 ca = pose.translation + r.toi * ta, cb = pose.translation + r.toi * tb;
    // The stretched capsule's support value along world n: m = R^T n, k = lin^T m.
    auto h_b = [&](Vec3 n) {
        const Vec3 m = mul_transpose(pose.rotation, n);
        const Vec3 k = mul_transpose(lin, m);
        return 10.002746623941405 * length(k) + 100 * std::fabs(k.z) + dot(m, offset) + dot(n, cb);
    };
    const double size = 1347.6615524367273 * 110, slack = (2 * 1e-10 + 1e-6) * size;
    EXPECT_LE(length(r.point - ca), 1 + slack) << "the point lies outside the ball";
    for (const Vec3 n : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1}, Vec3{0, 0, -1},
                         normalized_or(r.normal, {}), normalized_or(-1.0 * r.normal, {})})
        EXPECT_LE(dot(n, r.point), h_b(n) + slack) << "the point lies outside the stretched capsule";
    std::printf("stretched capsule: toi %.17g termination %d, point %.9g from the ball's centre\n", r.toi,
                static_cast<int>(r.termination), length(r.point - ca));
}
