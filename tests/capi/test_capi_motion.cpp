// SPDX-License-Identifier: MIT
// kairos_motion_cast through the shared library: a thin rod turning through a thin wall (hit that
// translation-only casts miss), equal orientations (q and -q) giving the shape cast's answer,
// overlap at the start, and the output left untouched on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "kairos/kairos.h"

namespace {

const double kPi = std::numbers::pi;

kairos_quat about(double x, double y, double z, double angle) {
    const double s = std::sin(0.5 * angle);
    return {x * s, y * s, z * s, std::cos(0.5 * angle)};
}
kairos_quat mul(kairos_quat a, kairos_quat b) {
    return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

struct Shapes : ::testing::Test {
    kairos_shape* rod = nullptr;
    kairos_shape* wall = nullptr;
    kairos_shape* box = nullptr;
    void SetUp() override {
        ASSERT_EQ(kairos_shape_segment(1.0, &rod), KAIROS_OK);
        ASSERT_EQ(kairos_shape_box({0.005, 10, 10}, &wall), KAIROS_OK);
        ASSERT_EQ(kairos_shape_box({0.5, 0.5, 0.5}, &box), KAIROS_OK);
    }
    void TearDown() override {
        kairos_shape_release(rod);
        kairos_shape_release(wall);
        kairos_shape_release(box);
    }
};

}  // namespace

TEST_F(Shapes, SpinningRodHitsThinWall) {
    // The rod (local z) starts along world y and turns by 0.99 pi about z: its tip sweeps through
    // the wall whose face is at x = 0.5 when cos(phi) = 0.5, phi = pi / 2 - angle t.
    const kairos_quat to_y = about(1, 0, 0, -kPi / 2);
    const double angle = 0.99 * kPi;
    const kairos_motion ma{{{0, 0, 0}, to_y}, {{0, 0, 0}, mul(about(0, 0, 1, -angle), to_y)}};
    const kairos_motion mb{{{0.505, 0, 0}, {0, 0, 0, 1}}, {{0.505, 0, 0}, {0, 0, 0, 1}}};
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    kairos_cast_result r;
    ASSERT_EQ(kairos_motion_cast(rod, &ma, wall, &mb, &qs, &r), KAIROS_OK);
    const double t_star = (kPi / 2 - std::acos(0.5)) / angle;
    EXPECT_EQ(r.hit, 1);
    EXPECT_LE(r.toi, t_star + qs.tolerance);
    EXPECT_GE(r.toi, t_star - 1e-8);
    EXPECT_NEAR(r.normal.x, 1, 1e-6);  // from A (the rod) toward B (the wall)
    EXPECT_NEAR(r.point.x, 0.5, 1e-6);
    EXPECT_EQ(r.termination, KAIROS_TERMINATION_HIT);
    EXPECT_GT(r.iterations, 0u);
    // The two end poses alone (a shape cast with no turn) see nothing.
    kairos_cast_result s;
    ASSERT_EQ(kairos_shape_cast(rod, &ma.start, {0, 0, 0}, wall, &mb.start, {0, 0, 0}, &qs, &s), KAIROS_OK);
    EXPECT_EQ(s.hit, 0);
}

TEST_F(Shapes, EqualOrientationsTakeTheShapeCast) {
    const kairos_quat q = about(0.6, 0, 0.8, 0.7);
    const kairos_quat neg{-q.x, -q.y, -q.z, -q.w};
    const kairos_motion ma{{{0, 0, 0}, q}, {{0, 0, 0}, neg}};
    const kairos_motion mb{{{4, 0.3, 0}, {0, 0, 0, 1}}, {{-4, 0.3, 0}, {0, 0, 0, 1}}};
    kairos_cast_result r, s;
    ASSERT_EQ(kairos_motion_cast(box, &ma, box, &mb, nullptr, &r), KAIROS_OK);
    ASSERT_EQ(kairos_shape_cast(box, &ma.start, {0, 0, 0}, box, &mb.start, {-8, 0, 0}, nullptr, &s), KAIROS_OK);
    EXPECT_EQ(r.hit, s.hit);
    EXPECT_EQ(r.toi, s.toi);
    EXPECT_EQ(r.normal.x, s.normal.x);
    EXPECT_EQ(r.normal.y, s.normal.y);
    EXPECT_EQ(r.normal.z, s.normal.z);
    EXPECT_EQ(r.point.x, s.point.x);
    EXPECT_EQ(r.iterations, s.iterations);
    EXPECT_EQ(r.termination, s.termination);
    EXPECT_EQ(r.hit, 1);
}

TEST_F(Shapes, OverlapAtTheStartAndNoContact) {
    const kairos_motion spin{{{0, 0, 0}, {0, 0, 0, 1}}, {{0, 0, 0}, about(0, 0, 1, 2.0)}};
    const kairos_motion near{{{0.5, 0, 0}, {0, 0, 0, 1}}, {{0.5, 0, 0}, {0, 0, 0, 1}}};
    const kairos_motion far{{{5, 0, 0}, {0, 0, 0, 1}}, {{5, 0, 0}, {0, 0, 0, 1}}};
    kairos_cast_result r;
    ASSERT_EQ(kairos_motion_cast(box, &spin, box, &near, nullptr, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 1);
    EXPECT_EQ(r.toi, 0);
    EXPECT_NEAR(std::sqrt(r.normal.x * r.normal.x + r.normal.y * r.normal.y + r.normal.z * r.normal.z), 1, 1e-12);
    ASSERT_EQ(kairos_motion_cast(box, &spin, box, &far, nullptr, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 0);
    EXPECT_EQ(r.toi, 1);
    EXPECT_EQ(r.termination, KAIROS_TERMINATION_SEPARATED);
}

TEST_F(Shapes, BadInputLeavesOutputUntouched) {
    kairos_motion bad{{{0, 0, 0}, {0, 0, 0, 1}}, {{0, 0, 0}, {0, 0, 0, 2}}};  // not a unit quaternion
    const kairos_motion ok{{{0, 0, 0}, {0, 0, 0, 1}}, {{1, 0, 0}, {0, 0, 0, 1}}};
    kairos_cast_result r;
    std::memset(&r, 0xab, sizeof r);
    kairos_cast_result r0 = r;
    EXPECT_EQ(kairos_motion_cast(box, &bad, box, &ok, nullptr, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::memcmp(&r, &r0, sizeof r), 0);
    bad.end.position.x = NAN;
    bad.end.orientation = {0, 0, 0, 1};
    EXPECT_EQ(kairos_motion_cast(box, &ok, box, &bad, nullptr, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::memcmp(&r, &r0, sizeof r), 0);
}
