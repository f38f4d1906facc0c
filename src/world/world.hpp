// SPDX-License-Identifier: MIT
// The world: objects with shapes, poses and pending moves, addressed by generation-checked ids,
// and the step that finds each pair's first contact (broad phase, then narrow phase;
// docs/algorithms.md §6).
//
// Thread safety: none; a world is used by one thread at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "casts/cast.hpp"
#include "math/transform.hpp"
#include "shapes/shape.hpp"
#include "world/workers.hpp"

namespace kairos {

// The first contact of a pair in a step. World frame.
struct Contact {
    uint64_t a = 0, b = 0;  // ids, a < b
    uint64_t user_a = 0, user_b = 0;
    double toi = 1;  // fraction of the step in [0, 1]
    Vec3 point;      // contact point at toi
    Vec3 normal;     // unit, from a toward b
};

// A broad-phase pair of the last step: ids (a < b) and the first moment their boxes overlap.
struct WorldPair {
    uint64_t a = 0, b = 0;
    double t_first = 0;
};

// Work of the last step.
struct StepCounters {
    uint64_t broad_phase_pairs = 0, swaps = 0, heap_operations = 0, narrow_phase_queries = 0, gjk_iterations = 0;
    double broad_phase_seconds = 0, narrow_phase_seconds = 0;
    uint64_t moving_objects = 0;    // objects given a move that changes their pose
    uint64_t rotating_objects = 0;  // of which turn
    uint64_t axis_rejections = 0;   // pairs a cached separating axis ruled out without a cast
    uint64_t false_positives = 0;   // broad-phase pairs whose boxes never overlap (encapsulating)
    uint64_t contacts = 0;
    uint64_t filtered_pairs = 0;  // broad-phase pairs a filter or two static objects rule out
};

// Which pairs collide (as Box2D's filter): two objects of the same non-zero group always collide
// when the group is > 0 and never when it is < 0; otherwise a pair collides when each one's
// category has a bit in the other's mask.
struct Filter {
    uint32_t category_bits = 1;
    uint32_t mask_bits = 0xffffffffu;
    int32_t group = 0;
};
inline bool filters_collide(const Filter& a, const Filter& b) {
    if (a.group != 0 && a.group == b.group) return a.group > 0;
    return (a.category_bits & b.mask_bits) != 0 && (b.category_bits & a.mask_bits) != 0;
}

// The earliest hit of a world query (World::ray_cast, World::shape_cast). World frame.
struct WorldHit {
    bool hit = false;
    uint64_t id = 0, user_data = 0;
    double toi = 1;  // fraction of the query's motion in [0, 1]
    Vec3 point;      // the contact at toi
    Vec3 normal;     // unit, outward from the object hit
    uint32_t casts = 0;  // pair casts run (work, for tests and benchmarks)
};

struct WorldSettings {
    BroadPhaseKind broad_phase = BroadPhaseKind::SpacetimeSap;
    double tolerance = 1e-10;       // relative accuracy of the casts (docs/c-api.md "Tolerances")
    uint32_t max_iterations = 256;  // a guard only
    uint32_t worker_count = 0;      // threads of the motion bounds and narrow phase, the caller's included
    TaskHook task_hook;             // an engine's scheduler instead of the world's own threads
};

class World {
public:
    struct Object {
        const Shape* shape = nullptr;  // holds one reference while alive
        Pose pose;                     // pose now (start of the next step)
        Pose end;                      // pose at the end of the next step, when `moving`
        Aabb box;                      // the broad phase's box now: the tight box at `pose` grown by
                                       // the margin, or larger after a turn (`loose`)
        bool moving = false;
        bool loose = false;
        bool is_static = false;  // never given a move; a pair of two static objects is never tested
        Filter filter;
        uint64_t user_data = 0;
        uint32_t generation = 1;  // of the current or next occupant of the slot
        bool alive = false;
    };

    explicit World(const WorldSettings& settings = {});
    World(const World&) = delete;
    World& operator=(const World&) = delete;
    ~World();

    const WorldSettings& settings() const { return settings_; }

    // An id packs the slot index (low 32 bits) and its generation (high 32 bits, >= 1), so 0 is
    // never an id and a removed object's id never matches the slot's next occupant.
    static uint64_t make_id(uint32_t index, uint32_t generation) { return (uint64_t{generation} << 32) | index; }
    static uint32_t index_of(uint64_t id) { return static_cast<uint32_t>(id & 0xffffffffu); }

    // Adds an object (retains the shape) standing still at `pose` (finite, unit quaternion).
    // Returns 0 when no slot can be had (BroadPhase::kMaxId + 1 slots). Throws std::bad_alloc
    // with nothing changed.
    uint64_t add(const Shape& shape, const Pose& pose, uint64_t user_data);
    // The live object with this id, or nullptr for 0, unknown and removed ids.
    const Object* find(uint64_t id) const;
    // Removes a live object (releases its shape); its id becomes stale. False for a stale id.
    bool remove(uint64_t id);
    // Teleports at once, without a sweep, and cancels a pending move. False for a stale id.
    bool set_pose(uint64_t id, const Pose& pose);
    // The pose at the end of the next step (that step only). False for a stale id or a static
    // object (nothing changes).
    bool move(uint64_t id, const Pose& end);
    // Room for `count` more moves: the next `count` calls of move() then cannot throw (a batch
    // of moves is all or nothing). Throws std::bad_alloc with nothing changed.
    void reserve_moves(std::size_t count) { moved_.reserve(moved_.size() + count); }
    // Static objects never move in a step (a pending move is cancelled); set_pose still places
    // them. False for a stale id.
    bool set_static(uint64_t id, bool is_static);
    // Pairs the filter rejects never reach the narrow phase, the contacts or the pairs. False for
    // a stale id.
    bool set_filter(uint64_t id, const Filter& filter);
    // Whether the pair of live objects in these slots is tested at all (filters, both static).
    bool pair_wanted(uint32_t a, uint32_t b) const {
        const Object& oa = objects_[a];
        const Object& ob = objects_[b];
        return !(oa.is_static && ob.is_static) && filters_collide(oa.filter, ob.filter);
    }

    // Finds each pair's first contact in [0, 1], then moves every object to its end pose and
    // clears the pending moves. Fills contacts, pairs and counters.
    void step();

    // Queries at the current poses (pending moves are not applied). filter: nullptr for every
    // object, else the objects whose filter collides with it (filters_collide). They change
    // nothing and share no scratch: several threads may query while no thread changes the world.
    // Ids of the objects whose tight bounding box at the pose overlaps q (closed, finite), in
    // increasing order, replacing out's contents.
    void query_box(const Aabb& q, const Filter* filter, std::vector<uint64_t>& out) const;
    // The earliest object hit by the ray origin + t translation, t in [0, 1] (kairos::ray_cast
    // with the world's settings); ties: the smaller id.
    WorldHit ray_cast(Vec3 origin, Vec3 translation, const Filter* filter) const;
    // The earliest object `shape` hits following start -> end (a translation: shape_cast; a turn:
    // motion_cast), the objects standing still; ties: the smaller id.
    WorldHit shape_cast(const Shape& shape, const Pose& start, const Pose& end, const Filter* filter, double tolerance,
                        uint32_t max_iterations) const;

    size_t live_count() const { return live_; }
    const std::vector<Object>& objects() const { return objects_; }
    const BroadPhase& broad_phase() const { return *broad_; }
    // The threads of the step (settings' worker_count or task hook), lent to batches of pair
    // queries. One job at a time: not while the world steps or another batch runs on it.
    Workers& workers() { return *workers_; }

    // Of the last step, valid until the next step.
    const std::vector<Contact>& contacts() const { return contacts_; }
    // Broad-phase pairs sorted by (a, b) ids.
    const std::vector<WorldPair>& pairs() const { return pairs_; }
    // The same pairs as 2 ids each (the C API hands this out).
    const std::vector<uint64_t>& overlap_ids() const { return overlap_ids_; }
    const StepCounters& counters() const { return counters_; }

private:
    // What the narrow phase needs of an object during one step.
    struct Sweep {
        Transform start;   // rigid pose at t = 0
        Vec3 translation;  // of the local origin over the step
        Vec3 axis;         // world rotation axis (unit) when turning
        double disk = 0;   // disk bound of the turn (docs/algorithms.md §4); 0 when not turning
        bool rotates = false;
    };
    // A separating axis found for a pair, kept for its next step (docs/algorithms.md §2).
    struct CachedAxis {
        uint64_t key;         // slot pair (lower slot << 32 | higher slot)
        uint64_t id_a, id_b;  // the ids it was found for (a slot's next occupant must not use it)
        Vec3 axis;            // world frame, from id_a's object toward id_b's
    };

    Aabb tight_box(const Shape& shape, const Pose& pose, Vec3 translation) const;
    Object* find_mutable(uint64_t id);
    // The motion pose -> end of a shape and its boxes at t = 0 and t = 1. box_now: the box it
    // has at `pose` when known (a translation then keeps it as the start box), else nullptr.
    // One pair of the narrow phase: found by the sequential pass over the broad-phase pairs, cast
    // by any worker, its outcome merged back in pair order (so no result depends on the workers).
    struct NarrowJob {
        uint32_t ia, ib;  // slots, id_a < id_b
        uint64_t id_a, id_b, key;
        Vec3 seed;  // a cached separating axis, or zero
    };
    struct NarrowOutcome {
        enum Kind : uint8_t { Rejected, Hit, Missed } kind = Missed;
        bool keep_axis = false;  // `axis` is a separating axis to cache for the next step
        Vec3 axis;
        CastResult cast;
        uint32_t extra_iterations = 0;  // of the end-pose check after a miss
    };
    void narrow_job(const NarrowJob& job, NarrowOutcome& out) const;
    Sweep sweep_of(const Shape& shape, const Pose& pose, const Pose& end, const Aabb* box_now, Aabb* out_start,
                   Aabb* out_end) const;
    // The slots whose broad-phase box, grown by `pad`, the box swept linearly over s (grown by
    // `pad` too) meets, and the filter admits, as (first time they meet, slot), sorted: a lower
    // bound on the time of any hit the casts report within `pad` of contact.
    double hit_pad(double tolerance, double reach) const;
    void sweep_candidates(const SweptAabb& s, double pad, const Filter* filter,
                          std::vector<std::pair<double, uint32_t>>& out) const;
    void narrow_phase(const std::vector<BroadPhasePair>& bp_pairs);

    WorldSettings settings_;
    std::unique_ptr<BroadPhase> broad_;
    std::vector<Object> objects_;
    std::vector<uint32_t> free_slots_;
    std::vector<uint32_t> moved_;  // slots given a move since the last step (may repeat)
    std::vector<uint32_t> loose_;  // slots whose box is looser than their pose needs
    size_t live_ = 0;

    std::vector<Sweep> sweeps_;   // by slot, filled for moving objects during a step
    std::vector<uint8_t> swept_;  // by slot: sweeps_ holds this step's motion
    std::vector<CachedAxis> axes_, next_axes_;
    std::vector<SweptAabb> motion_boxes_;  // by position in moved_: boxes at t = 0 and t = 1
    std::vector<NarrowJob> jobs_;
    std::vector<NarrowOutcome> outcomes_;
    std::unique_ptr<Workers> workers_;

    std::vector<Contact> contacts_;
    std::vector<WorldPair> pairs_;
    std::vector<uint64_t> overlap_ids_;
    StepCounters counters_;
};

}  // namespace kairos
