// SPDX-License-Identifier: MIT
// C API pair queries: distance, intersection, ray cast, shape cast, motion cast.
#include "boundary.hpp"
#include "casts/cast.hpp"
#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "motion/motion_cast.hpp"
#include "results.hpp"

using namespace kairos;
using namespace kairos::capi;

// The core's termination codes are the public ones.
static_assert(int32_t(Termination::None) == KAIROS_TERMINATION_NONE);
static_assert(int32_t(Termination::RelativeError) == KAIROS_TERMINATION_RELATIVE_ERROR);
static_assert(int32_t(Termination::NearContact) == KAIROS_TERMINATION_NEAR_CONTACT);
static_assert(int32_t(Termination::FullSimplex) == KAIROS_TERMINATION_FULL_SIMPLEX);
static_assert(int32_t(Termination::JohnsonFailed) == KAIROS_TERMINATION_JOHNSON_FAILED);
static_assert(int32_t(Termination::RepeatedSupport) == KAIROS_TERMINATION_REPEATED_SUPPORT);
static_assert(int32_t(Termination::NoProgress) == KAIROS_TERMINATION_NO_PROGRESS);
static_assert(int32_t(Termination::MaxIterations) == KAIROS_TERMINATION_MAX_ITERATIONS);
static_assert(int32_t(Termination::Separated) == KAIROS_TERMINATION_SEPARATED);
static_assert(int32_t(Termination::Hit) == KAIROS_TERMINATION_HIT);

namespace {

// The C layout of a cast result whose numbers are all finite (the last guard, see boundary.hpp).
kairos_cast_result checked(const CastResult& r, const char* fn) {
    require_finite_result(is_finite_result(r), fn);
    kairos_cast_result c;
    write_c(r, c);
    return c;
}

// kairos_distance and kairos_signed_distance: the same checks and the same result struct.
template <class Query>
[[gnu::always_inline]] inline int32_t distance_query(const char* fn, const kairos_shape* a, const kairos_pose* pose_a, const kairos_shape* b,
                       const kairos_pose* pose_b, const kairos_query_settings* settings, kairos_distance_result* out,
                       Query query) {
    return guarded(fn, [&] {
        require_pointer(a, fn, "a");
        const Transform pa = read_transform(pose_a, fn, "pose_a");
        require_pointer(b, fn, "b");
        const Transform pb = read_transform(pose_b, fn, "pose_b");
        const QuerySettings qs = read_query_settings(settings, fn, "settings");
        require_pointer(out, fn, "out");
        const DistanceResult r = query(shape_of(a), pa, shape_of(b), pb, qs.tolerance, qs.max_iterations);
        require_finite_result(is_finite_result(r), fn);
        write_c(r, *out);  // every check has passed: nothing below can fail, so *out is written in place
    });
}
}  // namespace

extern "C" {

KAIROS_API void kairos_query_settings_init(kairos_query_settings* s) {
    if (s == nullptr) return;
    s->struct_size = sizeof(kairos_query_settings);
    s->tolerance = capi::kDefaultQuerySettings.tolerance;
    s->max_iterations = capi::kDefaultQuerySettings.max_iterations;
}


KAIROS_API int32_t kairos_distance(const kairos_shape* a, const kairos_pose* pose_a, const kairos_shape* b,
                                   const kairos_pose* pose_b, const kairos_query_settings* settings,
                                   kairos_distance_result* out) {
    return distance_query(__func__, a, pose_a, b, pose_b, settings, out,
                          [](const auto&... x) { return gjk_distance(x...); });
}

KAIROS_API int32_t kairos_signed_distance(const kairos_shape* a, const kairos_pose* pose_a, const kairos_shape* b,
                                          const kairos_pose* pose_b, const kairos_query_settings* settings,
                                          kairos_distance_result* out) {
    return distance_query(__func__, a, pose_a, b, pose_b, settings, out,
                          [](const auto&... x) { return signed_distance(x...); });
}

KAIROS_API int32_t kairos_intersect(const kairos_shape* a, const kairos_pose* pose_a, const kairos_shape* b,
                                    const kairos_pose* pose_b, kairos_vec3* axis_cache, int32_t* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(a, fn, "a");
        const Transform pa = read_transform(pose_a, fn, "pose_a");
        require_pointer(b, fn, "b");
        const Transform pb = read_transform(pose_b, fn, "pose_b");
        require_pointer(out, fn, "out");
        // A missing, zero or non-finite cached axis is a fresh start, not an error.
        Vec3 axis{};
        if (axis_cache != nullptr) axis = {axis_cache->x, axis_cache->y, axis_cache->z};
        if (!is_finite(axis)) axis = {};
        const bool hit = gjk_intersect(shape_of(a), pa, shape_of(b), pb, axis, nullptr);
        *out = hit ? 1 : 0;
        if (axis_cache != nullptr && !hit) *axis_cache = to_c(axis);
    });
}

KAIROS_API int32_t kairos_ray_cast(const kairos_shape* s, const kairos_pose* pose, kairos_vec3 origin,
                                   kairos_vec3 translation, const kairos_query_settings* settings,
                                   kairos_cast_result* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(s, fn, "s");
        const Transform p = read_transform(pose, fn, "pose");
        const Vec3 o = read_point(origin, fn, "origin");
        const Vec3 t = read_point(translation, fn, "translation");
        const QuerySettings qs = read_query_settings(settings, fn, "settings");
        require_pointer(out, fn, "out");
        *out = checked(kairos::ray_cast(shape_of(s), p, o, t, qs.tolerance, qs.max_iterations), fn);
    });
}

KAIROS_API int32_t kairos_shape_cast(const kairos_shape* a, const kairos_pose* pose_a, kairos_vec3 translation_a,
                                     const kairos_shape* b, const kairos_pose* pose_b, kairos_vec3 translation_b,
                                     const kairos_query_settings* settings, kairos_cast_result* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(a, fn, "a");
        const Transform pa = read_transform(pose_a, fn, "pose_a");
        const Vec3 ta = read_point(translation_a, fn, "translation_a");
        require_pointer(b, fn, "b");
        const Transform pb = read_transform(pose_b, fn, "pose_b");
        const Vec3 tb = read_point(translation_b, fn, "translation_b");
        const QuerySettings qs = read_query_settings(settings, fn, "settings");
        require_pointer(out, fn, "out");
        *out = checked(kairos::shape_cast(shape_of(a), pa, ta, shape_of(b), pb, tb, qs.tolerance,
                                          qs.max_iterations),
                       fn);
    });
}

KAIROS_API int32_t kairos_motion_cast(const kairos_shape* a, const kairos_motion* motion_a, const kairos_shape* b,
                                      const kairos_motion* motion_b, const kairos_query_settings* settings,
                                      kairos_cast_result* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(a, fn, "a");
        require_pointer(motion_a, fn, "motion_a");
        const BodyPose a0 = read_pose(&motion_a->start, fn, "motion_a.start");
        const BodyPose a1 = read_pose(&motion_a->end, fn, "motion_a.end");
        require_pointer(b, fn, "b");
        require_pointer(motion_b, fn, "motion_b");
        const BodyPose b0 = read_pose(&motion_b->start, fn, "motion_b.start");
        const BodyPose b1 = read_pose(&motion_b->end, fn, "motion_b.end");
        const QuerySettings qs = read_query_settings(settings, fn, "settings");
        require_pointer(out, fn, "out");
        const Motion ma(Pose{a0.position, a0.orientation}, Pose{a1.position, a1.orientation});
        const Motion mb(Pose{b0.position, b0.orientation}, Pose{b1.position, b1.orientation});
        *out = checked(kairos::motion_cast(shape_of(a), ma, shape_of(b), mb, qs.tolerance, qs.max_iterations), fn);
    });
}

}  // extern "C"
