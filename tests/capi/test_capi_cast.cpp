// SPDX-License-Identifier: MIT
// kairos_ray_cast and kairos_shape_cast through the shared library: results, conventions (frames,
// normal direction, overlap at the start), and outputs left untouched on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "kairos/kairos.h"

namespace {

kairos_pose at(double x, double y, double z) { return {{x, y, z}, {0, 0, 0, 1}}; }

struct Shapes : ::testing::Test {
    kairos_shape* box = nullptr;
    kairos_shape* sphere = nullptr;
    void SetUp() override {
        ASSERT_EQ(kairos_shape_box({1, 1, 1}, &box), KAIROS_OK);
        ASSERT_EQ(kairos_shape_sphere(0.5, &sphere), KAIROS_OK);
    }
    void TearDown() override {
        kairos_shape_release(box);
        kairos_shape_release(sphere);
    }
};

}  // namespace

TEST_F(Shapes, ShapeCastFindsTheTunnellingHit) {
    // A sphere crossing a thin region in one step: both end poses are clear of the box, the cast
    // finds the contact at toi = (10 - 1 - 0.5) / 20.
    const kairos_pose pa = at(0, 0, 0), pb = at(-10, 0.2, 0);
    kairos_cast_result r;
    ASSERT_EQ(kairos_shape_cast(box, &pa, {0, 0, 0}, sphere, &pb, {20, 0, 0}, nullptr, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 1);
    EXPECT_NEAR(r.toi, 8.5 / 20, 1e-12);
    EXPECT_NEAR(r.normal.x, -1, 1e-9);  // from A (the box) toward B (the sphere, coming from -x)
    EXPECT_NEAR(r.point.x, -1, 1e-9);
    EXPECT_NEAR(r.point.y, 0.2, 1e-9);
    EXPECT_EQ(r.termination, KAIROS_TERMINATION_HIT);
    EXPECT_GT(r.iterations, 0u);
}

TEST_F(Shapes, MissOverlapAndRay) {
    kairos_query_settings s;
    kairos_query_settings_init(&s);
    s.tolerance = 1e-6;
    const kairos_pose pa = at(100, 0, 0), pb = at(100, 5, 0);
    kairos_cast_result r;
    ASSERT_EQ(kairos_shape_cast(box, &pa, {0, 0, 0}, box, &pb, {10, 0, 0}, &s, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 0);
    EXPECT_EQ(r.toi, 1);
    EXPECT_EQ(r.termination, KAIROS_TERMINATION_SEPARATED);
    // Overlap at the start: toi 0, normal along the minimum translation (+x: the boxes overlap
    // least along x), whatever the relative motion.
    const kairos_pose pc = at(100.5, 0, 0);
    ASSERT_EQ(kairos_shape_cast(box, &pa, {0, 0, 0}, box, &pc, {0, 2, 0}, &s, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 1);
    EXPECT_EQ(r.toi, 0);
    EXPECT_NEAR(r.normal.x, 1, 1e-12);
    // Ray cast: outward normal, hit point on the surface.
    ASSERT_EQ(kairos_ray_cast(sphere, &pa, {90, 0, 0}, {20, 0, 0}, nullptr, &r), KAIROS_OK);
    EXPECT_EQ(r.hit, 1);
    EXPECT_NEAR(r.toi, 9.5 / 20, 1e-12);
    EXPECT_NEAR(r.normal.x, -1, 1e-9);
    EXPECT_NEAR(r.point.x, 99.5, 1e-9);
}

TEST_F(Shapes, BadInputLeavesTheResultUntouched) {
    const kairos_pose p = at(0, 0, 0);
    kairos_cast_result r;
    std::memset(&r, 0xAB, sizeof r);
    kairos_cast_result before = r;
    EXPECT_EQ(kairos_shape_cast(box, &p, {NAN, 0, 0}, box, &p, {1, 0, 0}, nullptr, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(kairos_last_error(), "translation_a"), nullptr);
    EXPECT_EQ(std::memcmp(&r, &before, sizeof r), 0);
    EXPECT_EQ(kairos_ray_cast(nullptr, &p, {0, 0, 0}, {1, 0, 0}, nullptr, &r), KAIROS_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(kairos_ray_cast(box, &p, {0, 0, 0}, {INFINITY, 0, 0}, nullptr, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(kairos_last_error(), "kairos_ray_cast"), nullptr);
    EXPECT_EQ(std::memcmp(&r, &before, sizeof r), 0);
    kairos_query_settings s;
    kairos_query_settings_init(&s);
    s.tolerance = 0;
    EXPECT_EQ(kairos_shape_cast(box, &p, {0, 0, 0}, box, &p, {1, 0, 0}, &s, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::memcmp(&r, &before, sizeof r), 0);
}
