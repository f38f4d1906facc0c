// SPDX-License-Identifier: MIT
// C API batches of pair queries: kairos_distance_batch, kairos_shape_cast_batch,
// kairos_motion_cast_batch (kairos_world_move_batch is with the world, capi/world.cpp).
//
// Every query is checked on the calling thread before any is computed, so a refused batch names
// its first bad query whatever the threads. The results go to scratch memory and reach `out`
// only when all are finite: a refused batch writes nothing.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "boundary.hpp"
#include "casts/cast.hpp"
#include "gjk/gjk.hpp"
#include "motion/motion_cast.hpp"
#include "results.hpp"
#include "world_handle.hpp"

using namespace kairos;
using namespace kairos::capi;

namespace {

void check_shape_element(const kairos_shape* const* shapes, size_t i, const char* fn, const char* name) {
    if (shapes[i] == nullptr) fail(KAIROS_ERROR_NULL_ARGUMENT, fn, "%s[%zu] is NULL", name, i);
}

void check_point_element(const kairos_vec3* points, size_t i, const char* fn, const char* name) {
    if (points == nullptr) return;
    const kairos_vec3& v = points[i];
    if (std::fabs(v.x) <= KAIROS_MAX_MAGNITUDE && std::fabs(v.y) <= KAIROS_MAX_MAGNITUDE &&
        std::fabs(v.z) <= KAIROS_MAX_MAGNITUDE)
        return;  // NaN fails the comparisons and takes the path below
    char element[96];
    std::snprintf(element, sizeof element, "%s[%zu]", name, i);
    read_point(v, fn, element);
}

inline Vec3 point_at(const kairos_vec3* points, size_t i) {
    if (points == nullptr) return {};
    return {points[i].x, points[i].y, points[i].z};
}

// Pose i of an array already checked (NULL: identity).
inline Transform transform_at(const kairos_pose* poses, size_t i) {
    return poses == nullptr ? Transform{} : checked_transform(poses[i]);
}

// A motion's pose already checked.
Pose checked_pose(const kairos_pose& p) {
    return {{p.position.x, p.position.y, p.position.z}, unit_quat(p.orientation, squared_length(p.orientation))};
}

// Runs query(i, result) for i in [0, count) on the calling thread or the world's workers, into
// scratch; then, unless a result is not finite (the batch fails naming the first such query),
// copies the results to out.
template <class Result, class Query>
void run_batch(size_t count, kairos_world* workers, Result* out, const char* fn, Query&& query) {
    const std::unique_ptr<Result[]> scratch(new Result[count]);
    std::atomic<size_t> first_bad{count};
    auto range = [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            if (!query(i, scratch[i])) {
                size_t seen = first_bad.load(std::memory_order_relaxed);
                while (i < seen && !first_bad.compare_exchange_weak(seen, i, std::memory_order_relaxed)) {
                }
                return;  // the rest of this range is not needed: the batch fails
            }
        }
    };
    if (workers == nullptr) {
        range(0, count);
    } else {
        // Workers count in 32 bits: a larger batch runs as several jobs.
        constexpr size_t kJob = size_t{1} << 31;
        for (size_t base = 0; base < count && first_bad.load() == count; base += kJob) {
            const auto n = static_cast<uint32_t>(std::min(kJob, count - base));
            auto job = [&](uint32_t begin, uint32_t end) { range(base + begin, base + end); };
            workers->core.workers().run(n, 64, job);
        }
    }
    const size_t bad = first_bad.load();
    if (bad != count)
        fail(KAIROS_ERROR_INVALID_ARGUMENT, fn,
             "query %zu: the inputs together exceed the range double precision resolves (shape sizes and "
             "positions near KAIROS_MAX_MAGNITUDE): no finite result",
             bad);
    std::copy(scratch.get(), scratch.get() + count, out);
}

// What the three batches share, in the single call's order: every query's elements
// (check(i), which fails naming the first bad one), the settings, then out; then each query's
// core result (compute(i, settings)) goes through the finiteness guard into its C layout.
template <class Result, class Check, class Compute>
void batch(const char* fn, size_t count, Check&& check, const kairos_query_settings* settings, kairos_world* workers,
           Result* out, Compute&& compute) {
    for (size_t i = 0; i < count; ++i) check(i);
    const QuerySettings qs = read_query_settings(settings, fn, "settings");
    if (count == 0) return;
    require_pointer(out, fn, "out");
    run_batch(count, workers, out, fn, [&](size_t i, Result& r) {
        const auto core = compute(i, qs);
        if (!is_finite_result(core)) return false;
        write_c(core, r);
        return true;
    });
}

}  // namespace

extern "C" {

KAIROS_API int32_t kairos_distance_batch(const kairos_shape* const* a, const kairos_pose* poses_a,
                                         const kairos_shape* const* b, const kairos_pose* poses_b, size_t count,
                                         const kairos_query_settings* settings, kairos_world* workers,
                                         kairos_distance_result* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        // In the single call's order: the queries, the settings, then out.
        if (count > 0) {
            require_pointer(a, fn, "a");
            require_pointer(b, fn, "b");
        }
        auto check = [&](size_t i) {
            check_shape_element(a, i, fn, "a");
            check_pose_element(poses_a, i, fn, "poses_a");
            check_shape_element(b, i, fn, "b");
            check_pose_element(poses_b, i, fn, "poses_b");
        };
        batch(fn, count, check, settings, workers, out, [&](size_t i, const QuerySettings& qs) {
            return gjk_distance(shape_of(a[i]), transform_at(poses_a, i), shape_of(b[i]), transform_at(poses_b, i),
                                qs.tolerance, qs.max_iterations);
        });
    });
}

KAIROS_API int32_t kairos_shape_cast_batch(const kairos_shape* const* a, const kairos_pose* poses_a,
                                           const kairos_vec3* translations_a, const kairos_shape* const* b,
                                           const kairos_pose* poses_b, const kairos_vec3* translations_b,
                                           size_t count, const kairos_query_settings* settings,
                                           kairos_world* workers, kairos_cast_result* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        if (count > 0) {
            require_pointer(a, fn, "a");
            require_pointer(b, fn, "b");
        }
        auto check = [&](size_t i) {
            check_shape_element(a, i, fn, "a");
            check_pose_element(poses_a, i, fn, "poses_a");
            check_point_element(translations_a, i, fn, "translations_a");
            check_shape_element(b, i, fn, "b");
            check_pose_element(poses_b, i, fn, "poses_b");
            check_point_element(translations_b, i, fn, "translations_b");
        };
        batch(fn, count, check, settings, workers, out, [&](size_t i, const QuerySettings& qs) {
            return kairos::shape_cast(shape_of(a[i]), transform_at(poses_a, i), point_at(translations_a, i),
                                      shape_of(b[i]), transform_at(poses_b, i), point_at(translations_b, i),
                                      qs.tolerance, qs.max_iterations);
        });
    });
}

KAIROS_API int32_t kairos_motion_cast_batch(const kairos_shape* const* a, const kairos_motion* motions_a,
                                            const kairos_shape* const* b, const kairos_motion* motions_b,
                                            size_t count, const kairos_query_settings* settings,
                                            kairos_world* workers, kairos_cast_result* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        if (count > 0) {
            require_pointer(a, fn, "a");
            require_pointer(motions_a, fn, "motions_a");
            require_pointer(b, fn, "b");
            require_pointer(motions_b, fn, "motions_b");
        }
        auto check = [&](size_t i) {
            check_shape_element(a, i, fn, "a");
            // The motions' poses as elements of arrays of (start, end) pairs: "motions_a[3].end".
            const kairos_motion& ma = motions_a[i];
            const kairos_motion& mb = motions_b[i];
            const kairos_pose* poses[4] = {&ma.start, &ma.end, &mb.start, &mb.end};
            for (int k = 0; k < 4; ++k) {
                if (passes_pose_test(*poses[k], squared_length(poses[k]->orientation))) continue;
                char name[96];
                std::snprintf(name, sizeof name, "motions_%c[%zu].%s", k < 2 ? 'a' : 'b', i, k % 2 == 0 ? "start" : "end");
                read_pose_checked(poses[k], fn, name);
            }
            check_shape_element(b, i, fn, "b");
        };
        batch(fn, count, check, settings, workers, out, [&](size_t i, const QuerySettings& qs) {
            const Motion ma(checked_pose(motions_a[i].start), checked_pose(motions_a[i].end));
            const Motion mb(checked_pose(motions_b[i].start), checked_pose(motions_b[i].end));
            return kairos::motion_cast(shape_of(a[i]), ma, shape_of(b[i]), mb, qs.tolerance, qs.max_iterations);
        });
    });
}

}  // extern "C"
