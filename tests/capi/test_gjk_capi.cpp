// SPDX-License-Identifier: MIT
// kairos_distance and kairos_intersect through the shared library's C ABI: answers against closed
// forms, the axis cache round trip, and rejected input leaving outputs untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "kairos/kairos.h"

namespace {

struct Shape {
    kairos_shape* s = nullptr;
    ~Shape() { kairos_shape_release(s); }
};

kairos_pose pose_at(double x, double y, double z) { return {{x, y, z}, {0, 0, 0, 1}}; }

}  // namespace

TEST(GjkCapi, BoxBoxDistanceAndIntersect) {
    Shape box;
    ASSERT_EQ(kairos_shape_box({1, 1, 1}, &box.s), KAIROS_OK);
    const kairos_pose pa = pose_at(0, 0, 0), pb = pose_at(5, 0.5, -0.25);
    kairos_distance_result r;
    ASSERT_EQ(kairos_distance(box.s, &pa, box.s, &pb, nullptr, &r), KAIROS_OK);
    EXPECT_NEAR(r.distance, 3.0, 1e-14);
    EXPECT_EQ(r.intersecting, 0);
    EXPECT_NEAR(r.axis.x, 1.0, 1e-14);
    EXPECT_NEAR(r.point_a.x, 1.0, 1e-14);
    EXPECT_NEAR(r.point_b.x, 4.0, 1e-14);
    EXPECT_EQ(r.termination, KAIROS_TERMINATION_RELATIVE_ERROR);
    EXPECT_GE(r.iterations, 1u);

    // NULL poses are the identity: the same box twice overlaps.
    ASSERT_EQ(kairos_distance(box.s, nullptr, box.s, nullptr, nullptr, &r), KAIROS_OK);
    EXPECT_EQ(r.intersecting, 1);
    EXPECT_EQ(r.distance, 0);

    // The axis cache: a fresh start finds an axis; passing it again separates in one step.
    kairos_vec3 axis{0, 0, 0};
    int32_t hit = -1;
    ASSERT_EQ(kairos_intersect(box.s, &pa, box.s, &pb, &axis, &hit), KAIROS_OK);
    EXPECT_EQ(hit, 0);
    EXPECT_NEAR(std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z), 1.0, 1e-12);
    EXPECT_GT(axis.x, 0);
    const kairos_pose near = pose_at(1.5, 0, 0);
    const kairos_vec3 before = axis;
    ASSERT_EQ(kairos_intersect(box.s, &pa, box.s, &near, &axis, &hit), KAIROS_OK);
    EXPECT_EQ(hit, 1);
    EXPECT_EQ(std::memcmp(&before, &axis, sizeof axis), 0);  // no separating axis: cache kept
    ASSERT_EQ(kairos_intersect(box.s, &pa, box.s, &near, nullptr, &hit), KAIROS_OK);
    EXPECT_EQ(hit, 1);
    kairos_vec3 nan_axis{NAN, 0, 0};
    ASSERT_EQ(kairos_intersect(box.s, &pa, box.s, &pb, &nan_axis, &hit), KAIROS_OK);
    EXPECT_EQ(hit, 0);
    EXPECT_TRUE(std::isfinite(nan_axis.x));
}

TEST(GjkCapi, RoundShapesAndSettings) {
    Shape sphere, capsule;
    ASSERT_EQ(kairos_shape_sphere(0.5, &sphere.s), KAIROS_OK);
    ASSERT_EQ(kairos_shape_capsule(0.25, 1.0, &capsule.s), KAIROS_OK);
    const kairos_pose ps = pose_at(2, 0, 0.5), pc = pose_at(0, 0, 0);
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    EXPECT_EQ(qs.tolerance, 1e-10);
    EXPECT_EQ(qs.max_iterations, 256u);
    kairos_distance_result r;
    ASSERT_EQ(kairos_distance(sphere.s, &ps, capsule.s, &pc, &qs, &r), KAIROS_OK);
    EXPECT_NEAR(r.distance, 2 - 0.75, 1e-14);
    EXPECT_NEAR(r.axis.x, -1, 1e-14);  // from the sphere toward the capsule
    qs.max_iterations = 1;
    kairos_shape* b = nullptr;
    ASSERT_EQ(kairos_shape_box({1, 2, 3}, &b), KAIROS_OK);
    const kairos_pose turned = {{4, 1, 0}, {0.2, 0.3, 0.1, std::sqrt(1 - 0.04 - 0.09 - 0.01)}};
    ASSERT_EQ(kairos_distance(b, &pc, b, &turned, &qs, &r), KAIROS_OK);
    EXPECT_EQ(r.iterations, 1u);
    EXPECT_EQ(r.termination, KAIROS_TERMINATION_MAX_ITERATIONS);
    EXPECT_TRUE(std::isfinite(r.distance));
    kairos_shape_release(b);
}

TEST(GjkCapi, BadInputLeavesOutputsUntouched) {
    Shape box;
    ASSERT_EQ(kairos_shape_box({1, 1, 1}, &box.s), KAIROS_OK);
    const kairos_pose p = pose_at(0, 0, 0);
    kairos_pose bad = pose_at(NAN, 0, 0);
    kairos_distance_result r;
    std::memset(&r, 0x5a, sizeof r);
    kairos_distance_result r0;
    std::memcpy(&r0, &r, sizeof r);
    EXPECT_EQ(kairos_distance(box.s, &bad, box.s, &p, nullptr, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(kairos_distance(nullptr, &p, box.s, &p, nullptr, &r), KAIROS_ERROR_NULL_ARGUMENT);
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    qs.tolerance = -1;
    EXPECT_EQ(kairos_distance(box.s, &p, box.s, &p, &qs, &r), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::memcmp(&r, &r0, sizeof r), 0);
    int32_t hit = 7;
    kairos_vec3 axis{1, 2, 3};
    EXPECT_EQ(kairos_intersect(box.s, &p, box.s, &bad, &axis, &hit), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(hit, 7);
    EXPECT_EQ(axis.x, 1);
    EXPECT_NE(std::strlen(kairos_last_error()), 0u);
}
