// SPDX-License-Identifier: MIT
// Broad phase: the base class (checks of the calls, pending adds and removes, moves, the step's
// pair list) and the choice of a kind; each kind is built in its own file (factories.hpp).
//
// Measured (bench/bench_world.cpp, bench/results/world.csv): the queued sweep spends ~100-200 ns
// per swap on heap work and cache misses, and a uniform scene has ~42 swaps per moving box per
// step at 10k boxes; the global batch sweep does the same swaps at a few ns each; the region sweep
// makes the swaps local to columns (under one per box) and is the default (SpacetimeSap).
#include "broadphase/broadphase.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "broadphase/box_time.hpp"
#include "broadphase/factories.hpp"

namespace kairos {

namespace {

using broadphase_detail::valid_box;

bool same_box(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

}  // namespace

const char* to_string(BroadPhaseKind kind) {
    switch (kind) {
        case BroadPhaseKind::SpacetimeSap:
            return "spacetime_sap";
        case BroadPhaseKind::SpacetimeSapQueued:
            return "spacetime_sap_queued";
        case BroadPhaseKind::SpacetimeSapGlobal:
            return "spacetime_sap_global";
        case BroadPhaseKind::EncapsulatingSap:
            return "encapsulating_sap";
        case BroadPhaseKind::BruteForce:
            return "brute_force";
    }
    return "unknown";
}

std::unique_ptr<BroadPhase> BroadPhase::create(BroadPhaseKind kind) {
    switch (kind) {
        case BroadPhaseKind::SpacetimeSap:
            return broadphase_detail::make_spacetime_sap();
        case BroadPhaseKind::SpacetimeSapGlobal:
#if KAIROS_RESEARCH_BROADPHASES
            return broadphase_detail::make_global_sap();
#else
            return nullptr;
#endif
        case BroadPhaseKind::SpacetimeSapQueued:
            return broadphase_detail::make_queued_sap();
        case BroadPhaseKind::EncapsulatingSap:
            return broadphase_detail::make_encapsulating_sap();
        case BroadPhaseKind::BruteForce:
            return broadphase_detail::make_brute_force();
    }
    return nullptr;
}

BroadPhase::~BroadPhase() = default;

bool BroadPhase::contains(uint32_t id) const {
    return id < records_.size() && (records_[id].state == State::Live || records_[id].state == State::PendingAdd);
}

const Aabb* BroadPhase::box(uint32_t id) const { return contains(id) ? &records_[id].box : nullptr; }

bool BroadPhase::add(uint32_t id, const Aabb& box, bool is_static) {
    if (id > kMaxId || !valid_box(box) || contains(id) || live_count_ >= kMaxObjects) return false;
    if (id >= records_.size()) records_.resize(static_cast<std::size_t>(id) + 1);
    if (records_[id].state == State::PendingRemove) flush();  // the old object must leave first
    Record& r = records_[id];
    r.box = box;
    r.box_end = box;
    note_extent(box);
    r.state = State::PendingAdd;
    r.is_static = is_static;
    r.moving = false;
    pending_adds_.push_back(id);
    ++live_count_;
    return true;
}

bool BroadPhase::remove(uint32_t id) {
    if (!contains(id)) return false;
    Record& r = records_[id];
    r.state = r.state == State::PendingAdd ? State::Absent : State::PendingRemove;
    if (r.state == State::PendingRemove) pending_removes_.push_back(id);
    r.moving = false;
    --live_count_;
    return true;
}

bool BroadPhase::teleport(uint32_t id, const Aabb& box) {
    if (!contains(id) || !valid_box(box)) return false;
    Record& r = records_[id];
    const Aabb old = r.box;
    r.box = box;
    r.box_end = box;
    note_extent(box);
    if (r.state == State::Live) on_teleport(id, old);
    return true;
}

bool BroadPhase::move(uint32_t id, const Aabb& box_end) {
    if (!contains(id) || !valid_box(box_end) || records_[id].is_static) return false;
    Record& r = records_[id];
    r.box_end = box_end;
    note_extent(box_end);
    if (!r.moving) {
        r.moving = true;
        moving_.push_back(id);
    }
    return true;
}

bool BroadPhase::set_static(uint32_t id, bool is_static) {
    if (!contains(id)) return false;
    Record& r = records_[id];
    if (r.is_static == is_static) return true;
    if (is_static && r.moving) return false;
    r.is_static = is_static;
    if (r.state == State::Live) on_static_change(id);
    return true;
}

void BroadPhase::on_query_box(const Aabb& q, std::vector<uint32_t>& out) const {
    for (uint32_t id = 0; id < records_.size(); ++id) {
        if (contains(id) && boxes_overlap(records_[id].box, q)) out.push_back(id);
    }
}

bool BroadPhase::move(uint32_t id, const Aabb& box_start, const Aabb& box_end) {
    if (!contains(id) || !valid_box(box_start) || !valid_box(box_end) || records_[id].is_static) return false;
    Record& r = records_[id];
    if (!(box_start.min == r.box.min && box_start.max == r.box.max)) {
        // Only an object that then moves is re-examined by the step (see step()).
        if (r.state == State::Live && restarts_moving_objects() && !same_box(box_start, box_end)) {
            r.box = box_start;
            note_extent(box_start);
        } else {
            teleport(id, box_start);
        }
    }
    return move(id, box_end);
}

void BroadPhase::flush() {
    // The lists may hold ids whose state changed since they were queued.
    std::sort(pending_adds_.begin(), pending_adds_.end());
    pending_adds_.erase(std::unique(pending_adds_.begin(), pending_adds_.end()), pending_adds_.end());
    std::erase_if(pending_adds_, [&](uint32_t id) { return records_[id].state != State::PendingAdd; });
    std::sort(pending_removes_.begin(), pending_removes_.end());
    if (pending_adds_.empty() && pending_removes_.empty()) return;
    on_flush();
    for (uint32_t id : pending_removes_) records_[id] = Record{};
    for (uint32_t id : pending_adds_) records_[id].state = State::Live;
    pending_adds_.clear();
    pending_removes_.clear();
}

const std::vector<BroadPhasePair>& BroadPhase::step() {
    flush();
    counters_ = BroadPhaseCounters{};
    counters_.teleport_swaps = teleport_swaps_since_step_;
    teleport_swaps_since_step_ = 0;
    // Keep each moved object once, and only if it moves at all.
    std::size_t w = 0;
    for (uint32_t id : moving_) {
        Record& r = records_[id];
        if (r.state != State::Live || !r.moving) continue;
        r.moving = false;
        if (!same_box(r.box, r.box_end)) moving_[w++] = id;
    }
    moving_.resize(w);
    counters_.moving_objects = w;

    pairs_.clear();
    on_step();
    for (uint32_t id : moving_) records_[id].box = records_[id].box_end;
    moving_.clear();

    sort_pairs(pairs_, sort_scratch_);
    // A pair reported more than once (an overlap that ends and starts again within the step, or
    // a pair met in several regions): keep its earliest time.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        if (kept > 0 && pairs_[kept - 1].a == pairs_[i].a && pairs_[kept - 1].b == pairs_[i].b) {
            // Written so that a NaN time never replaces a number (there is none: times come from
            // first_overlap_time or are 0 or +infinity).
            if (pairs_[i].t_first < pairs_[kept - 1].t_first) pairs_[kept - 1].t_first = pairs_[i].t_first;
            continue;
        }
        pairs_[kept++] = pairs_[i];
    }
    pairs_.resize(kept);
    counters_.pairs = pairs_.size();
    for (const BroadPhasePair& p : pairs_) counters_.false_positives += std::isinf(p.t_first) ? 1 : 0;
    return pairs_;
}

void BroadPhase::collect_present(std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t id = 0; id < records_.size(); ++id) {
        if (records_[id].state == State::Live || records_[id].state == State::PendingRemove) out.push_back(id);
    }
}

std::string BroadPhase::check_invariants() const {
    std::size_t live = 0;
    for (uint32_t id = 0; id < records_.size(); ++id) {
        const Record& r = records_[id];
        if (r.state == State::Live || r.state == State::PendingAdd) {
            ++live;
            if (!valid_box(r.box) || !valid_box(r.box_end))
                return "object " + std::to_string(id) + " has an invalid box";
            if (r.is_static && !same_box(r.box, r.box_end)) return "static object " + std::to_string(id) + " moves";
        }
    }
    if (live != live_count_)
        return "live count " + std::to_string(live_count_) + ", records say " + std::to_string(live);
    return {};
}

}  // namespace kairos
