// SPDX-License-Identifier: MIT
// EndpointSap: bulk insertion and removal, teleports by adjacent swaps, the overlap set kept by
// the swaps, and the check of the arrays and the set against brute force.
#include "broadphase/endpoint_sap.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "broadphase/float_bounds.hpp"
#include "broadphase/overlap_check.hpp"

namespace kairos::broadphase_detail {

void EndpointSap::set_spans(uint32_t id, const Aabb& a, const Aabb& b, bool set_end) {
    float lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
        lo[k] = float_below(std::min(a.min[k], b.min[k]));
        hi[k] = float_above(std::max(a.max[k], b.max[k]));
    }
    for (int axis = 0; axis < 3; ++axis) {
        const int j1 = (axis + 1) % 3, j2 = (axis + 2) % 3;
        auto& arr = axes_[static_cast<std::size_t>(axis)];
        for (bool mx : {false, true}) {
            Endpoint& e = arr[ep(id, axis, mx)];
            if (set_end) e.p1 = mx ? b.max[axis] : b.min[axis];
            e.span[0] = lo[j1];
            e.span[1] = hi[j1];
            e.span[2] = lo[j2];
            e.span[3] = hi[j2];
        }
    }
}

void EndpointSap::rebuild_indices(int axis, std::size_t from, std::size_t to) {
    auto& arr = axes_[static_cast<std::size_t>(axis)];
    for (std::size_t i = from; i < to; ++i) ep(owner(arr[i]), axis, is_max(arr[i])) = static_cast<uint32_t>(i);
}

void EndpointSap::on_flush() {
    if (ep_.size() < records_.size()) ep_.resize(records_.size());

    if (!pending_removes_.empty()) {
        auto removed = [&](uint32_t id) { return records_[id].state == State::PendingRemove; };
        overlaps_.erase_pairs_of(removed, doomed_);
        for (int axis = 0; axis < 3; ++axis) {
            auto& arr = axes_[static_cast<std::size_t>(axis)];
            std::size_t w = 0;
            for (std::size_t r = 0; r < arr.size(); ++r) {
                if (removed(owner(arr[r]))) continue;
                arr[w] = arr[r];
                ep(owner(arr[w]), axis, is_max(arr[w])) = static_cast<uint32_t>(w);
                ++w;
            }
            arr.resize(w);
        }
    }

    if (!pending_adds_.empty()) {
        // Bulk insertion: sort the new endpoints, then merge them into each axis in one pass.
        for (int axis = 0; axis < 3; ++axis) {
            sort_items_.clear();
            for (uint32_t id : pending_adds_) {
                const Aabb& b = records_[id].box;
                sort_items_.push_back({ordered_key(b.min[axis]), id});
                sort_items_.push_back({ordered_key(b.max[axis]), id | (1u << 31)});
            }
            std::sort(sort_items_.begin(), sort_items_.end());
            auto& arr = axes_[static_cast<std::size_t>(axis)];
            merged_.clear();
            merged_.reserve(arr.size() + sort_items_.size());
            std::size_t r = 0;
            for (const SortItem& s : sort_items_) {
                const uint32_t id = s.flag_owner & ~(1u << 31);
                const bool mx = (s.flag_owner >> 31) != 0;
                const Aabb& b = records_[id].box;
                const double p = mx ? b.max[axis] : b.min[axis];
                const Endpoint e{p, p, (id << 2) | (records_[id].is_static ? 2u : 0u) | (mx ? 1u : 0u), {}};
                while (r < arr.size() && !before(e, arr[r])) merged_.push_back(arr[r++]);
                merged_.push_back(e);
            }
            while (r < arr.size()) merged_.push_back(arr[r++]);
            arr.swap(merged_);
            rebuild_indices(axis, 0, arr.size());
        }
        for (uint32_t id : pending_adds_) set_spans(id, records_[id].box, records_[id].box);

        // New overlaps: one sweep along x with the objects whose x interval is open; a pair is
        // tested only if one of the two is new, by index on y and z.
        auto is_new = [&](uint32_t id) { return records_[id].state == State::PendingAdd; };
        if (active_pos_.size() < records_.size()) active_pos_.resize(records_.size());
        active_all_.clear();
        active_new_.clear();
        auto drop = [&](std::vector<uint32_t>& list, uint32_t id) {
            const uint32_t i = active_pos_[id];
            list[i] = list.back();
            active_pos_[list[i]] = i;
            list.pop_back();
        };
        for (const Endpoint& e : axes_[0]) {
            const uint32_t id = owner(e);
            const bool fresh = is_new(id);
            if (is_max(e)) {
                drop(fresh ? active_new_ : active_all_, id);
                continue;
            }
            for (uint32_t other : active_new_) {
                if (!both_static(id, other) && overlap_on_other_axes(id, other, 0))
                    overlaps_.insert(pair_key(id, other));
            }
            if (fresh) {
                for (uint32_t other : active_all_) {
                    if (!both_static(id, other) && overlap_on_other_axes(id, other, 0))
                        overlaps_.insert(pair_key(id, other));
                }
            }
            auto& list = fresh ? active_new_ : active_all_;
            active_pos_[id] = static_cast<uint32_t>(list.size());
            list.push_back(id);
        }
    }
}

// Swaps the endpoints at i and i + 1 of an axis and keeps the overlap set: "][" -> "[]" starts an
// overlap on this axis, "[]" -> "][" ends one; the pair changes only if the others overlap too.
void EndpointSap::swap_at(int axis, uint32_t i, double t, bool report) {
    auto& arr = axes_[static_cast<std::size_t>(axis)];
    const Endpoint left = arr[i];
    const Endpoint right = arr[i + 1];
    arr[i] = right;
    arr[i + 1] = left;
    const uint32_t a = owner(left), b = owner(right);
    ep(a, axis, is_max(left)) = i + 1;
    ep(b, axis, is_max(right)) = i;
    if (is_max(left) == is_max(right)) return;
    if ((is_static(left) && is_static(right)) || !overlap_on_other_axes(a, b, axis)) return;
    if (is_max(left)) {
        overlaps_.insert(pair_key(a, b));
        if (report) pairs_.push_back({std::min(a, b), std::max(a, b), t});
    } else {
        overlaps_.erase(pair_key(a, b));
    }
}

// Moves the endpoint at idx (already holding its new position) to its place by adjacent swaps.
void EndpointSap::bubble(int axis, uint32_t idx) {
    auto& arr = axes_[static_cast<std::size_t>(axis)];
    while (idx > 0 && before(arr[idx], arr[idx - 1])) {
        swap_at(axis, idx - 1, 0.0, false);
        ++teleport_swaps_since_step_;
        --idx;
    }
    while (idx + 1 < arr.size() && before(arr[idx + 1], arr[idx])) {
        swap_at(axis, idx, 0.0, false);
        ++teleport_swaps_since_step_;
        ++idx;
    }
}

void EndpointSap::on_teleport(uint32_t id, const Aabb& old_box) {
    const Aabb& b = records_[id].box;
    for (int axis = 0; axis < 3; ++axis) {
        auto& arr = axes_[static_cast<std::size_t>(axis)];
        // Move first the endpoint that cannot cross its partner on the way: the max if it grows.
        const bool max_first = b.max[axis] >= old_box.max[axis];
        for (bool mx : {max_first, !max_first}) {
            Endpoint& e = arr[ep(id, axis, mx)];
            e.p0 = e.p1 = mx ? b.max[axis] : b.min[axis];
            bubble(axis, ep(id, axis, mx));
        }
    }
    set_spans(id, b, b);
}

void EndpointSap::on_static_change(uint32_t id) {
    const bool now_static = records_[id].is_static;
    for (int axis = 0; axis < 3; ++axis) {
        for (bool mx : {false, true}) {
            Endpoint& e = axes_[static_cast<std::size_t>(axis)][ep(id, axis, mx)];
            e.tag = (e.tag & ~2u) | (now_static ? 2u : 0u);
        }
    }
    // Overlapping pairs with static objects leave the set (or join it) with the flag.
    for (uint32_t other = 0; other < records_.size(); ++other) {
        if (other == id || records_[other].state != State::Live || !records_[other].is_static) continue;
        if (!(overlap_on_axis(id, other, 0) && overlap_on_axis(id, other, 1) && overlap_on_axis(id, other, 2)))
            continue;
        if (now_static)
            overlaps_.erase(pair_key(id, other));
        else
            overlaps_.insert(pair_key(id, other));
    }
}

void EndpointSap::on_query_box(const Aabb& q, std::vector<uint32_t>& out) const {
    // Objects not flushed yet have no endpoints; pending_adds_ may name one twice.
    const std::size_t from = out.size();
    for (uint32_t id : pending_adds_)
        if (records_[id].state == State::PendingAdd && boxes_overlap(records_[id].box, q)) out.push_back(id);
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(from), out.end());
    out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(from), out.end()), out.end());
    // Between steps the x array is sorted by p0, each object's box there; every object has one min
    // endpoint, and one whose box reaches q starts at most max_extent_x_ before q (a few ulps lower
    // for the rounding of the subtraction).
    const auto& arr = axes_[0];
    double first = q.min.x - max_extent_x_;
    first -= (std::fabs(first) + max_extent_x_) * 0x1p-50;
    auto it = std::lower_bound(arr.begin(), arr.end(), first, [](const Endpoint& e, double x) { return e.p0 < x; });
    for (; it != arr.end() && !(it->p0 > q.max.x); ++it) {
        if (is_max(*it)) continue;
        const uint32_t id = owner(*it);
        if (records_[id].state == State::Live && boxes_overlap(records_[id].box, q)) out.push_back(id);
    }
}

std::string EndpointSap::check_invariants() const {
    std::string base = BroadPhase::check_invariants();
    if (!base.empty()) return base;
    std::ostringstream why;
    std::vector<uint32_t> present;
    collect_present(present);
    for (int axis = 0; axis < 3; ++axis) {
        const auto& arr = axes_[static_cast<std::size_t>(axis)];
        if (arr.size() != 2 * present.size()) {
            why << "axis " << axis << " holds " << arr.size() << " endpoints for " << present.size() << " objects";
            return why.str();
        }
        for (std::size_t i = 0; i < arr.size(); ++i) {
            const Endpoint& e = arr[i];
            const uint32_t id = owner(e);
            if (id >= records_.size() || records_[id].state == State::Absent ||
                records_[id].state == State::PendingAdd) {
                why << "axis " << axis << " index " << i << ": endpoint of absent object " << id;
                return why.str();
            }
            if (ep(id, axis, is_max(e)) != i) {
                why << "axis " << axis << " index " << i << ": object " << id << " says " << ep(id, axis, is_max(e));
                return why.str();
            }
            const Aabb& b = records_[id].box;
            const double want = is_max(e) ? b.max[axis] : b.min[axis];
            if (e.p0 != want || e.p1 != want) {
                why << "axis " << axis << " index " << i << ": endpoint at " << e.p0 << "/" << e.p1 << ", box says "
                    << want;
                return why.str();
            }
            const int j1 = (axis + 1) % 3, j2 = (axis + 2) % 3;
            if (!(e.span[0] <= b.min[j1] && e.span[1] >= b.max[j1] && e.span[2] <= b.min[j2] &&
                  e.span[3] >= b.max[j2])) {
                why << "axis " << axis << " index " << i << ": span of object " << id << " does not hold its box";
                return why.str();
            }
            if (i > 0 && before(e, arr[i - 1])) {
                why << "axis " << axis << " not sorted at index " << i;
                return why.str();
            }
        }
    }
    return check_overlap_set(present, records_, overlaps_, [&](uint32_t a, uint32_t b, bool by_box, std::ostream& out) {
        const bool by_index = overlap_on_axis(a, b, 0) && overlap_on_axis(a, b, 1) && overlap_on_axis(a, b, 2);
        if (by_box != by_index)
            out << "pair " << a << "," << b << ": boxes overlap " << by_box << ", indices say " << by_index;
        return by_box == by_index;
    });
}

}  // namespace kairos::broadphase_detail
