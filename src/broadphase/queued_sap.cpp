// SPDX-License-Identifier: MIT
// The talks' space-time sweep and prune (SpacetimeSapQueued): every adjacent swap of the endpoint
// arrays is an event in an indexed heap, and the events are done in time order.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "broadphase/endpoint_sap.hpp"
#include "broadphase/factories.hpp"

namespace kairos {

namespace {

using broadphase_detail::EndpointSap;

// Binary min-heap of event slots with decrease- and increase-key: pos_ maps a slot to its place
// in the heap. Keys are (time, rank, slot), a total order, so the order in which events are
// taken does not depend on the order in which they were queued. Keys sit in the heap entries
// themselves, so a sift reads contiguous memory.
class EventHeap {
public:
    static constexpr uint32_t kNone = ~uint32_t{0};

    // Only while empty.
    void resize_slots(std::size_t n) {
        pos_.assign(n, kNone);
        heap_.reserve(n);
    }

    bool empty() const { return heap_.empty(); }
    bool queued(uint32_t slot) const { return pos_[slot] != kNone; }
    // Only for a queued slot.
    double time(uint32_t slot) const { return heap_[pos_[slot]].t; }
    uint32_t rank(uint32_t slot) const { return heap_[pos_[slot]].rank; }

    void push(uint32_t slot, double t, uint32_t rank) {
        heap_.push_back({t, slot, rank});
        sift_up(static_cast<uint32_t>(heap_.size() - 1));
    }

    void change(uint32_t slot, double t, uint32_t rank) {
        const uint32_t i = pos_[slot];
        const Entry e{t, slot, rank};
        const bool earlier = less(e, heap_[i]);
        heap_[i] = e;
        if (earlier) {
            sift_up(i);
        } else {
            sift_down(i);
        }
    }

    void remove(uint32_t slot) {
        const uint32_t i = pos_[slot];
        pos_[slot] = kNone;
        const Entry last = heap_.back();
        heap_.pop_back();
        if (last.slot == slot) return;
        heap_[i] = last;
        pos_[last.slot] = i;
        sift_up(i);
        sift_down(pos_[last.slot]);
    }

    // Only while not empty.
    uint32_t top() const { return heap_.front().slot; }

    // The earliest event: its slot and time. Floyd's variant: the hole at the top goes down to a
    // leaf along the smaller children (one comparison per level), then the last entry fills it
    // and rises, usually by a level or two.
    uint32_t pop(double* out_t) {
        const Entry top = heap_.front();
        *out_t = top.t;
        pos_[top.slot] = kNone;
        const Entry last = heap_.back();
        heap_.pop_back();
        const auto n = static_cast<uint32_t>(heap_.size());
        if (n == 0) return top.slot;
        uint32_t i = 0;
        for (uint32_t child = 1; child < n; child = 2 * i + 1) {
            if (child + 1 < n) child += less(heap_[child + 1], heap_[child]) ? 1 : 0;
            place(i, heap_[child]);
            i = child;
        }
        heap_[i] = last;
        sift_up(i);
        return top.slot;
    }

private:
    struct Entry {
        double t;
        uint32_t slot;
        uint32_t rank;
    };

    static bool less(const Entry& a, const Entry& b) {
        if (a.t != b.t) return a.t < b.t;
        if (a.rank != b.rank) return a.rank < b.rank;
        return a.slot < b.slot;
    }

    void place(uint32_t i, const Entry& e) {
        heap_[i] = e;
        pos_[e.slot] = i;
    }

    void sift_up(uint32_t i) {
        const Entry e = heap_[i];
        while (i > 0) {
            const uint32_t parent = (i - 1) / 2;
            if (!less(e, heap_[parent])) break;
            place(i, heap_[parent]);
            i = parent;
        }
        place(i, e);
    }

    void sift_down(uint32_t i) {
        const Entry e = heap_[i];
        const auto n = static_cast<uint32_t>(heap_.size());
        for (;;) {
            uint32_t child = 2 * i + 1;
            if (child >= n) break;
            if (child + 1 < n && less(heap_[child + 1], heap_[child])) ++child;
            if (!less(heap_[child], e)) break;
            place(i, heap_[child]);
            i = child;
        }
        place(i, e);
    }

    std::vector<Entry> heap_;
    std::vector<uint32_t> pos_;
};

// Event ranks at equal times: overlaps start before same-kind swaps, which come before overlaps
// end, so that boxes touching on all axes for one instant are seen overlapping at that instant.
constexpr uint32_t kRankStart = 0;
constexpr uint32_t kRankSame = 1;
constexpr uint32_t kRankEnd = 2;

// The talks' sweep: every adjacent swap is an event in an indexed heap, taken in time order, and
// a pair is reported when a swap makes it overlap on all three axes.
class QueuedSpacetimeSap final : public EndpointSap {
public:
    QueuedSpacetimeSap() : EndpointSap(BroadPhaseKind::SpacetimeSapQueued) {}
    std::string check_invariants() const override;

private:
    void on_flush() override;
    void on_step() override;
    void update_slot(int axis, uint32_t i, double t_now);
    EventHeap heap_;
};

void QueuedSpacetimeSap::on_flush() {
    EndpointSap::on_flush();
    // Slot of the adjacent endpoints at i and i + 1 of an axis: 4 * i + axis.
    heap_.resize_slots(4 * axes_[0].size());
}

// (Re)computes the event of the adjacent endpoints at i and i + 1 of an axis, at time t_now.
void QueuedSpacetimeSap::update_slot(int axis, uint32_t i, double t_now) {
    const auto& arr = axes_[static_cast<std::size_t>(axis)];
    if (i + 1 >= arr.size()) return;
    const uint32_t slot = 4 * i + static_cast<uint32_t>(axis);
    const Endpoint& l = arr[i];
    const Endpoint& r = arr[i + 1];
    const bool start = is_max(l) && !is_max(r);
    const double d1 = r.p1 - l.p1;
    // "][" must swap once the positions are equal ("[" sorts first); any other pair only once
    // the right one is strictly left of the left one. The comparisons are false for NaN.
    const bool swaps = start ? d1 <= 0 : d1 < 0;
    if (!swaps) {
        if (heap_.queued(slot)) {
            heap_.remove(slot);
            ++counters_.heap_removes;
        }
        return;
    }
    const double d0 = r.p0 - l.p0;
    // d0 > 0 >= d1 gives d0 - d1 >= d0 > 0 after rounding, so t lies in (0, 1]. An order that
    // rounding left inconsistent (d0 <= 0) swaps at once; never before the current time.
    double t = d0 > 0 ? d0 / (d0 - d1) : t_now;
    t = std::max(t, t_now);
    const uint32_t rank = start ? kRankStart : (is_max(l) == is_max(r) ? kRankSame : kRankEnd);
    if (heap_.queued(slot)) {
        if (heap_.time(slot) != t || heap_.rank(slot) != rank) {
            heap_.change(slot, t, rank);
            ++counters_.heap_updates;
        }
    } else {
        heap_.push(slot, t, rank);
        ++counters_.heap_pushes;
    }
}

void QueuedSpacetimeSap::on_step() {
    overlaps_.for_each([&](uint64_t k) {
        pairs_.push_back({static_cast<uint32_t>(k >> 32), static_cast<uint32_t>(k), 0.0});
    });
    if (moving_.empty()) return;

    for (uint32_t id : moving_) {
        const Aabb& e = records_[id].box_end;
        for (int axis = 0; axis < 3; ++axis) {
            auto& arr = axes_[static_cast<std::size_t>(axis)];
            arr[ep(id, axis, false)].p1 = e.min[axis];
            arr[ep(id, axis, true)].p1 = e.max[axis];
        }
    }
    // Only slots next to a moving endpoint can hold an event: static objects cost nothing here.
    // When at least half of the objects move, one pass along each array reads memory in order
    // instead (the statics' slots cost a comparison each, then).
    if (4 * moving_.size() >= axes_[0].size()) {
        for (int axis = 0; axis < 3; ++axis) {
            const auto n = static_cast<uint32_t>(axes_[static_cast<std::size_t>(axis)].size());
            for (uint32_t i = 0; i + 1 < n; ++i) update_slot(axis, i, 0.0);
        }
    } else {
        for (uint32_t id : moving_) {
            for (int axis = 0; axis < 3; ++axis) {
                for (bool mx : {false, true}) {
                    const uint32_t i = ep(id, axis, mx);
                    if (i > 0) update_slot(axis, i - 1, 0.0);
                    update_slot(axis, i, 0.0);
                }
            }
        }
    }
    while (!heap_.empty()) {
        double t = 0;
        const uint32_t slot = heap_.pop(&t);
        ++counters_.heap_pops;
        // The next event is known now: start loading its endpoints while this one is done.
        if (!heap_.empty()) {
            const uint32_t next = heap_.top();
            __builtin_prefetch(&axes_[next & 3][next >> 2]);
        }
        const int axis = static_cast<int>(slot & 3);
        const uint32_t i = slot >> 2;
        swap_at(axis, i, t, true);
        ++counters_.swaps;
        if (i > 0) update_slot(axis, i - 1, t);
        update_slot(axis, i, t);
        update_slot(axis, i + 1, t);
    }
    for (uint32_t id : moving_) {
        for (int axis = 0; axis < 3; ++axis) {
            auto& arr = axes_[static_cast<std::size_t>(axis)];
            for (bool mx : {false, true}) {
                Endpoint& e = arr[ep(id, axis, mx)];
                e.p0 = e.p1;
            }
        }
        set_spans(id, records_[id].box_end, records_[id].box_end);
    }
}

std::string QueuedSpacetimeSap::check_invariants() const {
    if (!heap_.empty()) return "event heap not empty between steps";
    return EndpointSap::check_invariants();
}

}  // namespace

namespace broadphase_detail {

std::unique_ptr<BroadPhase> make_queued_sap() { return std::make_unique<QueuedSpacetimeSap>(); }

}  // namespace broadphase_detail

}  // namespace kairos
