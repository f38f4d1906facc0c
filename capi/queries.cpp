// C API pair queries: distance, intersection, ray cast, shape cast, motion cast.
#include "boundary.hpp"

using namespace kairos;
using namespace kairos::capi;

extern "C" {

KAIROS_API void kairos_query_settings_init(kairos_query_settings* s) {
    if (s == nullptr) return;
    s->struct_size = sizeof(kairos_query_settings);
    s->tolerance = 1e-10;
    s->max_iterations = 256;
}

KAIROS_API int32_t kairos_distance(const kairos_shape* a, const kairos_pose* pose_a, const kairos_shape* b,
                                   const kairos_pose* pose_b, const kairos_query_settings* settings,
                                   kairos_distance_result* out) {
    return guarded(__func__, [&] {
        require_pointer(a, __func__, "a");
        const BodyPose pa = read_pose(pose_a, __func__, "pose_a");
        require_pointer(b, __func__, "b");
        const BodyPose pb = read_pose(pose_b, __func__, "pose_b");
        const QuerySettings qs = read_query_settings(settings, __func__, "settings");
        require_pointer(out, __func__, "out");
        (void)pa, (void)pb, (void)qs;
        fail(KAIROS_ERROR_NOT_IMPLEMENTED, __func__, "not implemented in this version");
    });
}

KAIROS_API int32_t kairos_intersect(const kairos_shape* a, const kairos_pose* pose_a, const kairos_shape* b,
                                    const kairos_pose* pose_b, kairos_vec3* axis_cache, int32_t* out) {
    return guarded(__func__, [&] {
        require_pointer(a, __func__, "a");
        const BodyPose pa = read_pose(pose_a, __func__, "pose_a");
        require_pointer(b, __func__, "b");
        const BodyPose pb = read_pose(pose_b, __func__, "pose_b");
        require_pointer(out, __func__, "out");
        // A missing, zero or non-finite cached axis is a fresh start, not an error.
        Vec3 axis{};
        if (axis_cache != nullptr) axis = {axis_cache->x, axis_cache->y, axis_cache->z};
        if (!is_finite(axis)) axis = {};
        (void)pa, (void)pb;
        fail(KAIROS_ERROR_NOT_IMPLEMENTED, __func__, "not implemented in this version");
    });
}

KAIROS_API int32_t kairos_ray_cast(const kairos_shape* s, const kairos_pose* pose, kairos_vec3 origin,
                                   kairos_vec3 translation, const kairos_query_settings* settings,
                                   kairos_cast_result* out) {
    return guarded(__func__, [&] {
        require_pointer(s, __func__, "s");
        read_pose(pose, __func__, "pose");
        read_vec3(origin, __func__, "origin");
        read_vec3(translation, __func__, "translation");
        read_query_settings(settings, __func__, "settings");
        require_pointer(out, __func__, "out");
        fail(KAIROS_ERROR_NOT_IMPLEMENTED, __func__, "not implemented in this version");
    });
}

KAIROS_API int32_t kairos_shape_cast(const kairos_shape* a, const kairos_pose* pose_a, kairos_vec3 translation_a,
                                     const kairos_shape* b, const kairos_pose* pose_b, kairos_vec3 translation_b,
                                     const kairos_query_settings* settings, kairos_cast_result* out) {
    return guarded(__func__, [&] {
        require_pointer(a, __func__, "a");
        read_pose(pose_a, __func__, "pose_a");
        read_vec3(translation_a, __func__, "translation_a");
        require_pointer(b, __func__, "b");
        read_pose(pose_b, __func__, "pose_b");
        read_vec3(translation_b, __func__, "translation_b");
        read_query_settings(settings, __func__, "settings");
        require_pointer(out, __func__, "out");
        fail(KAIROS_ERROR_NOT_IMPLEMENTED, __func__, "not implemented in this version");
    });
}

KAIROS_API int32_t kairos_motion_cast(const kairos_shape* a, const kairos_motion* motion_a, const kairos_shape* b,
                                      const kairos_motion* motion_b, const kairos_query_settings* settings,
                                      kairos_cast_result* out) {
    return guarded(__func__, [&] {
        require_pointer(a, __func__, "a");
        require_pointer(motion_a, __func__, "motion_a");
        read_pose(&motion_a->start, __func__, "motion_a.start");
        read_pose(&motion_a->end, __func__, "motion_a.end");
        require_pointer(b, __func__, "b");
        require_pointer(motion_b, __func__, "motion_b");
        read_pose(&motion_b->start, __func__, "motion_b.start");
        read_pose(&motion_b->end, __func__, "motion_b.end");
        read_query_settings(settings, __func__, "settings");
        require_pointer(out, __func__, "out");
        fail(KAIROS_ERROR_NOT_IMPLEMENTED, __func__, "not implemented in this version");
    });
}

}  // extern "C"
