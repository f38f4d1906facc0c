// SPDX-License-Identifier: MIT
// Motion over a step and the disk bound on rotation, against closed forms and sampled paths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "motion/motion.hpp"
#include "shapes/radius.hpp"
#include "shapes/shape.hpp"

using namespace kairos;

namespace {

Quat random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    return normalized(Quat{g(rng), g(rng), g(rng), g(rng)});
}

// Angle of the rotation taking a to b (in [0, pi]), independent of the Motion code.
double angle_between(Quat a, Quat b) {
    const double d = std::fabs(a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w);
    return 2 * std::acos(std::fmin(1.0, d));
}

// Support of a disk of `radius` centred at the origin, perpendicular to unit `normal`.
inline Vec3 disk_support(Vec3 normal, double radius, Vec3 d) {
    const DiskShape disk(normal, radius);
    return support(disk, d);
}

}  // namespace

TEST(Motion, EndpointsShortestArcAndConstantRate) {
    const uint32_t seed = 77;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-5, 5);
    for (int trial = 0; trial < 500; ++trial) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed << " trial " << trial);
        Pose s{{u(rng), u(rng), u(rng)}, random_unit(rng)};
        Pose e{{u(rng), u(rng), u(rng)}, random_unit(rng)};
        // The same end orientation given as -q must give the same motion.
        Pose e_neg = e;
        e_neg.orientation = {-e.orientation.x, -e.orientation.y, -e.orientation.z, -e.orientation.w};
        const Motion m(s, e), m_neg(s, e_neg);
        EXPECT_NEAR(m.angle(), m_neg.angle(), 1e-12);
        EXPECT_LE(m.angle(), std::numbers::pi + 1e-12);
        EXPECT_NEAR(m.angle(), angle_between(s.orientation, e.orientation), 1e-7);
        EXPECT_NEAR(angle_between(m.at(0).orientation, s.orientation), 0, 1e-7);
        EXPECT_NEAR(angle_between(m.at(0.999999999).orientation, e.orientation), 0, 1e-6);
        EXPECT_NEAR(length(m.at(0.5).position - 0.5 * (s.position + e.position)), 0, 1e-12);
        // Constant angular velocity about one axis: the turn from start to t is t * angle, and
        // the axis stays fixed (points on it do not move relative to the origin).
        for (double t : {0.1, 0.37, 0.5, 0.81}) {
            const Pose b = m.at(t);
            EXPECT_NEAR(angle_between(s.orientation, b.orientation), t * m.angle(), 1e-7) << t;
            const Vec3 on_axis_local = mul_transpose(to_matrix(s.orientation), m.axis());
            EXPECT_NEAR(length(to_matrix(b.orientation) * on_axis_local - m.axis()), 0, 1e-12) << t;
        }
    }
    // No rotation: a pure translation, whatever the (equal) orientation, and for q and -q.
    const Pose a{{0, 0, 0}, {0, 0, 0, 1}}, b{{1, 2, 3}, {0, 0, 0, 1}};
    EXPECT_FALSE(Motion(a, b).rotates());
    std::mt19937_64 r2(seed + 1);
    for (int i = 0; i < 200; ++i) {
        const Quat q = random_unit(r2);
        const Pose s{{0, 0, 0}, q}, e{{1, 0, 0}, q}, e_neg{{1, 0, 0}, {-q.x, -q.y, -q.z, -q.w}};
        EXPECT_FALSE(Motion(s, e).rotates()) << i;
        EXPECT_FALSE(Motion(s, e_neg).rotates()) << i;
        EXPECT_EQ(Motion(s, e).angle(), 0.0);
    }
}

TEST(Motion, DiskBoundContainsEveryPointPath) {
    // For a shape turning about its origin, each point's displacement relative to the origin
    // over [t0, t1] must lie within the disk of radius 2 rho sin(|da|/2), perpendicular to the axis.
    const uint32_t seed = 4242;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    BoxShape box({0.2, 1.5, 0.4});
    for (int trial = 0; trial < 300; ++trial) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed << " trial " << trial);
        const Pose s{{0, 0, 0}, random_unit(rng)}, e{{0, 0, 0}, random_unit(rng)};
        const Motion m(s, e);
        const Vec3 local_axis = mul_transpose(to_matrix(s.orientation), m.axis());
        const double rho = extreme_radius(box, local_axis);
        const double t0 = 0.5 * (u(rng) + 1), t1 = t0 + (1 - t0) * 0.5 * (u(rng) + 1);
        const double r = m.disk_radius(rho, t0, t1);
        const Mat3 r0 = to_matrix(m.at(t0).orientation);
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 x{corner & 1 ? 0.2 : -0.2, corner & 2 ? 1.5 : -1.5, corner & 4 ? 0.4 : -0.4};
            for (int k = 0; k <= 16; ++k) {
                const double t = t0 + (t1 - t0) * k / 16.0;
                const Vec3 moved = to_matrix(m.at(t).orientation) * x - r0 * x;
                EXPECT_LE(length(moved), r * (1 + 1e-9) + 1e-12);
                EXPECT_NEAR(dot(moved, m.axis()), 0, 1e-9);  // stays in the disk's plane
            }
        }
    }
}

TEST(Motion, DiskSupport) {
    const Vec3 n{0, 0, 1};
    EXPECT_EQ(disk_support(n, 2, {0, 0, 5}), (Vec3{0, 0, 0}));  // parallel to the normal: the centre
    EXPECT_EQ(disk_support(n, 2, {0, 0, -5}), (Vec3{0, 0, 0}));
    EXPECT_EQ(disk_support(n, 2, {0, 0, 0}), (Vec3{0, 0, 0}));
    const Vec3 p = disk_support(n, 2, {3, 4, 7});
    EXPECT_NEAR(p.x, 1.2, 1e-15);
    EXPECT_NEAR(p.y, 1.6, 1e-15);
    EXPECT_EQ(p.z, 0);
    // The support really maximises d.x over the disk (sampled rim).
    std::mt19937_64 rng(5);
    std::normal_distribution<double> g;
    for (int i = 0; i < 200; ++i) {
        const Vec3 axis = normalized_or({g(rng), g(rng), g(rng)}, {0, 0, 1});
        const Vec3 d{g(rng), g(rng), g(rng)};
        const Vec3 s = disk_support(axis, 0.7, d);
        const Vec3 e1 = normalized_or(cross(axis, {1, 0, 0}), {0, 1, 0}), e2 = cross(axis, e1);
        for (int k = 0; k < 64; ++k) {
            const double a = 2 * std::numbers::pi * k / 64;
            EXPECT_GE(dot(d, s), dot(d, 0.7 * (std::cos(a) * e1 + std::sin(a) * e2)) - 1e-12);
        }
    }
}
