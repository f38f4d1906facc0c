// SPDX-License-Identifier: MIT
// Bad input for every exported function: the right status, a message naming the argument, and
// outputs left untouched. Runs through the shared library, as callers do.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <thread>

#include "kairos/kairos.h"

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Checks status and that the thread's message names `argument`.
::testing::AssertionResult Rejected(int32_t status, int32_t expected, const char* argument) {
    if (status != expected)
        return ::testing::AssertionFailure()
               << "status " << kairos_status_name(status) << ", expected " << kairos_status_name(expected)
               << " (message: " << kairos_last_error() << ")";
    const std::string message = kairos_last_error();
    if (message.find(argument) == std::string::npos)
        return ::testing::AssertionFailure() << "message '" << message << "' does not name '" << argument << "'";
    return ::testing::AssertionSuccess();
}

// A sentinel handle: a failed constructor must leave it exactly as it was.
kairos_shape* const kSentinel = reinterpret_cast<kairos_shape*>(static_cast<uintptr_t>(0x5eed));

struct Shapes : ::testing::Test {
    kairos_shape* box = nullptr;
    void SetUp() override { ASSERT_EQ(kairos_shape_box({1, 2, 3}, &box), KAIROS_OK); }
    void TearDown() override { kairos_shape_release(box); }
};

kairos_pose identity() { return {{0, 0, 0}, {0, 0, 0, 1}}; }

}  // namespace

TEST(Library, VersionMatchesHeader) { EXPECT_EQ(kairos_version(), static_cast<uint32_t>(KAIROS_VERSION_NUMBER)); }

TEST(Library, StatusNamesForEveryValue) {
    const struct {
        int32_t v;
        const char* name;
    } known[] = {
        {KAIROS_OK, "KAIROS_OK"},
        {KAIROS_ERROR_NULL_ARGUMENT, "KAIROS_ERROR_NULL_ARGUMENT"},
        {KAIROS_ERROR_INVALID_ARGUMENT, "KAIROS_ERROR_INVALID_ARGUMENT"},
        {KAIROS_ERROR_STRUCT_SIZE, "KAIROS_ERROR_STRUCT_SIZE"},
        {KAIROS_ERROR_DEGENERATE, "KAIROS_ERROR_DEGENERATE"},
        {KAIROS_ERROR_STALE_ID, "KAIROS_ERROR_STALE_ID"},
        {KAIROS_ERROR_OUT_OF_MEMORY, "KAIROS_ERROR_OUT_OF_MEMORY"},
        {KAIROS_ERROR_NOT_IMPLEMENTED, "KAIROS_ERROR_NOT_IMPLEMENTED"},
        {KAIROS_ERROR_UNSUPPORTED_VERSION, "KAIROS_ERROR_UNSUPPORTED_VERSION"},
        {KAIROS_ERROR_INTERNAL, "KAIROS_ERROR_INTERNAL"},
        {KAIROS_ERROR_LIMIT, "KAIROS_ERROR_LIMIT"},
    };
    for (const auto& k : known) EXPECT_STREQ(kairos_status_name(k.v), k.name);
    for (int32_t v : {1, -11, 1000, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max()})
        EXPECT_STREQ(kairos_status_name(v), "KAIROS_UNKNOWN_STATUS") << v;
    // The values are part of the ABI and never renumbered.
    EXPECT_EQ(KAIROS_ERROR_NOT_IMPLEMENTED, -7);
    EXPECT_EQ(KAIROS_ERROR_LIMIT, -10);
}

TEST(Library, MessageStartsWithTheFunctionName) {
    kairos_shape* s = kSentinel;
    ASSERT_EQ(kairos_shape_cylinder(1, -3, &s), KAIROS_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::string(kairos_last_error()).rfind("kairos_shape_cylinder: half_height", 0), 0u)
        << kairos_last_error();
    ASSERT_EQ(kairos_world_remove(nullptr, 1), KAIROS_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(std::string(kairos_last_error()).rfind("kairos_world_remove: w", 0), 0u) << kairos_last_error();
    const kairos_api* api = nullptr;
    ASSERT_EQ(kairos_get_api(0, &api), KAIROS_ERROR_UNSUPPORTED_VERSION);
    EXPECT_EQ(std::string(kairos_last_error()).rfind("kairos_get_api: abi_version 0", 0), 0u) << kairos_last_error();
}

TEST(Library, LastErrorIsPerThreadAndStartsEmpty) {
    kairos_shape* s = kSentinel;
    ASSERT_NE(kairos_shape_sphere(-1, &s), KAIROS_OK);
    const std::string mine = kairos_last_error();
    EXPECT_NE(mine.find("radius"), std::string::npos);
    std::string other_first, other_after;
    std::thread t([&] {
        other_first = kairos_last_error();
        kairos_shape* b = nullptr;
        kairos_shape_box({1, kNaN, 1}, &b);
        other_after = kairos_last_error();
    });
    t.join();
    EXPECT_EQ(other_first, "");
    EXPECT_NE(other_after.find("half_extents.y"), std::string::npos) << other_after;
    EXPECT_EQ(std::string(kairos_last_error()), mine);  // the other thread's failure is not ours
    // A successful call leaves the message as it was.
    kairos_shape* ok = nullptr;
    ASSERT_EQ(kairos_shape_sphere(1, &ok), KAIROS_OK);
    kairos_shape_release(ok);
    EXPECT_EQ(std::string(kairos_last_error()), mine);
}

TEST(Library, GetApi) {
    const kairos_api* api = nullptr;
    EXPECT_TRUE(Rejected(kairos_get_api(KAIROS_ABI_VERSION, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    for (uint32_t bad : {0u, KAIROS_ABI_VERSION + 1, 0xffffffffu}) {
        EXPECT_TRUE(Rejected(kairos_get_api(bad, &api), KAIROS_ERROR_UNSUPPORTED_VERSION, "abi_version"));
        EXPECT_EQ(api, nullptr);
    }
    // Version 1: the 0.1 table's size, and the 0.1 settings init (it writes only the 0.1 struct).
    ASSERT_EQ(kairos_get_api(1, &api), KAIROS_OK);
    ASSERT_NE(api, nullptr);
    EXPECT_EQ(api->struct_size, offsetof(kairos_api, shape_triangle));
    EXPECT_NE(api->world_settings_init, &kairos_world_settings_init);
    kairos_world_settings s;
    std::memset(&s, 0xA5, sizeof s);
    api->world_settings_init(&s);
    EXPECT_EQ(s.struct_size, offsetof(kairos_world_settings, worker_count));
    EXPECT_EQ(s.worker_count, 0xA5A5A5A5u);  // beyond the 0.1 struct: untouched
    ASSERT_EQ(kairos_get_api(KAIROS_ABI_VERSION, &api), KAIROS_OK);
    ASSERT_NE(api, nullptr);
    EXPECT_EQ(api->struct_size, sizeof(kairos_api));
    EXPECT_EQ(api->abi_version, KAIROS_ABI_VERSION);
    EXPECT_EQ(api->world_settings_init, &kairos_world_settings_init);
    EXPECT_EQ(api->world_query_box, &kairos_world_query_box);
    // Every entry is set and is the exported function of the same name.
    EXPECT_EQ(api->status_name, &kairos_status_name);
    EXPECT_EQ(api->shape_sphere, &kairos_shape_sphere);
    EXPECT_EQ(api->distance, &kairos_distance);
    EXPECT_EQ(api->motion_cast, &kairos_motion_cast);
    EXPECT_EQ(api->world_step_stats, &kairos_world_step_stats);
    EXPECT_EQ(api->world_set_filter, &kairos_world_set_filter);
    EXPECT_EQ(api->world_get_user_data, &kairos_world_get_user_data);
    const size_t first = offsetof(kairos_api, status_name);
    const size_t n = (sizeof(kairos_api) - first) / sizeof(void (*)(void));
    for (size_t i = 0; i < n; ++i) {
        void (*fn)(void);
        std::memcpy(&fn, reinterpret_cast<const char*>(api) + first + i * sizeof fn, sizeof fn);
        EXPECT_NE(fn, nullptr) << "entry " << i;
    }
}

TEST(ShapeInput, PrimitiveSizes) {
    kairos_shape* s = kSentinel;
    for (double bad : {-1.0, 0.0, kNaN, kInf, -kInf}) {
        SCOPED_TRACE(bad);
        EXPECT_TRUE(Rejected(kairos_shape_sphere(bad, &s), KAIROS_ERROR_INVALID_ARGUMENT, "radius"));
        EXPECT_TRUE(Rejected(kairos_shape_box({1, 1, bad}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "half_extents.z"));
        EXPECT_TRUE(Rejected(kairos_shape_box({bad, 1, 1}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "half_extents.x"));
        EXPECT_TRUE(Rejected(kairos_shape_capsule(bad, 1, &s), KAIROS_ERROR_INVALID_ARGUMENT, "radius"));
        EXPECT_TRUE(Rejected(kairos_shape_cylinder(1, bad, &s), KAIROS_ERROR_INVALID_ARGUMENT, "half_height"));
        EXPECT_TRUE(Rejected(kairos_shape_cylinder(bad, 1, &s), KAIROS_ERROR_INVALID_ARGUMENT, "radius"));
        EXPECT_TRUE(Rejected(kairos_shape_cone(1, bad, &s), KAIROS_ERROR_INVALID_ARGUMENT, "half_height"));
        EXPECT_TRUE(Rejected(kairos_shape_cone(bad, 1, &s), KAIROS_ERROR_INVALID_ARGUMENT, "radius"));
        EXPECT_TRUE(Rejected(kairos_shape_segment(bad, &s), KAIROS_ERROR_INVALID_ARGUMENT, "half_length"));
        if (bad != 0.0) {  // a zero half_height capsule is a sphere, allowed
            EXPECT_TRUE(Rejected(kairos_shape_capsule(1, bad, &s), KAIROS_ERROR_INVALID_ARGUMENT, "half_height"));
        }
    }
    EXPECT_EQ(s, kSentinel);
    // The message carries the bad value.
    kairos_shape_sphere(-2.5, &s);
    EXPECT_NE(std::string(kairos_last_error()).find("-2.5"), std::string::npos) << kairos_last_error();

    EXPECT_TRUE(Rejected(kairos_shape_sphere(1, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_box({1, 1, 1}, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_capsule(1, 1, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_cylinder(1, 1, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_cone(1, 1, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_point(nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_segment(1, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));

    kairos_shape* capsule0 = nullptr;
    EXPECT_EQ(kairos_shape_capsule(1, 0, &capsule0), KAIROS_OK);
    kairos_shape_release(capsule0);
}

TEST(ShapeInput, ConvexHullPoints) {
    kairos_shape* s = kSentinel;
    const kairos_vec3 tetra[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(nullptr, 4, &s), KAIROS_ERROR_NULL_ARGUMENT, "points"));
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(tetra, 4, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(nullptr, 0, &s), KAIROS_ERROR_DEGENERATE, "count"));
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(tetra, 0, &s), KAIROS_ERROR_DEGENERATE, "count"));
    kairos_vec3 bad[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    bad[2].y = kNaN;
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(bad, 5, &s), KAIROS_ERROR_INVALID_ARGUMENT, "points[2].y"));
    bad[2].y = 1;
    bad[4].z = -kInf;
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(bad, 5, &s), KAIROS_ERROR_INVALID_ARGUMENT, "points[4].z"));
    bad[4].z = 2e100;  // finite, beyond KAIROS_MAX_MAGNITUDE
    EXPECT_TRUE(Rejected(kairos_shape_convex_hull(bad, 5, &s), KAIROS_ERROR_INVALID_ARGUMENT, "points[4].z"));
    EXPECT_EQ(s, kSentinel);
}

// Regression (fuzzer): a subnormal direction underflowed both of a cone's candidate scores to 0
// and the apex won over the rim; huge and tiny directions now pick the unit direction's point.
TEST(ShapeInput, SupportOfTinyAndHugeDirections) {
    kairos_shape* cone = nullptr;
    ASSERT_EQ(kairos_shape_cone(0.0041641107804989705, 1.0049439230945296, &cone), KAIROS_OK);
    kairos_vec3 unit{}, p{};
    ASSERT_EQ(kairos_shape_support(cone, {1, 0, 0}, &unit), KAIROS_OK);
    for (double scale : {1e-300, 1e-310, 4.0513382958982217e-322, 1e300, 1.7e308}) {
        ASSERT_EQ(kairos_shape_support(cone, {scale, 0, 0}, &p), KAIROS_OK);
        EXPECT_EQ(p.x, unit.x) << scale;
        EXPECT_EQ(p.z, unit.z) << scale;
    }
    kairos_shape_release(cone);
}

TEST(ShapeInput, TriangleCorners) {
    kairos_shape* s = kSentinel;
    const kairos_vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
    EXPECT_TRUE(Rejected(kairos_shape_triangle(a, b, c, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_triangle(a, {kNaN, 0, 0}, c, &s), KAIROS_ERROR_INVALID_ARGUMENT, "b.x"));
    EXPECT_TRUE(Rejected(kairos_shape_triangle(a, b, {0, 0, -kInf}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "c.z"));
    EXPECT_TRUE(Rejected(kairos_shape_triangle({0, -1e101, 0}, b, c, &s), KAIROS_ERROR_INVALID_ARGUMENT, "a.y"));
    EXPECT_TRUE(Rejected(kairos_shape_triangle(a, b, {2, 0, 0}, &s), KAIROS_ERROR_DEGENERATE, "collinear"));
    EXPECT_TRUE(Rejected(kairos_shape_triangle(a, a, c, &s), KAIROS_ERROR_DEGENERATE, "collinear"));
    EXPECT_TRUE(Rejected(kairos_shape_triangle(a, b, {0.5, 1e-12, 0}, &s), KAIROS_ERROR_DEGENERATE, "collinear"));
    EXPECT_EQ(s, kSentinel);
    ASSERT_EQ(kairos_shape_triangle(a, b, {0.5, 1e-9, 0}, &s), KAIROS_OK);  // thin, still a triangle
    kairos_shape_release(s);
}

TEST_F(Shapes, Composites) {
    kairos_shape* s = kSentinel;
    EXPECT_TRUE(Rejected(kairos_shape_minkowski_sum(nullptr, box, &s), KAIROS_ERROR_NULL_ARGUMENT, "a"));
    EXPECT_TRUE(Rejected(kairos_shape_minkowski_sum(box, nullptr, &s), KAIROS_ERROR_NULL_ARGUMENT, "b"));
    EXPECT_TRUE(Rejected(kairos_shape_minkowski_sum(box, box, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_shape_hull(nullptr, box, &s), KAIROS_ERROR_NULL_ARGUMENT, "a"));
    EXPECT_TRUE(Rejected(kairos_shape_hull(box, nullptr, &s), KAIROS_ERROR_NULL_ARGUMENT, "b"));
    EXPECT_TRUE(Rejected(kairos_shape_hull(box, box, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));

    double m[9] = {2, 0, 0, 0, 1, 0, 0, 0, 0.5};
    EXPECT_TRUE(Rejected(kairos_shape_transformed(nullptr, m, {0, 0, 0}, &s), KAIROS_ERROR_NULL_ARGUMENT, "s"));
    EXPECT_TRUE(Rejected(kairos_shape_transformed(box, nullptr, {0, 0, 0}, &s), KAIROS_ERROR_NULL_ARGUMENT, "linear"));
    EXPECT_TRUE(Rejected(kairos_shape_transformed(box, m, {0, 0, 0}, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(
        Rejected(kairos_shape_transformed(box, m, {0, kInf, 0}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "translation.y"));
    m[4] = kNaN;
    EXPECT_TRUE(Rejected(kairos_shape_transformed(box, m, {0, 0, 0}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "linear[4]"));
    const double singular[9] = {1, 2, 3, 2, 4, 6, 0, 0, 1};
    EXPECT_TRUE(
        Rejected(kairos_shape_transformed(box, singular, {0, 0, 0}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "singular"));
    const double zero[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    EXPECT_TRUE(
        Rejected(kairos_shape_transformed(box, zero, {0, 0, 0}, &s), KAIROS_ERROR_INVALID_ARGUMENT, "singular"));
    EXPECT_EQ(s, kSentinel);
    // A tiny but well-conditioned matrix (uniform scale 1e-9, mirrored) is fine.
    const double tiny[9] = {-1e-9, 0, 0, 0, 1e-9, 0, 0, 0, 1e-9};
    kairos_shape* t = nullptr;
    ASSERT_EQ(kairos_shape_transformed(box, tiny, {1, 2, 3}, &t), KAIROS_OK);
    kairos_vec3 p{};
    ASSERT_EQ(kairos_shape_support(t, {1, 1, 1}, &p), KAIROS_OK);
    EXPECT_DOUBLE_EQ(p.x, 1 + 1e-9);  // mirrored x: the support takes the -x corner, mapped to +1e-9
    kairos_shape_release(t);

    kairos_shape_retain(nullptr);
    kairos_shape_release(nullptr);
}

TEST_F(Shapes, SupportAndBounds) {
    kairos_vec3 out{7, 7, 7};
    EXPECT_TRUE(Rejected(kairos_shape_support(nullptr, {1, 0, 0}, &out), KAIROS_ERROR_NULL_ARGUMENT, "s"));
    EXPECT_TRUE(Rejected(kairos_shape_support(box, {1, kNaN, 0}, &out), KAIROS_ERROR_INVALID_ARGUMENT, "direction.y"));
    EXPECT_TRUE(Rejected(kairos_shape_support(box, {kInf, 0, 0}, &out), KAIROS_ERROR_INVALID_ARGUMENT, "direction.x"));
    EXPECT_TRUE(Rejected(kairos_shape_support(box, {1, 0, 0}, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_EQ(out.x, 7);

    kairos_vec3 lo{7, 7, 7}, hi{7, 7, 7};
    kairos_pose p = identity();
    EXPECT_TRUE(Rejected(kairos_shape_bounds(nullptr, &p, &lo, &hi), KAIROS_ERROR_NULL_ARGUMENT, "s"));
    EXPECT_TRUE(Rejected(kairos_shape_bounds(box, &p, nullptr, &hi), KAIROS_ERROR_NULL_ARGUMENT, "min"));
    EXPECT_TRUE(Rejected(kairos_shape_bounds(box, &p, &lo, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "max"));
    p.position.z = kNaN;
    EXPECT_TRUE(Rejected(kairos_shape_bounds(box, &p, &lo, &hi), KAIROS_ERROR_INVALID_ARGUMENT, "pose.position.z"));
    p = identity();
    p.orientation.w = kInf;
    EXPECT_TRUE(Rejected(kairos_shape_bounds(box, &p, &lo, &hi), KAIROS_ERROR_INVALID_ARGUMENT, "pose.orientation.w"));
    p.orientation = {0, 0, 0, 1.01};
    EXPECT_TRUE(Rejected(kairos_shape_bounds(box, &p, &lo, &hi), KAIROS_ERROR_INVALID_ARGUMENT, "unit quaternion"));
    p.orientation = {0, 0, 0, 0};
    EXPECT_TRUE(Rejected(kairos_shape_bounds(box, &p, &lo, &hi), KAIROS_ERROR_INVALID_ARGUMENT, "pose.orientation"));
    EXPECT_EQ(lo.x, 7);
    EXPECT_EQ(hi.z, 7);
    // Within the documented tolerance the quaternion is accepted (and normalised).
    p.orientation = {0, 0, 0, 1 + 0.5 * KAIROS_QUAT_TOLERANCE};
    ASSERT_EQ(kairos_shape_bounds(box, &p, &lo, &hi), KAIROS_OK);
    EXPECT_DOUBLE_EQ(hi.z, 3);
    ASSERT_EQ(kairos_shape_bounds(box, nullptr, &lo, &hi), KAIROS_OK);  // NULL pose: identity
    EXPECT_EQ(lo.y, -2);
}

TEST_F(Shapes, QueriesCheckEveryArgument) {
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    kairos_query_settings_init(nullptr);
    EXPECT_EQ(qs.struct_size, sizeof qs);
    EXPECT_GT(qs.tolerance, 0);
    EXPECT_LE(qs.tolerance, 1e-9);
    EXPECT_GE(qs.max_iterations, 1u);

    kairos_pose p = identity();
    kairos_pose bad = identity();
    bad.orientation = {1, 1, 0, 0};
    // kairos_distance and kairos_signed_distance check the same arguments alike; the message names
    // the function too.
    kairos_query_settings bs = qs;
    for (const auto query : {kairos_distance, kairos_signed_distance}) {
        kairos_distance_result dr;
        std::memset(&dr, 0xab, sizeof dr);
        const kairos_distance_result dr0 = dr;
        EXPECT_TRUE(Rejected(query(nullptr, &p, box, &p, &qs, &dr), KAIROS_ERROR_NULL_ARGUMENT, "a"));
        EXPECT_TRUE(Rejected(query(box, &p, nullptr, &p, &qs, &dr), KAIROS_ERROR_NULL_ARGUMENT, "b"));
        EXPECT_TRUE(
            Rejected(query(box, &bad, box, &p, &qs, &dr), KAIROS_ERROR_INVALID_ARGUMENT, "pose_a.orientation"));
        EXPECT_TRUE(
            Rejected(query(box, &p, box, &bad, &qs, &dr), KAIROS_ERROR_INVALID_ARGUMENT, "pose_b.orientation"));
        EXPECT_TRUE(Rejected(query(box, &p, box, &p, &qs, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
        bs = qs;
        bs.struct_size = 0;
        EXPECT_TRUE(
            Rejected(query(box, &p, box, &p, &bs, &dr), KAIROS_ERROR_STRUCT_SIZE, "settings->struct_size"));
        bs = qs;
        bs.struct_size = sizeof qs + 8;
        EXPECT_TRUE(
            Rejected(query(box, &p, box, &p, &bs, &dr), KAIROS_ERROR_STRUCT_SIZE, "settings->struct_size"));
        for (double tol : {0.0, -1e-3, 1.0, kNaN, kInf}) {
            bs = qs;
            bs.tolerance = tol;
            EXPECT_TRUE(
                Rejected(query(box, &p, box, &p, &bs, &dr), KAIROS_ERROR_INVALID_ARGUMENT, "settings->tolerance"))
                << tol;
        }
        bs = qs;
        bs.max_iterations = 0;
        EXPECT_TRUE(Rejected(query(box, &p, box, &p, &bs, &dr), KAIROS_ERROR_INVALID_ARGUMENT,
                             "settings->max_iterations"));
        EXPECT_EQ(std::memcmp(&dr, &dr0, sizeof dr), 0);
        EXPECT_TRUE(Rejected(query(nullptr, &p, box, &p, &qs, &dr), KAIROS_ERROR_NULL_ARGUMENT,
                             query == kairos_distance ? "kairos_distance" : "kairos_signed_distance"));
    }

    int32_t hit = 42;
    kairos_vec3 axis{1, 0, 0};
    EXPECT_TRUE(Rejected(kairos_intersect(nullptr, &p, box, &p, &axis, &hit), KAIROS_ERROR_NULL_ARGUMENT, "a"));
    EXPECT_TRUE(Rejected(kairos_intersect(box, &p, nullptr, &p, &axis, &hit), KAIROS_ERROR_NULL_ARGUMENT, "b"));
    EXPECT_TRUE(Rejected(kairos_intersect(box, &bad, box, &p, &axis, &hit), KAIROS_ERROR_INVALID_ARGUMENT, "pose_a"));
    EXPECT_TRUE(Rejected(kairos_intersect(box, &p, box, &p, &axis, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_EQ(hit, 42);
    EXPECT_EQ(axis.x, 1);

    kairos_cast_result cr;
    std::memset(&cr, 0xcd, sizeof cr);
    const kairos_cast_result cr0 = cr;
    EXPECT_TRUE(
        Rejected(kairos_ray_cast(nullptr, &p, {0, 0, 0}, {1, 0, 0}, &qs, &cr), KAIROS_ERROR_NULL_ARGUMENT, "s"));
    EXPECT_TRUE(
        Rejected(kairos_ray_cast(box, &bad, {0, 0, 0}, {1, 0, 0}, &qs, &cr), KAIROS_ERROR_INVALID_ARGUMENT, "pose"));
    EXPECT_TRUE(Rejected(kairos_ray_cast(box, &p, {kNaN, 0, 0}, {1, 0, 0}, &qs, &cr), KAIROS_ERROR_INVALID_ARGUMENT,
                         "origin.x"));
    EXPECT_TRUE(Rejected(kairos_ray_cast(box, &p, {0, 0, 0}, {1, 0, kInf}, &qs, &cr), KAIROS_ERROR_INVALID_ARGUMENT,
                         "translation.z"));
    EXPECT_TRUE(Rejected(kairos_ray_cast(box, &p, {0, 0, 0}, {1, 0, 0}, &bs, &cr), KAIROS_ERROR_INVALID_ARGUMENT,
                         "settings->max_iterations"));
    EXPECT_TRUE(
        Rejected(kairos_ray_cast(box, &p, {0, 0, 0}, {1, 0, 0}, &qs, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));

    EXPECT_TRUE(Rejected(kairos_shape_cast(nullptr, &p, {1, 0, 0}, box, &p, {0, 0, 0}, &qs, &cr),
                         KAIROS_ERROR_NULL_ARGUMENT, "a"));
    EXPECT_TRUE(Rejected(kairos_shape_cast(box, &p, {1, 0, 0}, nullptr, &p, {0, 0, 0}, &qs, &cr),
                         KAIROS_ERROR_NULL_ARGUMENT, "b"));
    EXPECT_TRUE(Rejected(kairos_shape_cast(box, &p, {kNaN, 0, 0}, box, &p, {0, 0, 0}, &qs, &cr),
                         KAIROS_ERROR_INVALID_ARGUMENT, "translation_a.x"));
    EXPECT_TRUE(Rejected(kairos_shape_cast(box, &p, {1, 0, 0}, box, &p, {0, -kInf, 0}, &qs, &cr),
                         KAIROS_ERROR_INVALID_ARGUMENT, "translation_b.y"));
    EXPECT_TRUE(Rejected(kairos_shape_cast(box, &p, {1, 0, 0}, box, &bad, {0, 0, 0}, &qs, &cr),
                         KAIROS_ERROR_INVALID_ARGUMENT, "pose_b"));
    EXPECT_TRUE(Rejected(kairos_shape_cast(box, &p, {1, 0, 0}, box, &p, {0, 0, 0}, &qs, nullptr),
                         KAIROS_ERROR_NULL_ARGUMENT, "out"));

    kairos_motion m{p, p};
    kairos_motion mbad{p, bad};
    EXPECT_TRUE(Rejected(kairos_motion_cast(nullptr, &m, box, &m, &qs, &cr), KAIROS_ERROR_NULL_ARGUMENT, "a"));
    EXPECT_TRUE(Rejected(kairos_motion_cast(box, nullptr, box, &m, &qs, &cr), KAIROS_ERROR_NULL_ARGUMENT, "motion_a"));
    EXPECT_TRUE(Rejected(kairos_motion_cast(box, &m, box, nullptr, &qs, &cr), KAIROS_ERROR_NULL_ARGUMENT, "motion_b"));
    EXPECT_TRUE(
        Rejected(kairos_motion_cast(box, &mbad, box, &m, &qs, &cr), KAIROS_ERROR_INVALID_ARGUMENT, "motion_a.end"));
    EXPECT_TRUE(
        Rejected(kairos_motion_cast(box, &m, box, &mbad, &qs, &cr), KAIROS_ERROR_INVALID_ARGUMENT, "motion_b.end"));
    EXPECT_TRUE(Rejected(kairos_motion_cast(box, &m, box, &m, &qs, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_EQ(std::memcmp(&cr, &cr0, sizeof cr), 0);
}

TEST(WorldInput, Create) {
    kairos_world* w = reinterpret_cast<kairos_world*>(static_cast<uintptr_t>(0x5eed));
    kairos_world* const w0 = w;
    kairos_world_settings s;
    kairos_world_settings_init(&s);
    kairos_world_settings_init(nullptr);
    EXPECT_EQ(s.struct_size, sizeof s);
    EXPECT_EQ(s.broad_phase, KAIROS_BROAD_PHASE_SPACETIME_SAP);
    EXPECT_EQ(s.query.struct_size, sizeof(kairos_query_settings));
    EXPECT_TRUE(Rejected(kairos_world_create(&s, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    kairos_world_settings b = s;
    b.struct_size = 4;
    EXPECT_TRUE(Rejected(kairos_world_create(&b, &w), KAIROS_ERROR_STRUCT_SIZE, "settings->struct_size"));
    b = s;
    b.broad_phase = 4;
    EXPECT_TRUE(Rejected(kairos_world_create(&b, &w), KAIROS_ERROR_INVALID_ARGUMENT, "settings->broad_phase"));
    b = s;
    b.query.tolerance = kNaN;
    EXPECT_TRUE(Rejected(kairos_world_create(&b, &w), KAIROS_ERROR_INVALID_ARGUMENT, "settings->query->tolerance"));
    b = s;
    b.query.struct_size = 0;
    EXPECT_TRUE(Rejected(kairos_world_create(&b, &w), KAIROS_ERROR_STRUCT_SIZE, "settings->query->struct_size"));
    EXPECT_EQ(w, w0);

    // A caller built against a newer header: a larger struct with a zero tail is accepted,
    // a non-zero tail (a field this library cannot honour) is refused.
    struct Newer {
        kairos_world_settings known;
        double future_field;
    } newer;
    std::memset(&newer, 0, sizeof newer);
    kairos_world_settings_init(&newer.known);
    newer.known.struct_size = sizeof newer;
    ASSERT_EQ(kairos_world_create(&newer.known, &w), KAIROS_OK);
    kairos_world_destroy(w);
    newer.future_field = 1.0;
    w = w0;
    EXPECT_TRUE(Rejected(kairos_world_create(&newer.known, &w), KAIROS_ERROR_STRUCT_SIZE, "non-zero"));
    EXPECT_EQ(w, w0);
    ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);  // NULL settings: defaults
    kairos_world_destroy(w);
    kairos_world_destroy(nullptr);
}

TEST_F(Shapes, WorldObjectsAndIds) {
    kairos_world* w = nullptr;
    ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
    kairos_pose p = identity();
    kairos_pose bad = identity();
    bad.position.x = kNaN;
    kairos_object_id id = 99;
    EXPECT_TRUE(Rejected(kairos_world_add(nullptr, box, &p, 1, &id), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_add(w, nullptr, &p, 1, &id), KAIROS_ERROR_NULL_ARGUMENT, "s"));
    EXPECT_TRUE(Rejected(kairos_world_add(w, box, &bad, 1, &id), KAIROS_ERROR_INVALID_ARGUMENT, "pose.position.x"));
    EXPECT_TRUE(Rejected(kairos_world_add(w, box, &p, 1, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_EQ(id, 99u);

    kairos_object_id a = 0, b = 0;
    ASSERT_EQ(kairos_world_add(w, box, &p, 10, &a), KAIROS_OK);
    ASSERT_EQ(kairos_world_add(w, box, nullptr, 11, &b), KAIROS_OK);
    EXPECT_NE(a, 0u);
    EXPECT_NE(b, 0u);
    EXPECT_NE(a, b);

    for (kairos_object_id stale : {kairos_object_id{0}, a ^ (kairos_object_id{1} << 40), b + 1000}) {
        EXPECT_TRUE(Rejected(kairos_world_remove(w, stale), KAIROS_ERROR_STALE_ID, "id"));
        EXPECT_TRUE(Rejected(kairos_world_set_pose(w, stale, &p), KAIROS_ERROR_STALE_ID, "id"));
        EXPECT_TRUE(Rejected(kairos_world_move(w, stale, &p), KAIROS_ERROR_STALE_ID, "id"));
    }
    EXPECT_TRUE(Rejected(kairos_world_remove(nullptr, a), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_set_pose(w, a, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "pose"));
    EXPECT_TRUE(Rejected(kairos_world_set_pose(w, a, &bad), KAIROS_ERROR_INVALID_ARGUMENT, "pose.position.x"));
    EXPECT_TRUE(Rejected(kairos_world_move(w, a, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "end"));
    EXPECT_TRUE(Rejected(kairos_world_move(w, a, &bad), KAIROS_ERROR_INVALID_ARGUMENT, "end.position.x"));
    EXPECT_EQ(kairos_world_move(w, a, &p), KAIROS_OK);
    EXPECT_EQ(kairos_world_set_pose(w, b, &p), KAIROS_OK);

    // A removed id stays stale even when its slot is reused.
    ASSERT_EQ(kairos_world_remove(w, a), KAIROS_OK);
    EXPECT_TRUE(Rejected(kairos_world_remove(w, a), KAIROS_ERROR_STALE_ID, "id"));
    kairos_object_id c = 0;
    ASSERT_EQ(kairos_world_add(w, box, &p, 12, &c), KAIROS_OK);
    EXPECT_NE(c, a);
    EXPECT_TRUE(Rejected(kairos_world_move(w, a, &p), KAIROS_ERROR_STALE_ID, "id"));
    EXPECT_EQ(kairos_world_move(w, c, &p), KAIROS_OK);

    EXPECT_TRUE(Rejected(kairos_world_step(nullptr), KAIROS_ERROR_NULL_ARGUMENT, "w"));

    const kairos_contact* contacts = nullptr;
    size_t n = 5;
    EXPECT_TRUE(Rejected(kairos_world_contacts(nullptr, &contacts, &n), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_contacts(w, nullptr, &n), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_world_contacts(w, &contacts, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "count"));
    const kairos_object_id* pairs = nullptr;
    EXPECT_TRUE(Rejected(kairos_world_overlaps(nullptr, &pairs, &n), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_overlaps(w, nullptr, &n), KAIROS_ERROR_NULL_ARGUMENT, "pairs"));
    EXPECT_TRUE(Rejected(kairos_world_overlaps(w, &pairs, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "count"));
    EXPECT_EQ(n, 5u);
    ASSERT_EQ(kairos_world_contacts(w, &contacts, &n), KAIROS_OK);
    EXPECT_EQ(n, 0u);  // no step has run

    // The world keeps its shapes alive: releasing ours first is fine.
    kairos_shape* sphere = nullptr;
    ASSERT_EQ(kairos_shape_sphere(0.5, &sphere), KAIROS_OK);
    kairos_object_id d = 0;
    ASSERT_EQ(kairos_world_add(w, sphere, &p, 13, &d), KAIROS_OK);
    kairos_shape_release(sphere);
    kairos_world_destroy(w);
}

TEST(WorldInput, StepStats) {
    kairos_world* w = nullptr;
    ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
    kairos_step_stats s;
    kairos_step_stats_init(&s);
    kairos_step_stats_init(nullptr);
    EXPECT_EQ(s.struct_size, sizeof s);
    EXPECT_TRUE(Rejected(kairos_world_step_stats(nullptr, &s), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_step_stats(w, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    s.struct_size = 0;
    EXPECT_TRUE(Rejected(kairos_world_step_stats(w, &s), KAIROS_ERROR_STRUCT_SIZE, "out->struct_size"));
    // An older caller's smaller struct: the library writes no byte past struct_size.
    unsigned char buffer[sizeof(kairos_step_stats) + 16];
    std::memset(buffer, 0xee, sizeof buffer);
    const uint32_t older = offsetof(kairos_step_stats, swaps);
    std::memcpy(buffer, &older, sizeof older);
    ASSERT_EQ(kairos_world_step_stats(w, reinterpret_cast<kairos_step_stats*>(buffer)), KAIROS_OK);
    for (size_t i = older; i < sizeof buffer; ++i) EXPECT_EQ(buffer[i], 0xee) << "byte " << i;
    kairos_step_stats full;
    kairos_step_stats_init(&full);
    ASSERT_EQ(kairos_world_step_stats(w, &full), KAIROS_OK);
    EXPECT_EQ(full.struct_size, sizeof full);
    EXPECT_EQ(full.broad_phase_pairs, 0u);
    kairos_world_destroy(w);
}

// The filter, static and getter functions: each bad argument named, nothing changed or written.
TEST(WorldInput, FiltersStaticAndGetters) {
    kairos_world* w = nullptr;
    ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
    kairos_shape* ball = nullptr;
    ASSERT_EQ(kairos_shape_sphere(0.5, &ball), KAIROS_OK);
    kairos_pose p{};
    p.orientation.w = 1;
    kairos_object_id id = 0, gone = 0;
    ASSERT_EQ(kairos_world_add(w, ball, &p, 5, &id), KAIROS_OK);
    ASSERT_EQ(kairos_world_add(w, ball, &p, 6, &gone), KAIROS_OK);
    ASSERT_EQ(kairos_world_remove(w, gone), KAIROS_OK);
    const kairos_filter f{2, 0xffffffffu, 0};
    EXPECT_TRUE(Rejected(kairos_world_set_filter(nullptr, id, &f), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_set_filter(w, gone, &f), KAIROS_ERROR_STALE_ID, "id"));
    EXPECT_TRUE(Rejected(kairos_world_set_filter(w, 0, &f), KAIROS_ERROR_STALE_ID, "id"));
    EXPECT_TRUE(Rejected(kairos_world_set_filter(w, id, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "f"));
    EXPECT_TRUE(Rejected(kairos_world_set_static(nullptr, id, 1), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_set_static(w, gone, 1), KAIROS_ERROR_STALE_ID, "id"));
    for (int32_t bad : {2, -1, 1 << 30})
        EXPECT_TRUE(Rejected(kairos_world_set_static(w, id, bad), KAIROS_ERROR_INVALID_ARGUMENT, "is_static"));
    // A refused set_static left the object ordinary: it still moves.
    kairos_pose end = p;
    end.position.x = 1;
    EXPECT_EQ(kairos_world_move(w, id, &end), KAIROS_OK);
    ASSERT_EQ(kairos_world_set_static(w, id, 1), KAIROS_OK);
    EXPECT_TRUE(Rejected(kairos_world_move(w, id, &end), KAIROS_ERROR_INVALID_ARGUMENT, "static"));

    kairos_pose out;
    std::memset(&out, 0x3C, sizeof out);
    const kairos_pose before = out;
    uint64_t user = 99;
    EXPECT_TRUE(Rejected(kairos_world_get_pose(nullptr, id, &out), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_get_pose(w, gone, &out), KAIROS_ERROR_STALE_ID, "id"));
    EXPECT_TRUE(Rejected(kairos_world_get_pose(w, id, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_TRUE(Rejected(kairos_world_get_user_data(nullptr, id, &user), KAIROS_ERROR_NULL_ARGUMENT, "w"));
    EXPECT_TRUE(Rejected(kairos_world_get_user_data(w, gone, &user), KAIROS_ERROR_STALE_ID, "id"));
    EXPECT_TRUE(Rejected(kairos_world_get_user_data(w, id, nullptr), KAIROS_ERROR_NULL_ARGUMENT, "out"));
    EXPECT_EQ(std::memcmp(&out, &before, sizeof out), 0);
    EXPECT_EQ(user, 99u);
    ASSERT_EQ(kairos_world_get_user_data(w, id, &user), KAIROS_OK);
    EXPECT_EQ(user, 5u);
    kairos_shape_release(ball);
    kairos_world_destroy(w);
}
