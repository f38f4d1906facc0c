/* SPDX-License-Identifier: MIT */
/* ABI test: load libkairos with dlopen, use it only through kairos_get_api, and check dlclose unloads it. */
/*
 * Usage: kairos_abi_dlopen <path to libkairos.so.0>. The program is not linked against the
 * library; it includes the header for the types only. Exits non-zero on any wrong answer.
 */
#define _GNU_SOURCE /* dlvsym */

#include <dlfcn.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <kairos/kairos.h>

static int failures = 0;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            ++failures;                                                              \
        }                                                                            \
    } while (0)

typedef int32_t (*get_api_fn)(uint32_t, const kairos_api**);

/* True when the object is still mapped in this process (RTLD_NOLOAD never loads it). */
static int is_loaded(const char* name) {
    void* handle = dlopen(name, RTLD_LAZY | RTLD_NOLOAD);
    if (handle == NULL) return 0;
    dlclose(handle); /* drop the reference RTLD_NOLOAD just took */
    return 1;
}

static void use_table(const kairos_api* api) {
    kairos_shape* shape = NULL;
    kairos_vec3 half, dir, out;
    kairos_vec3 lo = {0, 0, 0}, hi = {0, 0, 0};
    int32_t status;

    /* Every entry this program knows lies within the table the library gave. */
    CHECK(api->struct_size >= sizeof(kairos_api));
    CHECK(api->abi_version == KAIROS_ABI_VERSION);
    CHECK(api->version != NULL && api->version() == KAIROS_VERSION_NUMBER);
    CHECK(api->status_name != NULL && strcmp(api->status_name(KAIROS_OK), "KAIROS_OK") == 0);
    CHECK(api->world_step_stats != NULL); /* the last entry of ABI version 1 */
    CHECK(api->shape_triangle != NULL);
    CHECK(api->signed_distance != NULL);
    CHECK(api->world_get_user_data != NULL);
    CHECK(api->world_query_box != NULL);
    CHECK(api->world_move_batch != NULL);  /* the last entry of ABI version 2 */

    half.x = 1.0;
    half.y = 2.0;
    half.z = 3.0;
    status = api->shape_box(half, &shape);
    CHECK(status == KAIROS_OK);
    if (status != KAIROS_OK || shape == NULL) {
        fprintf(stderr, "shape_box: %s: %s\n", api->status_name(status), api->last_error());
        return;
    }
    dir.x = -1.0;
    dir.y = 1.0;
    dir.z = -1.0;
    status = api->shape_support(shape, dir, &out);
    CHECK(status == KAIROS_OK);
    CHECK(out.x == -1.0 && out.y == 2.0 && out.z == -3.0);
    status = api->shape_bounds(shape, NULL, &lo, &hi);
    CHECK(status == KAIROS_OK);
    CHECK(lo.x == -1.0 && lo.y == -2.0 && lo.z == -3.0 && hi.x == 1.0 && hi.y == 2.0 && hi.z == 3.0);
    api->shape_retain(shape);
    api->shape_release(shape);
    api->shape_release(shape);

    /* A failure through the table sets the same per-thread message. */
    shape = NULL;
    status = api->shape_sphere(NAN, &shape);
    CHECK(status == KAIROS_ERROR_INVALID_ARGUMENT);
    CHECK(shape == NULL);
    CHECK(strstr(api->last_error(), "radius") != NULL);
}

int main(int argc, char** argv) {
    const char* path;
    void* library;
    void* symbol;
    get_api_fn get_api;
    const kairos_api* api = NULL;
    const kairos_api* other = NULL;

    if (argc != 2) {
        fprintf(stderr, "usage: %s <path to libkairos.so.0>\n", argv[0]);
        return 2;
    }
    path = argv[1];
    if (is_loaded(path) || is_loaded("libkairos.so.0")) {
        fprintf(stderr, "libkairos is already loaded before dlopen: this program must not link it\n");
        return 1;
    }

    library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (library == NULL) {
        fprintf(stderr, "dlopen(%s): %s\n", path, dlerror());
        return 1;
    }
    /* ISO C has no object-to-function pointer conversion; POSIX guarantees the bytes agree. */
    symbol = dlsym(library, "kairos_get_api");
    if (symbol == NULL) {
        fprintf(stderr, "dlsym(kairos_get_api): %s\n", dlerror());
        dlclose(library);
        return 1;
    }
    memcpy(&get_api, &symbol, sizeof get_api);

    CHECK(get_api(KAIROS_ABI_VERSION, &api) == KAIROS_OK);
    if (api != NULL) use_table(api);

    /* A caller of ABI version 1 (Kairos 0.1) has the 0.1 kairos_world_settings, which ends before
     * worker_count: its init, through the version-1 table or as the symbol version KAIROS_0 that
     * 0.1 binaries bind to, writes no byte past that struct, and the world accepts it. */
    {
        const kairos_api* v1 = NULL;
        void* old_init_symbol = dlvsym(library, "kairos_world_settings_init", "KAIROS_0");
        void (*old_init)(kairos_world_settings*) = NULL;
        const size_t v1_size = offsetof(kairos_world_settings, worker_count);
        int round;
        CHECK(get_api(1u, &v1) == KAIROS_OK);
        CHECK(old_init_symbol != NULL);
        if (old_init_symbol != NULL) memcpy(&old_init, &old_init_symbol, sizeof old_init);
        for (round = 0; round < 2 && v1 != NULL; ++round) {
            union {
                kairos_world_settings s;
                unsigned char bytes[sizeof(kairos_world_settings)];
            } buffer;
            kairos_world* world = NULL;
            size_t i;
            void (*init)(kairos_world_settings*) = round == 0 ? v1->world_settings_init : old_init;
            if (init == NULL) continue;
            memset(buffer.bytes, 0xA5, sizeof buffer.bytes);
            init(&buffer.s);
            CHECK(buffer.s.struct_size == v1_size);
            for (i = v1_size; i < sizeof buffer.bytes; ++i) CHECK(buffer.bytes[i] == 0xA5);
            CHECK(v1->world_create(&buffer.s, &world) == KAIROS_OK);
            if (world != NULL) v1->world_destroy(world);
        }
        if (v1 != NULL) CHECK(v1->struct_size == offsetof(kairos_api, shape_triangle));
    }

    /* Versions the library does not provide, and bad pointers, are errors that write nothing. */
    other = (const kairos_api*)&failures;
    CHECK(get_api(KAIROS_ABI_VERSION + 1000u, &other) == KAIROS_ERROR_UNSUPPORTED_VERSION);
    CHECK(other == (const kairos_api*)&failures);
    if (api != NULL) CHECK(strstr(api->last_error(), "abi_version") != NULL);
    CHECK(get_api(0u, &other) == KAIROS_ERROR_UNSUPPORTED_VERSION);
    CHECK(other == (const kairos_api*)&failures);
    CHECK(get_api(KAIROS_ABI_VERSION, NULL) == KAIROS_ERROR_NULL_ARGUMENT);

    CHECK(is_loaded(path));
    CHECK(is_loaded("libkairos.so.0"));
    if (dlclose(library) != 0) {
        fprintf(stderr, "dlclose: %s\n", dlerror());
        ++failures;
    }
    /* After the last dlclose the library must be gone: no GNU unique symbols, no thread_local
     * objects with destructors, no -z nodelete. */
    if (is_loaded(path) || is_loaded("libkairos.so.0")) {
        fprintf(stderr, "libkairos is still loaded after dlclose: look for UNIQUE symbols "
                        "(readelf -Ws), thread_local objects with destructors, or DF_1_NODELETE "
                        "(readelf -d)\n");
        ++failures;
    }

    if (failures != 0) {
        fprintf(stderr, "dlopen_test: %d check(s) failed\n", failures);
        return 1;
    }
    printf("dlopen_test: all checks passed; the library unloaded on dlclose\n");
    return 0;
}
