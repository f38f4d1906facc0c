// SPDX-License-Identifier: MIT
// C API world: the handle, object bookkeeping, step, contacts, overlaps and step stats.
#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

#include "boundary.hpp"
#include "world_handle.hpp"

using namespace kairos;
using namespace kairos::capi;

namespace {

Pose state_of(const BodyPose& p) { return {p.position, p.orientation}; }

// The size of kairos_world_settings in 0.1 (callers built then know no more).
constexpr uint32_t kWorldSettingsFirstSize = offsetof(kairos_world_settings, worker_count);

const World::Object& live_object(const kairos_world* w, kairos_object_id id, const char* function) {
    const World::Object* o = w->core.find(id);
    if (o == nullptr)
        fail(KAIROS_ERROR_STALE_ID, function, "id %llu is %s", static_cast<unsigned long long>(id),
             id == 0 ? "0, which is never a valid id" : "not a live object of this world (unknown or removed)");
    return *o;
}

Filter filter_of(const kairos_filter* f) {
    return f == nullptr ? Filter{} : Filter{f->category_bits, f->mask_bits, f->group};
}

// The C layout of a world query's hit, once its numbers are known to be finite (see boundary.hpp).
kairos_world_hit checked(const WorldHit& h, const char* fn) {
    kairos_world_hit c{};
    c.toi = 1;
    if (!h.hit) return c;
    require_finite_result(std::isfinite(h.toi) && is_finite(h.point) && is_finite(h.normal), fn);
    c.hit = 1;
    c.id = h.id;
    c.user_data = h.user_data;
    c.toi = h.toi;
    c.point = to_c(h.point);
    c.normal = to_c(h.normal);
    return c;
}

}  // namespace

extern "C" {

KAIROS_API void kairos_world_settings_init(kairos_world_settings* s) {
    if (s == nullptr) return;
    std::memset(s, 0, sizeof *s);
    s->struct_size = sizeof(kairos_world_settings);
    s->broad_phase = KAIROS_BROAD_PHASE_SPACETIME_SAP;
    kairos_query_settings_init(&s->query);
}

// The 0.1 init, kept for binaries linked against 0.1 (kairos_world_settings_init@KAIROS_0, see
// cmake/kairos.map) and for kairos_get_api(1): their struct ends before worker_count, so only its
// first fields are written, and struct_size says so.
// Named outside kairos_* so that only its versioned alias is exported.
KAIROS_API void world_settings_init_0_1(kairos_world_settings* s) {
    if (s == nullptr) return;
    std::memset(s, 0, kWorldSettingsFirstSize);
    s->struct_size = kWorldSettingsFirstSize;
    s->broad_phase = KAIROS_BROAD_PHASE_SPACETIME_SAP;
    kairos_query_settings_init(&s->query);
}
__asm__(".symver world_settings_init_0_1,kairos_world_settings_init@KAIROS_0");

KAIROS_API int32_t kairos_world_create(const kairos_world_settings* settings, kairos_world** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        kairos_world_settings defaults;
        kairos_world_settings_init(&defaults);
        if (settings == nullptr) settings = &defaults;
        // Callers built against 0.1 know the fields up to `query`; later fields take defaults.
        constexpr size_t kFirstSize = kWorldSettingsFirstSize;
        if (settings->struct_size < kFirstSize)
            fail(KAIROS_ERROR_STRUCT_SIZE, fn,
                 "settings->struct_size is %u, smaller than the %zu bytes of this struct's first version; call "
                 "kairos_world_settings_init",
                 settings->struct_size, kFirstSize);
        require_struct_size(settings, settings->struct_size,
                            settings->struct_size < sizeof(kairos_world_settings) ? settings->struct_size
                                                                                  : sizeof(kairos_world_settings),
                            fn, "settings");
        auto has = [&](size_t offset, size_t size) { return settings->struct_size >= offset + size; };
        const uint32_t workers =
            has(offsetof(kairos_world_settings, worker_count), sizeof(uint32_t)) ? settings->worker_count : 0;
        if (workers > Workers::kMaxThreads)
            fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "settings->worker_count is %u; at most %u", workers,
                 Workers::kMaxThreads);
        TaskHook hook;
        if (has(offsetof(kairos_world_settings, task_user_context), sizeof(void*))) {
            hook.enqueue = settings->enqueue_task;
            hook.finish = settings->finish_task;
            hook.user_context = settings->task_user_context;
        }
        if ((hook.enqueue == nullptr) != (hook.finish == nullptr))
            fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "settings->%s is NULL while settings->%s is set; give both or neither",
                 hook.enqueue == nullptr ? "enqueue_task" : "finish_task",
                 hook.enqueue == nullptr ? "finish_task" : "enqueue_task");
        const int32_t bp = settings->broad_phase;
        if (bp != KAIROS_BROAD_PHASE_SPACETIME_SAP && bp != KAIROS_BROAD_PHASE_ENCAPSULATING_SAP &&
            bp != KAIROS_BROAD_PHASE_BRUTE_FORCE && bp != KAIROS_BROAD_PHASE_SPACETIME_SAP_QUEUED)
            fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "settings->broad_phase %d is not a KAIROS_BROAD_PHASE_* value", bp);
        const QuerySettings qs = read_query_settings(&settings->query, fn, "settings->query");
        require_pointer(out, fn, "out");
        WorldSettings ws;
        ws.broad_phase = bp == KAIROS_BROAD_PHASE_ENCAPSULATING_SAP      ? BroadPhaseKind::EncapsulatingSap
                         : bp == KAIROS_BROAD_PHASE_BRUTE_FORCE          ? BroadPhaseKind::BruteForce
                         : bp == KAIROS_BROAD_PHASE_SPACETIME_SAP_QUEUED ? BroadPhaseKind::SpacetimeSapQueued
                                                                         : BroadPhaseKind::SpacetimeSap;
        ws.tolerance = qs.tolerance;
        ws.max_iterations = qs.max_iterations;
        ws.worker_count = workers;
        ws.task_hook = hook;
        *out = new kairos_world(ws);
    });
}

KAIROS_API void kairos_world_destroy(kairos_world* w) { delete w; }

KAIROS_API int32_t kairos_world_add(kairos_world* w, kairos_shape* s, const kairos_pose* pose, uint64_t user_data,
                                    kairos_object_id* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        require_pointer(s, fn, "s");
        const BodyPose p = read_pose(pose, fn, "pose");
        require_pointer(out, fn, "out");
        const uint64_t id = w->core.add(shape_of(s), state_of(p), user_data);
        if (id == 0) fail(KAIROS_ERROR_LIMIT, fn, "the world holds the maximum number of objects");
        *out = id;
    });
}

KAIROS_API int32_t kairos_world_remove(kairos_world* w, kairos_object_id id) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        live_object(w, id, fn);
        w->core.remove(id);
    });
}

KAIROS_API int32_t kairos_world_set_pose(kairos_world* w, kairos_object_id id, const kairos_pose* pose) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        live_object(w, id, fn);
        require_pointer(pose, fn, "pose");
        w->core.set_pose(id, state_of(read_pose(pose, fn, "pose")));
    });
}

KAIROS_API int32_t kairos_world_move(kairos_world* w, kairos_object_id id, const kairos_pose* end) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        const World::Object& o = live_object(w, id, fn);
        require_pointer(end, fn, "end");
        const BodyPose p = read_pose(end, fn, "end");
        if (o.is_static)
            fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "id %llu is static (kairos_world_set_static): it never moves",
                 static_cast<unsigned long long>(id));
        w->core.move(id, state_of(p));
    });
}

KAIROS_API int32_t kairos_world_move_batch(kairos_world* w, const kairos_object_id* ids, const kairos_pose* ends,
                                           size_t count) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        if (count == 0) return;
        require_pointer(ids, fn, "ids");
        require_pointer(ends, fn, "ends");
        // Every move is checked before any is given, and room is made for them all: then none
        // can fail, and a refused batch moves nothing.
        for (size_t i = 0; i < count; ++i) {
            const World::Object* o = w->core.find(ids[i]);
            if (o == nullptr)
                fail(KAIROS_ERROR_STALE_ID, fn, "ids[%zu] is %llu, %s", i, static_cast<unsigned long long>(ids[i]),
                     ids[i] == 0 ? "which is never a valid id" : "not a live object of this world (unknown or removed)");
            if (o->is_static)
                fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "ids[%zu] is %llu, a static object (kairos_world_set_static): it never moves",
                     i, static_cast<unsigned long long>(ids[i]));
            check_pose_element(ends, i, fn, "ends");
        }
        w->core.reserve_moves(count);
        for (size_t i = 0; i < count; ++i) w->core.move(ids[i], state_of(read_pose(&ends[i], fn, "ends")));
    });
}

KAIROS_API int32_t kairos_world_set_filter(kairos_world* w, kairos_object_id id, const kairos_filter* f) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        live_object(w, id, fn);
        require_pointer(f, fn, "f");
        w->core.set_filter(id, Filter{f->category_bits, f->mask_bits, f->group});
    });
}

KAIROS_API int32_t kairos_world_set_static(kairos_world* w, kairos_object_id id, int32_t is_static) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        live_object(w, id, fn);
        if (is_static != 0 && is_static != 1)
            fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "is_static is %d; give 0 or 1", is_static);
        w->core.set_static(id, is_static == 1);
    });
}

KAIROS_API int32_t kairos_world_get_pose(const kairos_world* w, kairos_object_id id, kairos_pose* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        const World::Object& o = live_object(w, id, fn);
        require_pointer(out, fn, "out");
        out->position = to_c(o.pose.position);
        out->orientation = {o.pose.orientation.x, o.pose.orientation.y, o.pose.orientation.z, o.pose.orientation.w};
    });
}

KAIROS_API int32_t kairos_world_get_user_data(const kairos_world* w, kairos_object_id id, uint64_t* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        const World::Object& o = live_object(w, id, fn);
        require_pointer(out, fn, "out");
        *out = o.user_data;
    });
}

KAIROS_API int32_t kairos_world_ray_cast(const kairos_world* w, kairos_vec3 origin, kairos_vec3 translation,
                                         const kairos_filter* filter, kairos_world_hit* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        const Vec3 o = read_point(origin, fn, "origin");
        const Vec3 t = read_point(translation, fn, "translation");
        const Filter f = filter_of(filter);
        require_pointer(out, fn, "out");
        *out = checked(w->core.ray_cast(o, t, filter != nullptr ? &f : nullptr), fn);
    });
}

KAIROS_API int32_t kairos_world_shape_cast(const kairos_world* w, const kairos_shape* s, const kairos_motion* motion,
                                           const kairos_filter* filter, const kairos_query_settings* settings,
                                           kairos_world_hit* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        require_pointer(s, fn, "s");
        require_pointer(motion, fn, "motion");
        const BodyPose p0 = read_pose(&motion->start, fn, "motion->start");
        const BodyPose p1 = read_pose(&motion->end, fn, "motion->end");
        const Filter f = filter_of(filter);
        QuerySettings qs{w->core.settings().tolerance, w->core.settings().max_iterations};
        if (settings != nullptr) qs = read_query_settings(settings, fn, "settings");
        require_pointer(out, fn, "out");
        *out = checked(w->core.shape_cast(shape_of(s), state_of(p0), state_of(p1), filter != nullptr ? &f : nullptr,
                                          qs.tolerance, qs.max_iterations),
                       fn);
    });
}

KAIROS_API int32_t kairos_world_query_box(const kairos_world* w, kairos_vec3 min, kairos_vec3 max,
                                          const kairos_filter* filter, kairos_object_id* ids, size_t capacity,
                                          size_t* count) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        const Vec3 lo = read_point(min, fn, "min");
        const Vec3 hi = read_point(max, fn, "max");
        for (int k = 0; k < 3; ++k) {
            if (!(lo[k] <= hi[k]))
                fail(KAIROS_ERROR_INVALID_ARGUMENT, fn, "min.%c (%.17g) is above max.%c (%.17g)", "xyz"[k], lo[k],
                     "xyz"[k], hi[k]);
        }
        const Filter f = filter_of(filter);
        if (capacity > 0) require_pointer(ids, fn, "ids");
        require_pointer(count, fn, "count");
        std::vector<uint64_t> found;
        w->core.query_box({lo, hi}, filter != nullptr ? &f : nullptr, found);
        const size_t n = found.size() < capacity ? found.size() : capacity;
        if (n > 0) std::memcpy(ids, found.data(), n * sizeof(kairos_object_id));
        *count = found.size();
    });
}

KAIROS_API int32_t kairos_world_step(kairos_world* w) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        w->core.step();
        const std::vector<Contact>& cs = w->core.contacts();
        w->contacts.resize(cs.size());
        for (size_t i = 0; i < cs.size(); ++i) {
            const Contact& c = cs[i];
            kairos_contact& k = w->contacts[i];
            k.a = c.a;
            k.b = c.b;
            k.user_a = c.user_a;
            k.user_b = c.user_b;
            k.toi = c.toi;
            k.point = to_c(c.point);
            k.normal = to_c(c.normal);
        }
    });
}

KAIROS_API int32_t kairos_world_contacts(const kairos_world* w, const kairos_contact** out, size_t* count) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        require_pointer(out, fn, "out");
        require_pointer(count, fn, "count");
        *out = w->contacts.data();
        *count = w->contacts.size();
    });
}

KAIROS_API int32_t kairos_world_overlaps(const kairos_world* w, const kairos_object_id** pairs, size_t* count) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        require_pointer(pairs, fn, "pairs");
        require_pointer(count, fn, "count");
        *pairs = w->core.overlap_ids().data();
        *count = w->core.overlap_ids().size() / 2;
    });
}

KAIROS_API void kairos_step_stats_init(kairos_step_stats* s) {
    if (s == nullptr) return;
    std::memset(s, 0, sizeof *s);
    s->struct_size = sizeof(kairos_step_stats);
}

KAIROS_API int32_t kairos_world_step_stats(const kairos_world* w, kairos_step_stats* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(w, fn, "w");
        require_pointer(out, fn, "out");
        if (out->struct_size < sizeof(uint32_t))
            fail(KAIROS_ERROR_STRUCT_SIZE, fn, "out->struct_size is %u; call kairos_step_stats_init", out->struct_size);
        const StepCounters& c = w->core.counters();
        kairos_step_stats full;
        kairos_step_stats_init(&full);
        full.broad_phase_pairs = c.broad_phase_pairs;
        full.swaps = c.swaps;
        full.heap_operations = c.heap_operations;
        full.narrow_phase_queries = c.narrow_phase_queries;
        full.gjk_iterations = c.gjk_iterations;
        full.broad_phase_seconds = c.broad_phase_seconds;
        full.narrow_phase_seconds = c.narrow_phase_seconds;
        // Older callers know a prefix; newer ones keep their unknown tail untouched.
        const size_t n = out->struct_size < sizeof full ? out->struct_size : sizeof full;
        const uint32_t caller_size = out->struct_size;
        std::memcpy(reinterpret_cast<unsigned char*>(out) + sizeof(uint32_t),
                    reinterpret_cast<const unsigned char*>(&full) + sizeof(uint32_t), n - sizeof(uint32_t));
        out->struct_size = caller_size;
    });
}

}  // extern "C"
