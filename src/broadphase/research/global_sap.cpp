// SPDX-License-Identifier: MIT
// The space-time sweep in one batch per axis (SpacetimeSapGlobal, class GlobalSpacetimeSap): each axis
// brought from its start order to its end order by adjacent swaps, crossings tested exactly.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "broadphase/box_time.hpp"
#include "broadphase/endpoint_sap.hpp"
#include "broadphase/factories.hpp"
#include "broadphase/pair_set.hpp"

namespace kairos {

namespace {

using broadphase_detail::EndpointSap;

// ---- Space-time sweep in one batch per axis ---------------------------------------------------
//
// Over the step every endpoint moves linearly, so two endpoints cross at most once, and they cross
// exactly when their order at the end differs from their order at the start. Bringing an axis
// from the start order to the end order by adjacent swaps performs exactly those crossings, each
// once: the same swaps as the queued sweep, done in array order instead of time order, with no
// heap and with memory read in sequence. A pair can first overlap at t > 0 only right after a
// crossing "]a [b" -> "[b ]a" on some axis (the one whose overlap starts last); each such
// crossing's pair gets first_overlap_time, the exact 4D test brute force runs, so pairs and times
// equal brute force exactly. Pairs overlapping at t = 0 are the overlap set kept between steps.
class GlobalSpacetimeSap final : public EndpointSap {
public:
    GlobalSpacetimeSap() : EndpointSap(BroadPhaseKind::SpacetimeSapGlobal) {}

private:
    // The end order: by end position, then "[" before "]".
    static bool end_before(const Endpoint& a, const Endpoint& b) {
        return a.p1 < b.p1 || (a.p1 == b.p1 && (a.tag & 1) < (b.tag & 1));
    }
    void on_step() override;
    void crossing(const Endpoint& max_a, const Endpoint& min_b);
    void sort_axis(int axis);
    void bubble_moving(int axis);

    std::vector<uint64_t> entered_;  // pairs found by crossings that overlap at the end
    std::vector<uint32_t> movers_;   // scratch: array indices of moving endpoints
};

// "]a" and "[b" swapped, and their spans meet: a and b may start to overlap on this axis during
// the step. (The sweeps test the spans first, inline: most crossings end there.)
void GlobalSpacetimeSap::crossing(const Endpoint& max_a, const Endpoint& min_b) {
    test_swept_pair(owner(max_a), owner(min_b), entered_);
}

// Insertion sort of a whole axis by end position: each endpoint that ends before its left
// neighbour moves left past every endpoint it crosses. O(n + swaps), sequential memory.
void GlobalSpacetimeSap::sort_axis(int axis) {
    auto& arr = axes_[static_cast<std::size_t>(axis)];
    const std::size_t n = arr.size();
    std::size_t lo = n, hi = 0;
    uint64_t swaps = 0;
    for (std::size_t i = 1; i < n; ++i) {
        if (!end_before(arr[i], arr[i - 1])) continue;
        const Endpoint e = arr[i];
        const bool e_is_min = !is_max(e);
        std::size_t j = i;
        do {
            const Endpoint& f = arr[j - 1];
            if (e_is_min && is_max(f) && spans_meet(f, e)) crossing(f, e);
            arr[j] = f;
            --j;
        } while (j > 0 && end_before(e, arr[j - 1]));
        arr[j] = e;
        swaps += i - j;
        lo = std::min(lo, j);
        hi = i + 1;
    }
    if (lo < hi) rebuild_indices(axis, lo, hi);
    counters_.swaps += swaps;
}

// Only the moving endpoints, each bubbled to its place in turn, so statics cost nothing. First
// those moving right, rightmost first; then those moving left, leftmost first. An endpoint then
// only ever meets endpoints whose key is final (or, moving right, left movers still at their
// start, which it truly crosses), so every swap is a true crossing and none is undone later: the
// swaps are exactly those of the insertion sort. Each endpoint is compared by its current key:
// max(p0, p1) in the first pass, p1 in the second.
void GlobalSpacetimeSap::bubble_moving(int axis) {
    auto& arr = axes_[static_cast<std::size_t>(axis)];
    const auto n = static_cast<uint32_t>(arr.size());
    uint64_t swaps = 0;
    for (int pass = 0; pass < 2; ++pass) {
        movers_.clear();
        for (uint32_t id : moving_) {
            for (bool mx : {false, true}) {
                const uint32_t i = ep(id, axis, mx);
                const Endpoint& e = arr[i];
                if (pass == 0 ? e.p1 > e.p0 : e.p1 < e.p0) movers_.push_back(i);
            }
        }
        if (pass == 0) {
            std::sort(movers_.begin(), movers_.end(), std::greater<uint32_t>());
            for (uint32_t i0 : movers_) {
                const Endpoint e = arr[i0];
                uint32_t i = i0;
                while (i + 1 < n) {
                    const Endpoint& f = arr[i + 1];
                    const double fk = std::max(f.p0, f.p1);
                    if (!(fk < e.p1 || (fk == e.p1 && (f.tag & 1) < (e.tag & 1)))) break;
                    if (is_max(e) && !is_max(f) && spans_meet(e, f)) crossing(e, f);
                    arr[i] = f;
                    ep(owner(f), axis, is_max(f)) = i;
                    ++i;
                }
                arr[i] = e;
                ep(owner(e), axis, is_max(e)) = i;
                swaps += i - i0;
            }
        } else {
            std::sort(movers_.begin(), movers_.end());
            for (uint32_t i0 : movers_) {
                const Endpoint e = arr[i0];
                uint32_t i = i0;
                while (i > 0 && end_before(e, arr[i - 1])) {
                    const Endpoint& f = arr[i - 1];
                    if (is_max(f) && !is_max(e) && spans_meet(f, e)) crossing(f, e);
                    arr[i] = f;
                    ep(owner(f), axis, is_max(f)) = i;
                    --i;
                }
                arr[i] = e;
                ep(owner(e), axis, is_max(e)) = i;
                swaps += i0 - i;
            }
        }
    }
    counters_.swaps += swaps;
}

void GlobalSpacetimeSap::on_step() {
    // Pairs overlapping at the start; those apart at the end leave the set afterwards.
    doomed_.clear();
    entered_.clear();
    overlaps_.for_each([&](uint64_t k) {
        const auto a = static_cast<uint32_t>(k >> 32), b = static_cast<uint32_t>(k);
        pairs_.push_back({a, b, 0.0});
        if (!boxes_overlap(records_[a].box_end, records_[b].box_end)) doomed_.push_back(k);
    });
    if (moving_.empty()) return;

    for (uint32_t id : moving_) set_spans(id, records_[id].box, records_[id].box_end, true);
    // When many objects move, one insertion sort per axis reads memory in order (statics cost a
    // comparison each); otherwise only the moving endpoints are touched.
    const bool whole = 8 * moving_.size() >= axes_[0].size();
    for (int axis = 0; axis < 3; ++axis) {
        if (whole) {
            sort_axis(axis);
        } else {
            bubble_moving(axis);
        }
    }
    for (uint64_t k : doomed_) overlaps_.erase(k);
    for (uint64_t k : entered_) overlaps_.insert(k);
    // The end becomes the start. The spans stay: the step's union still holds the end box.
    if (whole) {
        for (auto& arr : axes_) {
            for (Endpoint& e : arr) e.p0 = e.p1;
        }
    } else {
        for (uint32_t id : moving_) {
            for (int axis = 0; axis < 3; ++axis) {
                auto& arr = axes_[static_cast<std::size_t>(axis)];
                arr[ep(id, axis, false)].p0 = arr[ep(id, axis, false)].p1;
                arr[ep(id, axis, true)].p0 = arr[ep(id, axis, true)].p1;
            }
        }
    }
}

}  // namespace

namespace broadphase_detail {

std::unique_ptr<BroadPhase> make_global_sap() { return std::make_unique<GlobalSpacetimeSap>(); }

}  // namespace broadphase_detail

}  // namespace kairos
