/* SPDX-License-Identifier: MIT */
/* ABI test: a strict C99 program linked against libkairos; exits non-zero on any wrong answer. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include <kairos/kairos.h>

static int failures = 0;

#define CHECK(cond)                                                              \
    do {                                                                         \
        if (!(cond)) {                                                           \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            ++failures;                                                          \
        }                                                                        \
    } while (0)

/* A status check that also shows the status name and last error when it fails. */
#define CHECK_STATUS(call, expected)                                                          \
    do {                                                                                      \
        int32_t status_ = (call);                                                             \
        if (status_ != (expected)) {                                                          \
            fprintf(stderr, "%s:%d: %s returned %s (%d), expected %s; last error: %s\n",     \
                    __FILE__, __LINE__, #call, kairos_status_name(status_), (int)status_,    \
                    kairos_status_name(expected), kairos_last_error());                     \
            ++failures;                                                                       \
        }                                                                                     \
    } while (0)

static kairos_vec3 vec3(double x, double y, double z) {
    kairos_vec3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

static int near3(kairos_vec3 a, kairos_vec3 b, double tol) {
    return fabs(a.x - b.x) <= tol && fabs(a.y - b.y) <= tol && fabs(a.z - b.z) <= tol;
}

/* True when the last error on this thread mentions word (the argument's name). */
static int error_mentions(const char* word) {
    const char* message = kairos_last_error();
    return message != NULL && strstr(message, word) != NULL;
}

/* support(s, d) must be expected (within 1e-12 of each coordinate's scale). */
static void check_support(const char* what, const kairos_shape* s, kairos_vec3 d, kairos_vec3 expected) {
    kairos_vec3 got = vec3(-999.0, -999.0, -999.0);
    int32_t status = kairos_shape_support(s, d, &got);
    if (status != KAIROS_OK || !near3(got, expected, 1e-12)) {
        fprintf(stderr, "support of %s along (%g, %g, %g): status %s, got (%.17g, %.17g, %.17g), "
                        "expected (%.17g, %.17g, %.17g); last error: %s\n",
                what, d.x, d.y, d.z, kairos_status_name(status), got.x, got.y, got.z,
                expected.x, expected.y, expected.z, kairos_last_error());
        ++failures;
    }
}

static void check_bounds(const char* what, const kairos_shape* s, const kairos_pose* pose,
                         kairos_vec3 expected_min, kairos_vec3 expected_max) {
    kairos_vec3 lo = vec3(-999.0, -999.0, -999.0), hi = vec3(-999.0, -999.0, -999.0);
    int32_t status = kairos_shape_bounds(s, pose, &lo, &hi);
    if (status != KAIROS_OK || !near3(lo, expected_min, 1e-12) || !near3(hi, expected_max, 1e-12)) {
        fprintf(stderr, "bounds of %s: status %s, got [(%.17g, %.17g, %.17g), (%.17g, %.17g, %.17g)]; "
                        "last error: %s\n",
                what, kairos_status_name(status), lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, kairos_last_error());
        ++failures;
    }
}

static void test_version_and_names(void) {
    CHECK(kairos_version() == KAIROS_VERSION_NUMBER);
    CHECK(kairos_version() / 10000 == KAIROS_VERSION_MAJOR);
    /* Nothing has failed on this thread yet. */
    CHECK(kairos_last_error() != NULL && kairos_last_error()[0] == '\0');

#define CHECK_NAME(code) CHECK(strcmp(kairos_status_name(code), #code) == 0)
    CHECK_NAME(KAIROS_OK);
    CHECK_NAME(KAIROS_ERROR_NULL_ARGUMENT);
    CHECK_NAME(KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK_NAME(KAIROS_ERROR_STRUCT_SIZE);
    CHECK_NAME(KAIROS_ERROR_DEGENERATE);
    CHECK_NAME(KAIROS_ERROR_STALE_ID);
    CHECK_NAME(KAIROS_ERROR_OUT_OF_MEMORY);
    CHECK_NAME(KAIROS_ERROR_NOT_IMPLEMENTED);
    CHECK_NAME(KAIROS_ERROR_UNSUPPORTED_VERSION);
    CHECK_NAME(KAIROS_ERROR_INTERNAL);
    CHECK_NAME(KAIROS_ERROR_LIMIT);
#undef CHECK_NAME
    CHECK(strcmp(kairos_status_name(12345), "KAIROS_UNKNOWN_STATUS") == 0);
    CHECK(strcmp(kairos_status_name(-11), "KAIROS_UNKNOWN_STATUS") == 0);
    CHECK(strcmp(kairos_status_name(INT32_MIN), "KAIROS_UNKNOWN_STATUS") == 0);
    CHECK(strcmp(kairos_status_name(INT32_MAX), "KAIROS_UNKNOWN_STATUS") == 0);
}

static void test_shapes(void) {
    const double r2 = sqrt(0.5);
    kairos_shape *sphere = NULL, *box = NULL, *capsule = NULL, *cylinder = NULL, *cone = NULL;
    kairos_shape *point = NULL, *segment = NULL, *hull = NULL, *sum = NULL, *both = NULL, *moved = NULL;
    kairos_vec3 cube[9];
    kairos_pose pose;
    const double stretch[9] = {2, 0, 0, 0, 1, 0, 0, 0, 1};
    int i;

    CHECK_STATUS(kairos_shape_sphere(2.0, &sphere), KAIROS_OK);
    CHECK_STATUS(kairos_shape_box(vec3(1.0, 2.0, 3.0), &box), KAIROS_OK);
    CHECK_STATUS(kairos_shape_capsule(1.0, 2.0, &capsule), KAIROS_OK);
    CHECK_STATUS(kairos_shape_cylinder(1.0, 2.0, &cylinder), KAIROS_OK);
    CHECK_STATUS(kairos_shape_cone(1.0, 2.0, &cone), KAIROS_OK);
    CHECK_STATUS(kairos_shape_point(&point), KAIROS_OK);
    CHECK_STATUS(kairos_shape_segment(3.0, &segment), KAIROS_OK);
    for (i = 0; i < 8; ++i) cube[i] = vec3(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
    cube[8] = vec3(0.25, -0.5, 0.125); /* interior: dropped */
    CHECK_STATUS(kairos_shape_convex_hull(cube, 9, &hull), KAIROS_OK);
    if (failures != 0) {
        fprintf(stderr, "shape construction failed; skipping the rest of the shape checks\n");
        goto release;
    }
    CHECK_STATUS(kairos_shape_minkowski_sum(box, sphere, &sum), KAIROS_OK);
    CHECK_STATUS(kairos_shape_hull(sphere, segment, &both), KAIROS_OK);
    CHECK_STATUS(kairos_shape_transformed(sphere, stretch, vec3(5.0, 0.0, 0.0), &moved), KAIROS_OK);
    if (failures != 0) goto release;

    check_support("sphere", sphere, vec3(1, 0, 0), vec3(2, 0, 0));
    check_support("sphere", sphere, vec3(3, 3, 0), vec3(2 * r2, 2 * r2, 0));
    check_support("box", box, vec3(1, -1, 1), vec3(1, -2, 3));
    check_support("capsule", capsule, vec3(0, 0, 1), vec3(0, 0, 3));
    check_support("capsule", capsule, vec3(1, 0, 1), vec3(r2, 0, 2 + r2));
    check_support("cylinder", cylinder, vec3(1, 0, 1), vec3(1, 0, 2));
    check_support("cylinder", cylinder, vec3(0, -1, -1), vec3(0, -1, -2));
    check_support("cone", cone, vec3(0, 0, 1), vec3(0, 0, 2));
    check_support("cone", cone, vec3(1, 0, -1), vec3(1, 0, -2));
    check_support("point", point, vec3(1, 2, 3), vec3(0, 0, 0));
    check_support("segment", segment, vec3(0.5, 0, -1), vec3(0, 0, -3));
    check_support("convex hull", hull, vec3(1, 2, 3), vec3(1, 1, 1));
    check_support("convex hull", hull, vec3(-1, 2, -3), vec3(-1, 1, -1));
    check_support("box + sphere", sum, vec3(1, 1, 1),
                  vec3(1 + 2 / sqrt(3.0), 2 + 2 / sqrt(3.0), 3 + 2 / sqrt(3.0)));
    check_support("hull(sphere, segment)", both, vec3(0, 0, 1), vec3(0, 0, 3));
    check_support("hull(sphere, segment)", both, vec3(1, 0, 0), vec3(2, 0, 0));
    check_support("stretched sphere", moved, vec3(1, 0, 0), vec3(9, 0, 0));
    check_support("stretched sphere", moved, vec3(0, 1, 0), vec3(5, 2, 0));

    /* Bounds: identity, a translation, and a quarter turn about z (x and y half extents swap). */
    check_bounds("box", box, NULL, vec3(-1, -2, -3), vec3(1, 2, 3));
    check_bounds("capsule", capsule, NULL, vec3(-1, -1, -3), vec3(1, 1, 3));
    check_bounds("cone", cone, NULL, vec3(-1, -1, -2), vec3(1, 1, 2));
    check_bounds("point", point, NULL, vec3(0, 0, 0), vec3(0, 0, 0));
    pose.position = vec3(10, 0, -1);
    pose.orientation.x = 0;
    pose.orientation.y = 0;
    pose.orientation.z = 0;
    pose.orientation.w = 1;
    check_bounds("translated sphere", sphere, &pose, vec3(8, -2, -3), vec3(12, 2, 1));
    pose.orientation.z = r2;
    pose.orientation.w = r2;
    check_bounds("turned box", box, &pose, vec3(8, -1, -4), vec3(12, 1, 2));
    check_bounds("turned segment", segment, &pose, vec3(10, 0, -4), vec3(10, 0, 2));

    /* Reference counting: a retained shape survives one release; composites keep their parts. */
    kairos_shape_retain(sphere);
    kairos_shape_release(sphere);
    check_support("sphere after retain/release", sphere, vec3(0, 0, -1), vec3(0, 0, -2));
    kairos_shape_retain(NULL);
    kairos_shape_release(NULL);

release:
    kairos_shape_release(sphere);
    kairos_shape_release(box);
    /* The parts are gone from the caller; the composites still work. */
    if (sum != NULL) check_support("box + sphere after releasing parts", sum, vec3(-1, -1, -1),
                                   vec3(-1 - 2 / sqrt(3.0), -2 - 2 / sqrt(3.0), -3 - 2 / sqrt(3.0)));
    if (moved != NULL) check_support("stretched sphere after releasing its part", moved,
                                     vec3(-1, 0, 0), vec3(1, 0, 0));
    kairos_shape_release(capsule);
    kairos_shape_release(cylinder);
    kairos_shape_release(cone);
    kairos_shape_release(point);
    kairos_shape_release(segment);
    kairos_shape_release(hull);
    kairos_shape_release(sum);
    kairos_shape_release(both);
    kairos_shape_release(moved);
}

static void test_bad_input(void) {
    kairos_shape* const sentinel = (kairos_shape*)&failures; /* never dereferenced */
    kairos_shape* out = sentinel;
    kairos_shape* sphere = NULL;
    kairos_vec3 v = vec3(7, 7, 7), lo = vec3(7, 7, 7), hi = vec3(7, 7, 7);
    kairos_vec3 flat[4];
    kairos_pose pose;

    CHECK_STATUS(kairos_shape_sphere(1.0, NULL), KAIROS_ERROR_NULL_ARGUMENT);
    CHECK(error_mentions("out"));

    CHECK_STATUS(kairos_shape_sphere(-1.0, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(out == sentinel);
    CHECK(error_mentions("radius"));
    CHECK_STATUS(kairos_shape_sphere(0.0, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(kairos_shape_sphere(NAN, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(kairos_shape_sphere(INFINITY, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(kairos_shape_box(vec3(1, 0, 1), &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(error_mentions("half_extents"));
    CHECK_STATUS(kairos_shape_capsule(1.0, -0.5, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(error_mentions("half_height"));
    CHECK_STATUS(kairos_shape_segment(NAN, &out), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(error_mentions("half_length"));
    CHECK(out == sentinel);

    /* No points name no shape; collinear corners name no triangle. */
    flat[0] = vec3(0, 0, 0);
    flat[1] = vec3(1, 0, 0);
    flat[2] = vec3(2, 0, 0);
    CHECK_STATUS(kairos_shape_triangle(flat[0], flat[1], flat[2], &out), KAIROS_ERROR_DEGENERATE);
    CHECK(error_mentions("collinear"));
    CHECK_STATUS(kairos_shape_convex_hull(NULL, 0, &out), KAIROS_ERROR_DEGENERATE);
    CHECK_STATUS(kairos_shape_convex_hull(NULL, 5, &out), KAIROS_ERROR_NULL_ARGUMENT);
    CHECK(out == sentinel);

    CHECK_STATUS(kairos_shape_support(NULL, vec3(1, 0, 0), &v), KAIROS_ERROR_NULL_ARGUMENT);
    CHECK_STATUS(kairos_shape_sphere(1.0, &sphere), KAIROS_OK);
    if (sphere == NULL) return;
    CHECK_STATUS(kairos_shape_support(sphere, vec3(1, 0, 0), NULL), KAIROS_ERROR_NULL_ARGUMENT);
    CHECK(error_mentions("out"));
    CHECK_STATUS(kairos_shape_support(sphere, vec3(NAN, 0, 0), &v), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(error_mentions("direction"));
    CHECK(v.x == 7 && v.y == 7 && v.z == 7);

    /* A quaternion of length 2 is not a rotation. */
    pose.position = vec3(0, 0, 0);
    pose.orientation.x = 0;
    pose.orientation.y = 0;
    pose.orientation.z = 0;
    pose.orientation.w = 2;
    CHECK_STATUS(kairos_shape_bounds(sphere, &pose, &lo, &hi), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(error_mentions("pose"));
    CHECK_STATUS(kairos_shape_bounds(sphere, NULL, NULL, &hi), KAIROS_ERROR_NULL_ARGUMENT);
    CHECK(error_mentions("min"));
    CHECK_STATUS(kairos_shape_bounds(sphere, NULL, &lo, NULL), KAIROS_ERROR_NULL_ARGUMENT);
    CHECK(error_mentions("max"));
    CHECK(lo.x == 7 && hi.x == 7);
    kairos_shape_release(sphere);

    /* A successful call leaves the last error as it was. */
    {
        char before[512];
        strncpy(before, kairos_last_error(), sizeof before - 1);
        before[sizeof before - 1] = '\0';
        CHECK(before[0] != '\0');
        CHECK_STATUS(kairos_shape_point(&out), KAIROS_OK);
        CHECK(strcmp(before, kairos_last_error()) == 0);
        if (out != sentinel) kairos_shape_release(out);
    }
}

static void test_settings_and_world(void) {
    kairos_query_settings query;
    kairos_world_settings settings;
    kairos_step_stats stats;
    kairos_world* world = NULL;
    kairos_world* const sentinel = (kairos_world*)&failures;
    kairos_world* bad = sentinel;
    kairos_shape* sphere = NULL;
    kairos_object_id id = 0, id2 = 0;
    kairos_pose pose;

    memset(&query, 0, sizeof query);
    kairos_query_settings_init(&query);
    CHECK(query.struct_size == sizeof(kairos_query_settings));
    CHECK(query.tolerance == 1e-10);
    CHECK(query.max_iterations == 256);
    kairos_query_settings_init(NULL);

    memset(&settings, 0xff, sizeof settings);
    kairos_world_settings_init(&settings);
    CHECK(settings.struct_size == sizeof(kairos_world_settings));
    CHECK(settings.broad_phase == KAIROS_BROAD_PHASE_SPACETIME_SAP);
    CHECK(settings.query.struct_size == sizeof(kairos_query_settings));
    CHECK(settings.query.tolerance == 1e-10);

    memset(&stats, 0xff, sizeof stats);
    kairos_step_stats_init(&stats);
    CHECK(stats.struct_size == sizeof(kairos_step_stats));
    CHECK(stats.broad_phase_pairs == 0 && stats.gjk_iterations == 0);

    /* An uninitialised (zero) struct_size is caught. */
    settings.struct_size = 0;
    CHECK_STATUS(kairos_world_create(&settings, &bad), KAIROS_ERROR_STRUCT_SIZE);
    CHECK(bad == sentinel);
    kairos_world_settings_init(&settings);
    settings.broad_phase = 99;
    CHECK_STATUS(kairos_world_create(&settings, &bad), KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(bad == sentinel);
    CHECK_STATUS(kairos_world_create(NULL, NULL), KAIROS_ERROR_NULL_ARGUMENT);

    kairos_world_settings_init(&settings);
    CHECK_STATUS(kairos_world_create(&settings, &world), KAIROS_OK);
    CHECK_STATUS(kairos_shape_sphere(1.0, &sphere), KAIROS_OK);
    if (world == NULL || sphere == NULL) {
        kairos_world_destroy(world);
        kairos_shape_release(sphere);
        return;
    }
    CHECK_STATUS(kairos_world_add(world, sphere, NULL, 42, &id), KAIROS_OK);
    CHECK(id != 0);
    CHECK_STATUS(kairos_world_add(world, sphere, NULL, 43, &id2), KAIROS_OK);
    CHECK(id2 != 0 && id2 != id);
    /* The world holds its own references. */
    kairos_shape_release(sphere);
    CHECK_STATUS(kairos_world_remove(world, id), KAIROS_OK);
    CHECK_STATUS(kairos_world_remove(world, id), KAIROS_ERROR_STALE_ID);
    CHECK_STATUS(kairos_world_remove(world, 0), KAIROS_ERROR_STALE_ID);
    pose.position = vec3(1, 2, 3);
    pose.orientation.x = 0;
    pose.orientation.y = 0;
    pose.orientation.z = 0;
    pose.orientation.w = 1;
    CHECK_STATUS(kairos_world_set_pose(world, id, &pose), KAIROS_ERROR_STALE_ID);
    CHECK_STATUS(kairos_world_set_pose(world, id2, &pose), KAIROS_OK);
    CHECK_STATUS(kairos_world_remove(world, id2), KAIROS_OK);
    kairos_world_destroy(world);
    kairos_world_destroy(NULL);
}

/* Queries may still be KAIROS_ERROR_NOT_IMPLEMENTED in this version; when they answer, the
 * answer must be right. */
static void test_distance_if_available(void) {
    kairos_shape *a = NULL, *b = NULL;
    kairos_pose pose_b;
    kairos_distance_result result;
    int32_t status;

    CHECK_STATUS(kairos_shape_sphere(1.0, &a), KAIROS_OK);
    CHECK_STATUS(kairos_shape_sphere(2.0, &b), KAIROS_OK);
    if (a == NULL || b == NULL) goto done;
    pose_b.position = vec3(5, 0, 0);
    pose_b.orientation.x = 0;
    pose_b.orientation.y = 0;
    pose_b.orientation.z = 0;
    pose_b.orientation.w = 1;
    memset(&result, 0, sizeof result);
    status = kairos_distance(a, NULL, b, &pose_b, NULL, &result);
    if (status == KAIROS_ERROR_NOT_IMPLEMENTED) {
        printf("kairos_distance: not implemented in this version (allowed)\n");
    } else {
        CHECK_STATUS(status, KAIROS_OK);
        CHECK(fabs(result.distance - 2.0) <= 1e-8);
        CHECK(result.intersecting == 0);
        CHECK(near3(result.point_a, vec3(1, 0, 0), 1e-6));
        CHECK(near3(result.point_b, vec3(3, 0, 0), 1e-6));
        CHECK(near3(result.axis, vec3(1, 0, 0), 1e-6));
    }
done:
    kairos_shape_release(a);
    kairos_shape_release(b);
}

/* kairos_last_error is per thread: a failure on another thread does not touch this one's. */
static void* fail_on_other_thread(void* arg) {
    char* seen = (char*)arg;
    kairos_shape* s = NULL;
    const char* message;
    (void)kairos_shape_sphere(-3.0, &s);
    message = kairos_last_error();
    strncpy(seen, message, 255);
    seen[255] = '\0';
    return NULL;
}

static void test_thread_local_error(void) {
    char mine[256], theirs[256];
    pthread_t thread;
    kairos_shape* s = NULL;
    CHECK_STATUS(kairos_shape_box(vec3(-1, 1, 1), &s), KAIROS_ERROR_INVALID_ARGUMENT);
    strncpy(mine, kairos_last_error(), sizeof mine - 1);
    mine[sizeof mine - 1] = '\0';
    theirs[0] = '\0';
    CHECK(pthread_create(&thread, NULL, fail_on_other_thread, theirs) == 0);
    CHECK(pthread_join(thread, NULL) == 0);
    CHECK(theirs[0] != '\0');
    CHECK(strcmp(mine, theirs) != 0);
    CHECK(strcmp(mine, kairos_last_error()) == 0);
}

int main(void) {
    test_version_and_names();
    test_shapes();
    test_bad_input();
    test_settings_and_world();
    test_distance_if_available();
    test_thread_local_error();
    if (failures != 0) {
        fprintf(stderr, "c99_program: %d check(s) failed\n", failures);
        return 1;
    }
    printf("c99_program: all checks passed (libkairos %u, header %d)\n", (unsigned)kairos_version(),
           KAIROS_VERSION_NUMBER);
    return 0;
}
