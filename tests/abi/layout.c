/* SPDX-License-Identifier: MIT */
/* ABI test: pins the size and field offsets of every public struct, and the numeric constants. */
/*
 * These values are the ABI of major version 0 on x86-64 (LP64, System V). A failure here means a
 * public struct or constant changed: that is an ABI break unless the change only appends to a
 * growing struct (kairos_world_settings, kairos_step_stats, kairos_api), in which case update the
 * size below, the ABI baseline (scripts/update-abi-baseline.sh) and abi/CHANGELOG.md together.
 * Frozen structs (vec3, quat, pose, motion, query_settings, the results, contact) never change.
 */
#include <stddef.h>
#include <stdint.h>

#include <kairos/kairos.h>

#if !(defined(__x86_64__) && defined(__LP64__))
#error "layout.c pins the x86-64 LP64 layout; add the values for this target before using it"
#endif

/* _Static_assert is C11; __extension__ lets this file build as strict C99 with -pedantic. */
#define PIN(cond) __extension__ _Static_assert(cond, #cond)
#define PIN_SIZE(type, bytes) PIN(sizeof(type) == (bytes))
#define PIN_OFFSET(type, field, bytes) PIN(offsetof(type, field) == (bytes))

/* ---- Scalars the structs are made of ---------------------------------------------------------- */
PIN(sizeof(double) == 8);
PIN(sizeof(void*) == 8);
PIN(sizeof(size_t) == 8);
PIN_SIZE(kairos_object_id, 8);

/* ---- Plain types (frozen) --------------------------------------------------------------------- */
PIN_SIZE(kairos_vec3, 24);
PIN_OFFSET(kairos_vec3, x, 0);
PIN_OFFSET(kairos_vec3, y, 8);
PIN_OFFSET(kairos_vec3, z, 16);

PIN_SIZE(kairos_quat, 32);
PIN_OFFSET(kairos_quat, x, 0);
PIN_OFFSET(kairos_quat, y, 8);
PIN_OFFSET(kairos_quat, z, 16);
PIN_OFFSET(kairos_quat, w, 24);

PIN_SIZE(kairos_pose, 56);
PIN_OFFSET(kairos_pose, position, 0);
PIN_OFFSET(kairos_pose, orientation, 24);
PIN_OFFSET(kairos_pose, orientation.w, 48);

PIN_SIZE(kairos_motion, 112);
PIN_OFFSET(kairos_motion, start, 0);
PIN_OFFSET(kairos_motion, end, 56);
PIN_OFFSET(kairos_motion, end.orientation, 80);

/* ---- Query settings (frozen: embedded by value in kairos_world_settings) ---------------------- */
PIN_SIZE(kairos_query_settings, 24);
PIN_OFFSET(kairos_query_settings, struct_size, 0);
PIN_OFFSET(kairos_query_settings, tolerance, 8);
PIN_OFFSET(kairos_query_settings, max_iterations, 16);

/* ---- Results (frozen) ------------------------------------------------------------------------- */
PIN_SIZE(kairos_distance_result, 96);
PIN_OFFSET(kairos_distance_result, distance, 0);
PIN_OFFSET(kairos_distance_result, point_a, 8);
PIN_OFFSET(kairos_distance_result, point_b, 32);
PIN_OFFSET(kairos_distance_result, axis, 56);
PIN_OFFSET(kairos_distance_result, intersecting, 80);
PIN_OFFSET(kairos_distance_result, iterations, 84);
PIN_OFFSET(kairos_distance_result, termination, 88);

PIN_SIZE(kairos_cast_result, 72);
PIN_OFFSET(kairos_cast_result, hit, 0);
PIN_OFFSET(kairos_cast_result, toi, 8);
PIN_OFFSET(kairos_cast_result, point, 16);
PIN_OFFSET(kairos_cast_result, normal, 40);
PIN_OFFSET(kairos_cast_result, iterations, 64);
PIN_OFFSET(kairos_cast_result, termination, 68);

/* ---- World ------------------------------------------------------------------------------------ */
/* Growing: fields may be appended after query, so only the prefix offsets are pinned forever. */
/* 0.1's struct ended at 32 bytes (worker_count's offset): its init stays exported for it. */
PIN_SIZE(kairos_world_settings, 64);
PIN_OFFSET(kairos_world_settings, worker_count, 32);
PIN_OFFSET(kairos_world_settings, enqueue_task, 40);
PIN_OFFSET(kairos_world_settings, finish_task, 48);
PIN_OFFSET(kairos_world_settings, task_user_context, 56);
PIN_OFFSET(kairos_world_settings, struct_size, 0);
PIN_OFFSET(kairos_world_settings, broad_phase, 4);
PIN_OFFSET(kairos_world_settings, query, 8);
PIN_OFFSET(kairos_world_settings, query.tolerance, 16);
PIN_OFFSET(kairos_world_settings, query.max_iterations, 24);

PIN_SIZE(kairos_filter, 12);
PIN_OFFSET(kairos_filter, category_bits, 0);
PIN_OFFSET(kairos_filter, mask_bits, 4);
PIN_OFFSET(kairos_filter, group, 8);
PIN_SIZE(kairos_world_hit, 80);
PIN_OFFSET(kairos_world_hit, hit, 0);
PIN_OFFSET(kairos_world_hit, id, 8);
PIN_OFFSET(kairos_world_hit, user_data, 16);
PIN_OFFSET(kairos_world_hit, toi, 24);
PIN_OFFSET(kairos_world_hit, point, 32);
PIN_OFFSET(kairos_world_hit, normal, 56);

PIN_SIZE(kairos_contact, 88);
PIN_OFFSET(kairos_contact, a, 0);
PIN_OFFSET(kairos_contact, b, 8);
PIN_OFFSET(kairos_contact, user_a, 16);
PIN_OFFSET(kairos_contact, user_b, 24);
PIN_OFFSET(kairos_contact, toi, 32);
PIN_OFFSET(kairos_contact, point, 40);
PIN_OFFSET(kairos_contact, normal, 64);

/* Growing: the library writes at most struct_size bytes. */
PIN_SIZE(kairos_step_stats, 64);
PIN_OFFSET(kairos_step_stats, struct_size, 0);
PIN_OFFSET(kairos_step_stats, broad_phase_pairs, 8);
PIN_OFFSET(kairos_step_stats, swaps, 16);
PIN_OFFSET(kairos_step_stats, heap_operations, 24);
PIN_OFFSET(kairos_step_stats, narrow_phase_queries, 32);
PIN_OFFSET(kairos_step_stats, gjk_iterations, 40);
PIN_OFFSET(kairos_step_stats, broad_phase_seconds, 48);
PIN_OFFSET(kairos_step_stats, narrow_phase_seconds, 56);

/* ---- The dlopen function table (append-only) -------------------------------------------------- */
/* Every entry of ABI version 1, in order: 8 bytes of header, then one 8-byte pointer each. */
#define PIN_API(field, index) PIN_OFFSET(kairos_api, field, 8 + 8 * (index))
PIN_OFFSET(kairos_api, struct_size, 0);
PIN_OFFSET(kairos_api, abi_version, 4);
PIN_API(status_name, 0);
PIN_API(last_error, 1);
PIN_API(version, 2);
PIN_API(shape_sphere, 3);
PIN_API(shape_box, 4);
PIN_API(shape_capsule, 5);
PIN_API(shape_cylinder, 6);
PIN_API(shape_cone, 7);
PIN_API(shape_point, 8);
PIN_API(shape_segment, 9);
PIN_API(shape_convex_hull, 10);
PIN_API(shape_minkowski_sum, 11);
PIN_API(shape_hull, 12);
PIN_API(shape_transformed, 13);
PIN_API(shape_retain, 14);
PIN_API(shape_release, 15);
PIN_API(shape_support, 16);
PIN_API(shape_bounds, 17);
PIN_API(query_settings_init, 18);
PIN_API(distance, 19);
PIN_API(intersect, 20);
PIN_API(ray_cast, 21);
PIN_API(shape_cast, 22);
PIN_API(motion_cast, 23);
PIN_API(world_settings_init, 24);
PIN_API(world_create, 25);
PIN_API(world_destroy, 26);
PIN_API(world_add, 27);
PIN_API(world_remove, 28);
PIN_API(world_set_pose, 29);
PIN_API(world_move, 30);
PIN_API(world_step, 31);
PIN_API(world_contacts, 32);
PIN_API(world_overlaps, 33);
PIN_API(step_stats_init, 34);
PIN_API(world_step_stats, 35);
/* ABI version 2 appends: */
PIN_API(shape_triangle, 36);
PIN_API(signed_distance, 37);
PIN_API(world_set_filter, 38);
PIN_API(world_set_static, 39);
PIN_API(world_get_pose, 40);
PIN_API(world_get_user_data, 41);
PIN_API(world_ray_cast, 42);
PIN_API(world_shape_cast, 43);
PIN_API(world_query_box, 44);
PIN_API(distance_batch, 45);
PIN_API(shape_cast_batch, 46);
PIN_API(motion_cast_batch, 47);
PIN_API(world_move_batch, 48);
/* The size of ABI version 2's table: 49 entries. A new ABI version appends and grows this. */
PIN_SIZE(kairos_api, 8 + 8 * 49);
PIN(KAIROS_ABI_VERSION == 2u);

/* ---- Constants are ABI too: never renumbered -------------------------------------------------- */
PIN(KAIROS_OK == 0);
PIN(KAIROS_ERROR_NULL_ARGUMENT == -1);
PIN(KAIROS_ERROR_INVALID_ARGUMENT == -2);
PIN(KAIROS_ERROR_STRUCT_SIZE == -3);
PIN(KAIROS_ERROR_DEGENERATE == -4);
PIN(KAIROS_ERROR_STALE_ID == -5);
PIN(KAIROS_ERROR_OUT_OF_MEMORY == -6);
PIN(KAIROS_ERROR_NOT_IMPLEMENTED == -7);
PIN(KAIROS_ERROR_UNSUPPORTED_VERSION == -8);
PIN(KAIROS_ERROR_INTERNAL == -9);
PIN(KAIROS_ERROR_LIMIT == -10);

PIN(KAIROS_TERMINATION_NONE == 0);
PIN(KAIROS_TERMINATION_RELATIVE_ERROR == 1);
PIN(KAIROS_TERMINATION_NEAR_CONTACT == 2);
PIN(KAIROS_TERMINATION_FULL_SIMPLEX == 3);
PIN(KAIROS_TERMINATION_JOHNSON_FAILED == 4);
PIN(KAIROS_TERMINATION_REPEATED_SUPPORT == 5);
PIN(KAIROS_TERMINATION_NO_PROGRESS == 6);
PIN(KAIROS_TERMINATION_MAX_ITERATIONS == 7);
PIN(KAIROS_TERMINATION_SEPARATED == 8);
PIN(KAIROS_TERMINATION_HIT == 9);

PIN(KAIROS_BROAD_PHASE_SPACETIME_SAP == 0);
PIN(KAIROS_BROAD_PHASE_ENCAPSULATING_SAP == 1);
PIN(KAIROS_BROAD_PHASE_BRUTE_FORCE == 2);

/* The version macros are consistent with each other. */
PIN(KAIROS_VERSION_NUMBER ==
    KAIROS_VERSION_MAJOR * 10000 + KAIROS_VERSION_MINOR * 100 + KAIROS_VERSION_PATCH);
PIN(KAIROS_VERSION_MAJOR == 0);

/* The function types in the table match the exported functions exactly (a mismatch would be a
 * silent ABI break for dlopen users). Initialising a pointer of the table's type from the
 * function needs no cast only when the types agree; -Werror turns a mismatch into an error. */
static const kairos_api kairos_layout_table_types = {
    sizeof(kairos_api), KAIROS_ABI_VERSION,
    kairos_status_name, kairos_last_error, kairos_version,
    kairos_shape_sphere, kairos_shape_box, kairos_shape_capsule, kairos_shape_cylinder,
    kairos_shape_cone, kairos_shape_point, kairos_shape_segment, kairos_shape_convex_hull,
    kairos_shape_minkowski_sum, kairos_shape_hull, kairos_shape_transformed,
    kairos_shape_retain, kairos_shape_release, kairos_shape_support, kairos_shape_bounds,
    kairos_query_settings_init, kairos_distance, kairos_intersect, kairos_ray_cast,
    kairos_shape_cast, kairos_motion_cast,
    kairos_world_settings_init, kairos_world_create, kairos_world_destroy, kairos_world_add,
    kairos_world_remove, kairos_world_set_pose, kairos_world_move, kairos_world_step,
    kairos_world_contacts, kairos_world_overlaps, kairos_step_stats_init, kairos_world_step_stats,
    kairos_shape_triangle, kairos_signed_distance,
    kairos_world_set_filter, kairos_world_set_static, kairos_world_get_pose, kairos_world_get_user_data,
    kairos_world_ray_cast, kairos_world_shape_cast, kairos_world_query_box,
    kairos_distance_batch, kairos_shape_cast_batch, kairos_motion_cast_batch, kairos_world_move_batch,
};

/* Referenced so that the table above is not an unused variable under -Wall. */
const kairos_api* kairos_layout_table(void);
const kairos_api* kairos_layout_table(void) { return &kairos_layout_table_types; }
