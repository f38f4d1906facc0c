// SPDX-License-Identifier: MIT
// Extreme radius about an axis, against its definition R = max over unit w perpendicular to the
// axis of h(w) = w . s(w), sampled densely (a lower bound within cos(pi/N) of the truth).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "shapes/radius.hpp"
#include "shapes/shape.hpp"

using namespace kairos;

namespace {

// Densely sampled max of h over the circle perpendicular to u: never above the true radius.
double sampled_lower_bound(const Shape& s, Vec3 u, int n = 4096) {
    const Vec3 helper = std::fabs(u.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
    const Vec3 e1 = normalized_or(cross(u, helper), {1, 0, 0});
    const Vec3 e2 = cross(u, e1);
    double best = 0;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n;
        const Vec3 w = std::cos(a) * e1 + std::sin(a) * e2;
        best = std::max(best, dot(w, support(s, w)));
    }
    return best;
}

struct Released {
    void operator()(const Shape* s) const { s->release(); }
};
using Ref = std::unique_ptr<const Shape, Released>;

ConvexHullShape* hull_of(std::vector<Vec3> v) {
    auto* h = new ConvexHullShape();
    h->vertices = std::move(v);
    return h;
}

}  // namespace

TEST(ExtremeRadius, AgainstSampledSupportForEveryKind) {
    const uint32_t seed = 20261122;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(-1, 1);

    Ref box(new BoxShape({0.3, 1.2, 2.5}));
    Ref sphere(new SphereShape(0.7));
    Ref capsule(new CapsuleShape(0.4, 1.5));
    Ref cylinder(new CylinderShape(0.9, 0.3));
    Ref tall_cylinder(new CylinderShape(0.2, 3.0));
    Ref cone(new ConeShape(1.1, 0.8));
    Ref thin_cone(new ConeShape(0.1, 2.0));
    Ref segment(new SegmentShape(2.0));
    Ref point(new PointShape());
    Ref hull(hull_of({{1, 0, 0}, {-0.5, 0.8, 0.1}, {-0.5, -0.8, -0.2}, {0.1, 0.2, 1.7}, {0.3, -0.1, -1.1}}));
    Mat3 shear;
    shear.r[0] = {2, 0.5, 0};
    shear.r[1] = {0, 0.3, 0.2};
    shear.r[2] = {-0.4, 0, 1.5};
    Ref transformed(new TransformedShape(*box, shear, {0.5, -0.3, 1.0}));
    Ref transformed_cone(new TransformedShape(*cone, shear, {0, 0, 0}));
    Ref sum(new MinkowskiSumShape(*box, *sphere));
    Ref sum_off(new MinkowskiSumShape(*transformed, *capsule));
    Ref hull2(new HullOfTwoShape(*cylinder, *transformed));

    struct Case {
        const char* name;
        const Shape* s;
        double slack;  // how far above the truth the bound may be, relative
    } cases[] = {
        {"box", box.get(), 1e-9},
        {"sphere", sphere.get(), 1e-9},
        {"capsule", capsule.get(), 1e-9},
        {"cylinder", cylinder.get(), 1e-9},
        {"tall cylinder", tall_cylinder.get(), 1e-9},
        {"cone", cone.get(), 1e-9},
        {"thin cone", thin_cone.get(), 1e-9},
        {"segment", segment.get(), 1e-9},
        {"hull", hull.get(), 1e-9},
        {"transformed box", transformed.get(), 1.3e-3},
        {"transformed cone", transformed_cone.get(), 1.3e-3},
        {"box + sphere", sum.get(), 1.3e-3},
        {"transformed + capsule", sum_off.get(), 1.3e-3},
        {"hull of cylinder and transformed", hull2.get(), 1.3e-3},
    };
    for (const Case& c : cases) {
        for (int trial = 0; trial < 120; ++trial) {
            Vec3 u{unit(rng), unit(rng), unit(rng)};
            if (trial == 0) u = {0, 0, 1};  // along the primitives' own axis
            if (trial == 1) u = {1, 0, 0};
            u = normalized_or(u, {0, 0, 1});
            const double rho = extreme_radius(*c.s, u);
            const double truth_below = sampled_lower_bound(*c.s, u);
            // The dense samples are within cos(pi/4096) ~ 1 - 3e-7 of the truth.
            const double truth_above = truth_below / std::cos(std::numbers::pi / 4096);
            SCOPED_TRACE(::testing::Message() << c.name << " trial " << trial << " seed " << seed << " axis (" << u.x
                                              << ", " << u.y << ", " << u.z << ")");
            EXPECT_GE(rho, truth_below * (1 - 1e-12));  // never below the true radius
            EXPECT_LE(rho, truth_above * (1 + c.slack) + 1e-12);
        }
    }
    EXPECT_EQ(extreme_radius(*point, {0.3, 0.4, 0.5}), 0.0);
}

TEST(ExtremeRadius, ClosedForms) {
    Ref rod(new SegmentShape(1.0));
    EXPECT_DOUBLE_EQ(extreme_radius(*rod, {0, 0, 1}), 0.0);  // spinning about its own axis
    EXPECT_DOUBLE_EQ(extreme_radius(*rod, {1, 0, 0}), 1.0);
    Ref cube(new BoxShape({1, 1, 1}));
    EXPECT_DOUBLE_EQ(extreme_radius(*cube, {0, 0, 1}), std::sqrt(2.0));
    EXPECT_NEAR(extreme_radius(*cube, {1, 1, 1}), std::sqrt(8.0 / 3.0),
                1e-15);  // body diagonal: corners at sqrt(3 - 1/3)
    Ref cyl(new CylinderShape(1, 2));
    EXPECT_DOUBLE_EQ(extreme_radius(*cyl, {0, 0, 1}), 1.0);
    EXPECT_DOUBLE_EQ(extreme_radius(*cyl, {1, 0, 0}), std::sqrt(5.0));
    Ref cone(new ConeShape(1, 2));
    EXPECT_DOUBLE_EQ(extreme_radius(*cone, {0, 0, 1}), 1.0);
    EXPECT_DOUBLE_EQ(extreme_radius(*cone, {1, 0, 0}), std::sqrt(5.0));
    // Axis length does not matter.
    EXPECT_DOUBLE_EQ(extreme_radius(*cyl, {0, 0, 7}), 1.0);
}

TEST(ExtremeRadius, DiskAndFattenedShapes) {
    // The rotation bound's disk, alone and summed with a shape, against the sampled definition.
    std::mt19937_64 rng(99);
    std::normal_distribution<double> g;
    for (int i = 0; i < 50; ++i) {
        const Vec3 n = normalized_or({g(rng), g(rng), g(rng)}, {0, 0, 1});
        const Vec3 u = normalized_or({g(rng), g(rng), g(rng)}, {0, 0, 1});
        Ref disk(new DiskShape(n, 0.6));
        Ref box(new BoxShape({0.5, 0.2, 0.9}));
        Ref fat(new MinkowskiSumShape(*box, *disk));
        SCOPED_TRACE(i);
        EXPECT_DOUBLE_EQ(extreme_radius(*disk, u), 0.6);
        const double truth = sampled_lower_bound(*fat, u);
        EXPECT_GE(extreme_radius(*fat, u), truth * (1 - 1e-12));
        EXPECT_LE(extreme_radius(*fat, u), truth / std::cos(std::numbers::pi / 4096) * (1 + 1.3e-3));
    }
}
