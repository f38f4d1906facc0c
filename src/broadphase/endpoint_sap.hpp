// SPDX-License-Identifier: MIT
// Sorted endpoint arrays per axis (EndpointSap), the base of the global and the queued space-time
// sweeps. Internal to broadphase/ (namespace broadphase_detail).
//
// Source: the talks' space-time sweep and prune (docs/algorithms.md §5). Per axis a sorted array of
// endpoints; over the step every endpoint moves linearly from p0 (t = 0) to p1 (t = 1). Two
// adjacent endpoints L < R swap at the root of d(t) = (1 - t) d0 + t d1 with d0 = R.p0 - L.p0 and
// d1 = R.p1 - L.p1, that is t = d0 / (d0 - d1). Whether they swap at all depends only on the sign
// of d1, so the arrays end the step in exactly the order of the end positions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "broadphase/pair_set.hpp"

namespace kairos::broadphase_detail {

// Sorted endpoint arrays per axis, shared by both space-time sweeps: bulk insertion, removal,
// teleports by local swaps, and the set of pairs overlapping now. Subclasses sweep the step.
class EndpointSap : public BroadPhase {
public:
    std::string check_invariants() const override;

protected:
    explicit EndpointSap(BroadPhaseKind kind) : BroadPhase(kind) {}

    // One interval endpoint: its coordinate at the start and at the end of the step (equal between
    // steps) and tag = owner id << 2 | 2 if the owner is static | 1 for a max ("]"), 0 for a min
    // ("["), so that a swap reads nothing else to know what it changes.
    // span: the owner's interval on the two other axes (axis + 1, axis + 2: lo, hi, lo, hi) over
    // the step, rounded outward to float: a quick, conservative filter for a crossing's pair.
    struct Endpoint {
        double p0;
        double p1;
        uint32_t tag;
        float span[4];
    };
    static uint32_t owner(const Endpoint& e) { return e.tag >> 2; }
    static bool is_max(const Endpoint& e) { return (e.tag & 1) != 0; }
    static bool is_static(const Endpoint& e) { return (e.tag & 2) != 0; }
    // The order between steps: by position, then "[" before "]", so touching intervals overlap.
    static bool before(const Endpoint& a, const Endpoint& b) {
        return a.p0 < b.p0 || (a.p0 == b.p0 && (a.tag & 1) < (b.tag & 1));
    }
    // Sort key for bulk insertion. The talks put the "]" flag in the least significant bit of the
    // key; a double needs all 64 bits to keep every position apart, so the flag is the bit right
    // after them (a 65-bit key), and the owner orders equal keys deterministically.
    struct SortItem {
        uint64_t key;
        uint32_t flag_owner;  // is_max << 31 | owner
        bool operator<(const SortItem& o) const { return key != o.key ? key < o.key : flag_owner < o.flag_owner; }
    };

    void on_flush() override;
    void on_teleport(uint32_t id, const Aabb& old_box) override;
    // Rewrites the owner's tags and its pairs with static objects: O(n) (a scan of the others).
    void on_static_change(uint32_t id) override;
    // The min endpoints on x within the longest extent before the query box, by binary search.
    void on_query_box(const Aabb& q, std::vector<uint32_t>& out) const override;

    uint32_t& ep(uint32_t id, int axis, bool max) {
        return ep_[id][2 * static_cast<std::size_t>(axis) + (max ? 1u : 0u)];
    }
    uint32_t ep(uint32_t id, int axis, bool max) const {
        return ep_[id][2 * static_cast<std::size_t>(axis) + (max ? 1u : 0u)];
    }
    bool overlap_on_axis(uint32_t a, uint32_t b, int axis) const {
        return ep(a, axis, false) < ep(b, axis, true) && ep(b, axis, false) < ep(a, axis, true);
    }
    bool overlap_on_other_axes(uint32_t a, uint32_t b, int axis) const {
        return overlap_on_axis(a, b, (axis + 1) % 3) && overlap_on_axis(a, b, (axis + 2) % 3);
    }
    bool both_static(uint32_t a, uint32_t b) const { return records_[a].is_static && records_[b].is_static; }

    void swap_at(int axis, uint32_t i, double t, bool report);
    void bubble(int axis, uint32_t idx);
    // Sets the spans of an object's six endpoints to the union of boxes a and b, and with
    // set_end their end positions to b's (one pass over the six).
    void set_spans(uint32_t id, const Aabb& a, const Aabb& b, bool set_end = false);
    static bool spans_meet(const Endpoint& x, const Endpoint& y) {
        return !(x.span[0] > y.span[1] || y.span[0] > x.span[1] || x.span[2] > y.span[3] || y.span[2] > x.span[3]);
    }
    void rebuild_indices(int axis, std::size_t from, std::size_t to);

    std::array<std::vector<Endpoint>, 3> axes_;
    std::vector<std::array<uint32_t, 6>> ep_;  // by id: index of [min, max] on x, y, z
    PairSet overlaps_;                         // pairs overlapping now, not both static
    // Scratch buffers kept between flushes.
    std::vector<SortItem> sort_items_;
    std::vector<Endpoint> merged_;
    std::vector<uint64_t> doomed_;
    std::vector<uint32_t> active_all_, active_new_, active_pos_;
};

}  // namespace kairos::broadphase_detail
