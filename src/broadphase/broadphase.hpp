// SPDX-License-Identifier: MIT
// Broad phase over one step: pairs of axis-aligned boxes that overlap at some moment of the step.
//
// Source: the talks' "space-time sweep and prune with queued swaps" (docs/algorithms.md §5). Each
// object has a box at the start (t = 0) and at the end (t = 1) of the step; every box coordinate
// moves linearly in t in between. A pair is reported with the first t in [0, 1] at which its
// boxes overlap on all three axes at once (closed boxes: touching counts as overlapping).
// Independent of shapes and of the C API: objects are plain uint32 ids chosen by the caller.
//
// Thread safety: none; one broad phase is used by one thread at a time.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "math/math.hpp"

namespace kairos {

// Closed axis-aligned box, world frame; min <= max on every axis, all finite.
struct Aabb {
    Vec3 min;
    Vec3 max;
};

// One object over one step: its box at t = 0 and at t = 1 (each coordinate linear in between).
struct SweptAabb {
    Aabb start;
    Aabb end;
};

// A reported pair: a < b (ids), and the first moment of the step in [0, 1] at which the boxes
// overlap on all three axes. The encapsulating variant also reports pairs whose boxes never
// overlap at one moment; their `t_first` is +infinity.
struct BroadPhasePair {
    uint32_t a = 0;
    uint32_t b = 0;
    double t_first = 0;
};

enum class BroadPhaseKind {
    SpacetimeSap,        // regions: columns along x, a sweep along x on the swept intervals in each,
                         // every candidate with a moving object tested exactly in space-time
    EncapsulatingSap,    // plain sweep and prune on the boxes swept over the whole step
    BruteForce,          // exact 4D box overlap of every pair, O(n^2): the reference
    SpacetimeSapQueued,  // the talks' sweep: one sorted array per axis, swaps queued in an indexed
                         // heap and done in time order
    SpacetimeSapGlobal,  // one sorted array per axis brought to the end order in one batch; every
                         // crossing that may start an overlap tested exactly in space-time. Research
                         // only: create() returns null unless built with KAIROS_RESEARCH_BROADPHASES
};

// "spacetime_sap", "encapsulating_sap", "brute_force", "spacetime_sap_queued",
// "spacetime_sap_global".
const char* to_string(BroadPhaseKind kind);

// Work done by one step (and, for teleport_swaps, by the teleports since the previous step).
struct BroadPhaseCounters {
    uint64_t pairs = 0;            // pairs reported by the step (false positives included)
    uint64_t false_positives = 0;  // reported pairs whose boxes never overlap at one moment
    uint64_t swaps = 0;            // adjacent swaps performed by the sweep: of endpoints (global and
                                   // queued sweeps), of swept intervals within a column (regions)
    uint64_t teleport_swaps = 0;   // swaps done by teleports since the previous step
    uint64_t heap_pushes = 0;
    uint64_t heap_pops = 0;       // events taken from the top of the heap
    uint64_t heap_updates = 0;    // key changes of a queued event (decrease or increase)
    uint64_t heap_removes = 0;    // queued events cancelled before their time
    uint64_t moving_objects = 0;  // objects given an end box different from their start box
    uint64_t crossing_tests = 0;  // exact space-time tests of candidates (global: pairs whose
                                  // endpoints crossed; regions: candidates with a moving object)
};

// The first moment in [0, 1] at which two swept boxes overlap on all three axes; false if they
// never do. Exact for linear coordinates up to one rounding of the crossing time
// `s0 / (s0 - s1)` of each separation s = (min of one box) - (max of the other); the space-time
// sweep computes its swap times with the same expression, so both agree on ties.
// Inline: the sweeps call it per candidate pair from several files.
inline bool first_overlap_time(const SweptAabb& a, const SweptAabb& b, double* out_t) {
    double lo = 0, hi = 1;
    // Overlap needs s(t) <= 0 for both separations s of an axis; s is linear, so each condition
    // holds on a half-line of t. Its end is s0 / (s0 - s1), the swap time of the sweep.
    auto condition = [&](double s0, double s1) {
        if (s0 <= 0) {
            if (s1 > 0) hi = std::min(hi, s0 / (s0 - s1));
        } else if (s1 <= 0) {
            lo = std::max(lo, s0 / (s0 - s1));
        } else {
            hi = -1;  // separated for the whole step
        }
    };
    for (int k = 0; k < 3; ++k) {
        condition(a.start.min[k] - b.start.max[k], a.end.min[k] - b.end.max[k]);
        condition(b.start.min[k] - a.start.max[k], b.end.min[k] - a.end.max[k]);
    }
    if (!(lo <= hi)) return false;
    *out_t = lo;
    return true;
}

// True if two boxes overlap (closed) on all three axes.
inline bool boxes_overlap(const Aabb& a, const Aabb& b) {
    for (int k = 0; k < 3; ++k) {
        if (a.min[k] > b.max[k] || b.min[k] > a.max[k]) return false;
    }
    return true;
}

// Sorts pairs by (a, b), stable (equal pairs keep their order). Ids below 2^30.
void sort_pairs(std::vector<BroadPhasePair>& pairs, std::vector<BroadPhasePair>& scratch);

// Order-preserving map of a double onto an unsigned integer: x < y iff key(x) < key(y), and
// -0.0 and +0.0 share one key. The sign is handled by flipping: negative values get all bits
// inverted, non-negative ones get the top bit set. NaN is not allowed.
uint64_t ordered_key(double x);

// A broad phase that persists between steps. Between steps: add, remove, teleport (a new box
// without sweeping). For the coming step: move (the box at the end of the step); objects not
// moved stay where they are. step() reports the pairs and moves every object to its end box.
// Pairs of two static objects are never reported; pairs already overlapping at the start are
// reported with t_first = 0, every step while they overlap. Ids are caller-chosen indices < 2^30.
// Steady state (no adds or removes) allocates nothing per swap: buffers grow to their peak once.
class BroadPhase {
public:
    static std::unique_ptr<BroadPhase> create(BroadPhaseKind kind);
    virtual ~BroadPhase();
    BroadPhase(const BroadPhase&) = delete;
    BroadPhase& operator=(const BroadPhase&) = delete;

    BroadPhaseKind kind() const { return kind_; }

    // Each returns false, changing nothing, on an id out of range or already used, or with
    // kMaxObjects present (add), an id not present (the others), a box with NaN, infinity or
    // min > max, or a move of a static object. Adds are inserted in bulk (one sort) at the next
    // step or flush().
    bool add(uint32_t id, const Aabb& box, bool is_static);
    bool remove(uint32_t id);
    // Sets the box at once, with no sweep between the old and the new one; cancels a move.
    bool teleport(uint32_t id, const Aabb& box);
    // The box at the end of the coming step (t = 1).
    bool move(uint32_t id, const Aabb& box_end);
    // A move that also replaces the box at the start of the coming step (as a teleport would;
    // the world's turning objects get a new start box every step). A broad phase whose step
    // re-examines every moving object anyway skips the teleport's own work.
    bool move(uint32_t id, const Aabb& box_start, const Aabb& box_end);

    // Sweeps the step and returns its pairs sorted by (a, b), each once. The buffer is owned by
    // the broad phase and valid until the next call of a non-const member.
    const std::vector<BroadPhasePair>& step();
    // Performs pending adds and removes now (step() does it anyway).
    void flush();

    const BroadPhaseCounters& counters() const { return counters_; }
    bool contains(uint32_t id) const;
    std::size_t size() const { return live_count_; }
    // The current box (start of the coming step); nullptr for an unknown id.
    const Aabb* box(uint32_t id) const;

    // Appends to `out` the id of every object present (added, not removed) whose current box
    // overlaps q (closed boxes), each once, in no particular order. Uses the broad phase's own
    // structure (the space-time sweep in regions: the columns q touches; the sorted endpoints:
    // the stretch of x before q within the longest extent); the references (encapsulating, brute
    // force) scan every object. q: finite, min <= max.
    void query_box(const Aabb& q, std::vector<uint32_t>& out) const { on_query_box(q, out); }
    // Size of the structure's spatial cells (0: none). A long thin query is best split into
    // pieces about this long on y and z (a query visits every column its box touches).
    virtual double query_cell_size() const { return 0; }
    // At least the largest extent along any axis of any box ever given (it never shrinks).
    double max_extent() const { return max_extent_; }
    // Changes whether the object is static (never moved; pairs of two static objects are never
    // reported). False, changing nothing, for an id not present, or when making static an object
    // given a move for the coming step.
    bool set_static(uint32_t id, bool is_static);

    // Debug check of the internal structure against brute force at the current moment; the
    // empty string if it holds, otherwise a description of the first fault. O(n^2).
    virtual std::string check_invariants() const;

    static constexpr uint32_t kMaxId = (1u << 30) - 1;
    static constexpr std::size_t kMaxObjects = std::size_t{1} << 28;  // event slots fit 32 bits

protected:
    explicit BroadPhase(BroadPhaseKind kind) : kind_(kind) {}

    enum class State : uint8_t { Absent, PendingAdd, Live, PendingRemove };
    struct Record {
        Aabb box;      // at the start of the coming step
        Aabb box_end;  // at its end; equals box unless moved
        State state = State::Absent;
        bool is_static = false;
        bool moving = false;  // listed in moving_ for the coming step
    };

    // Hooks of the implementations. on_flush inserts the ids in pending_adds_ and deletes the ids
    // in pending_removes_ (both sorted, disjoint); the base updates the records afterwards.
    virtual void on_flush() = 0;
    virtual void on_teleport(uint32_t id, const Aabb& old_box) = 0;
    // Fills pairs_ (any order, duplicates allowed: the base keeps the earliest) and the
    // counters; records still hold the start boxes and moving_ the moved ids (deduplicated).
    virtual void on_step() = 0;
    // True when step() re-keys every moving object and re-tests all its pairs, so a new start box
    // needs no work before it (move with a start box then skips on_teleport).
    virtual bool restarts_moving_objects() const { return false; }
    // query_box's work: by default every record.
    virtual void on_query_box(const Aabb& q, std::vector<uint32_t>& out) const;
    // A present object's static flag has just changed (records hold the new one): by default
    // nothing (the listed broad phases read the flag each step).
    virtual void on_static_change(uint32_t id) { (void)id; }

    // Objects present in the structure, by id: Live or PendingRemove. Brute force over them.
    void collect_present(std::vector<uint32_t>& out) const;
    // Objects a and b (either order) whose boxes may meet during the step: when the swept boxes
    // do, appends the pair and its first time to pairs_ and, when the end boxes overlap, its key
    // to `entered`. Counts a crossing test.
    void test_swept_pair(uint32_t a, uint32_t b, std::vector<uint64_t>& entered);

    BroadPhaseKind kind_;
    std::vector<Record> records_;
    std::vector<uint32_t> pending_adds_;
    std::vector<uint32_t> pending_removes_;
    std::vector<uint32_t> moving_;
    std::vector<BroadPhasePair> pairs_;
    std::vector<BroadPhasePair> sort_scratch_;
    BroadPhaseCounters counters_;
    // At least the longest extent along x of any box ever given (add, teleport, move): an
    // interval sorted by its start that reaches x starts after x minus this.
    double max_extent_x_ = 0;
    double max_extent_ = 0;  // the same over the three axes
    void note_extent(const Aabb& b) {
        max_extent_x_ = std::max(max_extent_x_, b.max.x - b.min.x);
        max_extent_ = std::max({max_extent_, b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
    }
    uint64_t teleport_swaps_since_step_ = 0;
    std::size_t live_count_ = 0;
};

}  // namespace kairos
