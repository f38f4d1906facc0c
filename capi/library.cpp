// SPDX-License-Identifier: MIT
// Library information: version, status names, last error, and the dlopen function table.
#include <cstddef>

#include "boundary.hpp"

namespace kairos::capi {
const char* last_error_message();
}

extern "C" {

KAIROS_API uint32_t kairos_version(void) { return KAIROS_VERSION_NUMBER; }

KAIROS_API const char* kairos_last_error(void) { return kairos::capi::last_error_message(); }

KAIROS_API const char* kairos_status_name(int32_t status) {
    switch (status) {
        case KAIROS_OK:
            return "KAIROS_OK";
        case KAIROS_ERROR_NULL_ARGUMENT:
            return "KAIROS_ERROR_NULL_ARGUMENT";
        case KAIROS_ERROR_INVALID_ARGUMENT:
            return "KAIROS_ERROR_INVALID_ARGUMENT";
        case KAIROS_ERROR_STRUCT_SIZE:
            return "KAIROS_ERROR_STRUCT_SIZE";
        case KAIROS_ERROR_DEGENERATE:
            return "KAIROS_ERROR_DEGENERATE";
        case KAIROS_ERROR_STALE_ID:
            return "KAIROS_ERROR_STALE_ID";
        case KAIROS_ERROR_OUT_OF_MEMORY:
            return "KAIROS_ERROR_OUT_OF_MEMORY";
        case KAIROS_ERROR_NOT_IMPLEMENTED:
            return "KAIROS_ERROR_NOT_IMPLEMENTED";
        case KAIROS_ERROR_UNSUPPORTED_VERSION:
            return "KAIROS_ERROR_UNSUPPORTED_VERSION";
        case KAIROS_ERROR_INTERNAL:
            return "KAIROS_ERROR_INTERNAL";
        case KAIROS_ERROR_LIMIT:
            return "KAIROS_ERROR_LIMIT";
        default:
            return "KAIROS_UNKNOWN_STATUS";
    }
}

KAIROS_API int32_t kairos_get_api(uint32_t abi_version, const kairos_api** out) {
    // Entries are in the order of the struct; new ones are only ever appended.
    static const kairos_api table = {
        sizeof(kairos_api),
        KAIROS_ABI_VERSION,
        kairos_status_name,
        kairos_last_error,
        kairos_version,
        kairos_shape_sphere,
        kairos_shape_box,
        kairos_shape_capsule,
        kairos_shape_cylinder,
        kairos_shape_cone,
        kairos_shape_point,
        kairos_shape_segment,
        kairos_shape_convex_hull,
        kairos_shape_minkowski_sum,
        kairos_shape_hull,
        kairos_shape_transformed,
        kairos_shape_retain,
        kairos_shape_release,
        kairos_shape_support,
        kairos_shape_bounds,
        kairos_query_settings_init,
        kairos_distance,
        kairos_intersect,
        kairos_ray_cast,
        kairos_shape_cast,
        kairos_motion_cast,
        kairos_world_settings_init,
        kairos_world_create,
        kairos_world_destroy,
        kairos_world_add,
        kairos_world_remove,
        kairos_world_set_pose,
        kairos_world_move,
        kairos_world_step,
        kairos_world_contacts,
        kairos_world_overlaps,
        kairos_step_stats_init,
        kairos_world_step_stats,
        kairos_shape_triangle,
        kairos_signed_distance,
        kairos_world_set_filter,
        kairos_world_set_static,
        kairos_world_get_pose,
        kairos_world_get_user_data,
        kairos_world_ray_cast,
        kairos_world_shape_cast,
        kairos_world_query_box,
        kairos_distance_batch,
        kairos_shape_cast_batch,
        kairos_motion_cast_batch,
        kairos_world_move_batch,
    };
    // Version 1's callers know the 0.1 table and the 0.1 kairos_world_settings: their table ends
    // before shape_triangle and initialises the settings as 0.1 did (no write past its end).
    static const kairos_api table_v1 = [] {
        kairos_api t = table;
        t.struct_size = offsetof(kairos_api, shape_triangle);
        t.world_settings_init = world_settings_init_0_1;
        return t;
    }();
    const char* const fn = __func__;
    return kairos::capi::guarded(fn, [&] {
        using kairos::capi::fail;
        kairos::capi::require_pointer(out, fn, "out");
        if (abi_version < 1 || abi_version > KAIROS_ABI_VERSION)
            fail(KAIROS_ERROR_UNSUPPORTED_VERSION, fn, "abi_version %u is not provided (this library provides 1 to %u)",
                 abi_version, KAIROS_ABI_VERSION);
        *out = abi_version == 1 ? &table_v1 : &table;
    });
}

}  // extern "C"
