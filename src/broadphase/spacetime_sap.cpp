// SPDX-License-Identifier: MIT
// SpacetimeSap's flush, teleport and step: objects entered and removed, the overlap set kept between
// steps, the sweep of the columns the moving objects touch; and the check of the structure.
#include "broadphase/spacetime_sap.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "broadphase/box_time.hpp"
#include "broadphase/factories.hpp"
#include "broadphase/overlap_check.hpp"
#include "broadphase/pair_set.hpp"

namespace kairos::broadphase_detail {

template <class Wanted, class F>
void SpacetimeSap::sweep_column(const std::vector<Entry>& entries, Wanted&& wanted, F&& f) {
    // The active list holds copies of the entries whose x interval is still open, compacted as
    // it is read; the tests are written without branches but for the rare pair that meets.
    std::size_t n = 0;  // active entries: active_[0, n); the vector only grows
    for (const Entry& e : entries) {
        std::size_t w = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const Active a = active_[i];
            const bool open = !(a.hi < e.lo);  // once closed, closed for good: the lows only grow
            active_[w] = a;
            w += open ? 1 : 0;
            const bool meet = open & !(a.span[0] > e.span[1]) & !(e.span[0] > a.span[1]) & !(a.span[2] > e.span[3]) &
                              !(e.span[2] > a.span[3]);
            if (meet && wanted(a.id, e.id)) f(a.id, e.id);
        }
        n = w;
        const Active next{e.hi, {e.span[0], e.span[1], e.span[2], e.span[3]}, e.id};
        if (n == active_.size()) {
            active_.push_back(next);
        } else {
            active_[n] = next;
        }
        ++n;
    }
}

void SpacetimeSap::on_flush() {
    if (members_.size() < records_.size()) {
        members_.resize(records_.size());
        moving_flag_.resize(records_.size(), 0);
        stale_flag_.resize(records_.size(), 0);
        pending_.resize(records_.size(), 0);
        leaving_.resize(records_.size(), 0);
        entry_.resize(records_.size());
    }
    if (!pending_removes_.empty()) {
        auto removed = [&](uint32_t id) { return records_[id].state == State::PendingRemove; };
        overlaps_.erase_pairs_of(removed, doomed_);
        for (uint32_t id : pending_removes_) unlist(id);
        std::erase_if(stale_, removed);
        for (uint32_t id : pending_removes_) stale_flag_[id] = 0;
    }
    if (pending_adds_.empty()) return;
    if (cell_size_ == 0) {
        // Columns about four typical objects wide.
        extents_.clear();
        for (uint32_t id : pending_adds_) {
            const Aabb& b = records_[id].box;
            extents_.push_back(std::max(b.max.y - b.min.y, b.max.z - b.min.z));
        }
        std::nth_element(extents_.begin(), extents_.begin() + static_cast<std::ptrdiff_t>(extents_.size() / 2),
                         extents_.end());
        const double median = extents_[extents_.size() / 2];
        cell_size_ = std::isfinite(median) && median > 0 ? 4 * median : 1.0;
        inverse_cell_ = 1 / cell_size_;
        if (!(inverse_cell_ > 0 && std::isfinite(inverse_cell_))) cell_size_ = inverse_cell_ = 1.0;
    }
    // Enter the new objects (appended, then each touched column sorted once), then find their
    // overlaps by sweeping those columns.
    ++pass_;
    queued_.clear();
    auto is_new = [&](uint32_t id) { return records_[id].state == State::PendingAdd; };
    for (uint32_t id : pending_adds_) {
        const Aabb& k = records_[id].box;
        place(id, k);
        if (members_[id].large) {
            large_.insert(std::lower_bound(large_.begin(), large_.end(), id), id);
            continue;
        }
        const Entry e = entry_[id];
        const bool is_static = members_[id].in_statics;
        for_columns(id, [&](uint32_t c) {
            list_of(columns_[c], is_static).push_back(e);
            double& longest = max_len_of(columns_[c], is_static);
            longest = std::max(longest, e.hi - e.lo);
            queue(c);
        });
    }
    auto found = [&](uint32_t a, uint32_t b) {
        if (boxes_overlap(records_[a].box, records_[b].box)) overlaps_.insert(pair_key(a, b));
    };
    for (uint32_t c : queued_) {
        Column& col = columns_[c];
        std::sort(col.entries.begin(), col.entries.end(), entry_less);
        std::sort(col.statics.begin(), col.statics.end(), entry_less);
        // Both kinds in one sweep (additions are rare: the merge is not worth avoiding).
        const std::vector<Entry>* all = &col.entries;
        if (!col.statics.empty()) {
            merged_.clear();
            std::merge(col.entries.begin(), col.entries.end(), col.statics.begin(), col.statics.end(),
                       std::back_inserter(merged_), entry_less);
            all = &merged_;
        }
        sweep_column(
            *all, [&](uint32_t a, uint32_t b) { return (is_new(a) || is_new(b)) && !both_static(a, b); }, found);
    }
    queued_.clear();
    // Large new objects against everything present; large old ones against the new.
    for (uint32_t l : large_) {
        for (uint32_t id = 0; id < members_.size(); ++id) {
            if (id == l || !members_[id].listed || !(is_new(l) || is_new(id)) || both_static(l, id)) continue;
            if (members_[id].large && id < l) continue;  // that pair comes from id's turn
            found(l, id);
        }
    }
}

void SpacetimeSap::on_teleport(uint32_t id, const Aabb& old_box) {
    // Drop its pairs: partners share one of its columns (or it is large: all of them), and their
    // boxes overlapped its old box. A column entry's keyed box holds its object's box, so an
    // entry whose keyed box misses the box (the entry's own data: no lookup) has no pair with it.
    Member& m = members_[id];
    auto drop = [&](uint32_t other) {
        if (other != id) overlaps_.erase(pair_key(id, other));
    };
    auto entry_meets = [](const Entry& e, const Aabb& q) {
        return !(e.lo > q.max.x || e.hi < q.min.x || e.span[0] > q.max.y || e.span[1] < q.min.y ||
                 e.span[2] > q.max.z || e.span[3] < q.min.z);
    };
    if (m.large) {
        for (uint32_t other = 0; other < members_.size(); ++other) {
            if (members_[other].listed) drop(other);
        }
    } else {
        for_columns(id, [&](uint32_t c) { for_entries_near(columns_[c], old_box, [&](const Entry& e) {
            if (entry_meets(e, old_box)) drop(e.id);
        }); });
        for (uint32_t l : large_) drop(l);
    }
    unlist(id);
    const Aabb& b = records_[id].box;
    list(id, b);
    stale_flag_[id] = 0;  // keyed by its box now (it may stay listed in stale_)
    auto add = [&](uint32_t other) {
        if (other != id && members_[other].listed && !both_static(id, other) && boxes_overlap(b, records_[other].box))
            overlaps_.insert(pair_key(id, other));
    };
    if (m.large) {
        for (uint32_t other = 0; other < members_.size(); ++other) add(other);
    } else {
        for_columns(id, [&](uint32_t c) { for_entries_near(columns_[c], b, [&](const Entry& e) {
            if (entry_meets(e, b)) add(e.id);
        }); });
        for (uint32_t l : large_) add(l);
    }
}

void SpacetimeSap::on_step() {
    for (uint32_t id : moving_) moving_flag_[id] = 1;
    // Pairs overlapping at the start: those of two still objects keep their state; those with a
    // moving object are tested again by the sweeps below.
    doomed_.clear();
    entered_.clear();
    kept_.clear();
    overlaps_.for_each([&](uint64_t k) {
        const auto a = static_cast<uint32_t>(k >> 32), b = static_cast<uint32_t>(k);
        if (moving_flag_[a] || moving_flag_[b]) {
            doomed_.push_back(k);
        } else {
            pairs_.push_back({a, b, 0.0});
            kept_.push_back(k);
        }
    });
    if (2 * doomed_.size() > overlaps_.size()) {
        overlaps_.clear();  // most pairs move: rebuilding is cheaper than erasing
        for (uint64_t k : kept_) overlaps_.insert(k);
    } else {
        for (uint64_t k : doomed_) overlaps_.erase(k);
    }

    // Re-key the moving objects by their swept boxes, and the objects swept last step by their
    // boxes; only their columns are swept.
    ++pass_;
    queued_.clear();
    rekeys_.clear();
    for (uint32_t id : stale_) {
        if (stale_flag_[id] && !moving_flag_[id] && records_[id].state == State::Live) rekeys_.push_back(id);
        stale_flag_[id] = 0;
    }
    rekeys_.insert(rekeys_.end(), moving_.begin(), moving_.end());
    stale_.assign(moving_.begin(), moving_.end());
    for (uint32_t id : stale_) stale_flag_[id] = 1;
    rekey_all();
    // Per column: a full sweep when many of its entries move; otherwise each moving entry looks
    // up its neighbours along x (entries starting within the column's longest entry before it),
    // so still entries cost nothing but a binary search.
    // The moving entries of each column, grouped by a counting sort over the queued columns.
    for (uint32_t c : queued_) columns_[c].movers = 0;
    std::size_t memberships = 0;
    for (uint32_t id : moving_) {
        if (members_[id].large) continue;
        for_columns(id, [&](uint32_t c) { ++columns_[c].movers; });
    }
    for (uint32_t c : queued_) {
        columns_[c].first_mover = static_cast<uint32_t>(memberships);
        memberships += columns_[c].movers;
        columns_[c].movers = 0;
    }
    column_movers_.resize(memberships);
    for (uint32_t id : moving_) {
        if (members_[id].large) continue;
        for_columns(id, [&](uint32_t c) { column_movers_[columns_[c].first_mover + columns_[c].movers++] = id; });
    }
    candidates_.clear();
    auto wanted = [&](uint32_t a, uint32_t b) { return moving_flag_[a] || moving_flag_[b]; };
    auto collect = [&](uint32_t a, uint32_t b) { candidates_.push_back({a, b}); };
    for (uint32_t c : queued_) {
        Column& col = columns_[c];
        if (col.movers == 0) continue;
        // Moving entries against the others that are not static: one sweep when many move, else a
        // search each; against the static ones always a search each.
        const bool sweep = 8 * std::size_t{col.movers} >= col.entries.size();
        if (sweep) {
            col.max_len = 0;
            for (const Entry& e : col.entries) col.max_len = std::max(col.max_len, e.hi - e.lo);
            sweep_column(col.entries, wanted, collect);
        }
        for (uint32_t k = 0; k < col.movers; ++k) query_column(col, column_movers_[col.first_mover + k], !sweep);
    }
    queued_.clear();
    // The exact tests, with the records of a later candidate loaded ahead (they are scattered).
    constexpr std::size_t kAhead = 8;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
        if (i + kAhead < candidates_.size()) {
            __builtin_prefetch(&records_[candidates_[i + kAhead].first]);
            __builtin_prefetch(&records_[candidates_[i + kAhead].second]);
        }
        test_swept_pair(candidates_[i].first, candidates_[i].second, entered_);
    }
    for (uint32_t l : large_) {
        for (uint32_t id = 0; id < members_.size(); ++id) {
            if (id == l || !members_[id].listed || !(moving_flag_[l] || moving_flag_[id])) continue;
            if (members_[id].large && id < l) continue;
            test_swept_pair(l, id, entered_);
        }
    }
    for (uint64_t k : entered_) overlaps_.insert(k);
    for (uint32_t id : moving_) moving_flag_[id] = 0;
}

std::string SpacetimeSap::check_invariants() const {
    std::string base = BroadPhase::check_invariants();
    if (!base.empty()) return base;
    std::ostringstream why;
    std::vector<uint32_t> present;
    collect_present(present);
    std::size_t entries = 0;
    for (const Column& c : columns_) {
        for (const std::vector<Entry>* v : {&c.entries, &c.statics}) {
            entries += v->size();
            for (std::size_t i = 1; i < v->size(); ++i)
                if (!entry_less((*v)[i - 1], (*v)[i])) return "a column is not sorted";
        }
    }
    std::size_t expected_entries = 0;
    for (uint32_t id : present) {
        const Member& m = members_[id];
        const Aabb& b = records_[id].box;
        if (!m.listed) {
            why << "object " << id << " is not listed";
            return why.str();
        }
        for (int k = 0; k < 3; ++k) {
            if (m.keyed.min[k] > b.min[k] || m.keyed.max[k] < b.max[k]) {
                why << "object " << id << " is keyed by a box that does not hold its box";
                return why.str();
            }
        }
        if (m.in_statics != records_[id].is_static) {
            why << "object " << id << " is listed as " << (m.in_statics ? "" : "not ") << "static";
            return why.str();
        }
        if (m.large) {
            if (!std::binary_search(large_.begin(), large_.end(), id)) return "large object missing from the list";
            continue;
        }
        if (m.y0 != cell(m.keyed.min.y) || m.y1 != cell(m.keyed.max.y) || m.z0 != cell(m.keyed.min.z) ||
            m.z1 != cell(m.keyed.max.z)) {
            why << "object " << id << " has a stale column range";
            return why.str();
        }
        const Entry want = make_entry(id, m.keyed);
        for (int32_t cy = m.y0; cy <= m.y1; ++cy) {
            for (int32_t cz = m.z0; cz <= m.z1; ++cz) {
                ++expected_entries;
                const Column* c = find_column(cy, cz);
                const std::vector<Entry>* v = c == nullptr ? nullptr : m.in_statics ? &c->statics : &c->entries;
                const bool ok = v != nullptr && std::any_of(v->begin(), v->end(), [&](const Entry& e) {
                                    return e.id == id && e.lo == want.lo && e.hi == want.hi &&
                                           std::equal(std::begin(e.span), std::end(e.span), std::begin(want.span));
                                });
                if (!ok) {
                    why << "object " << id << " is missing from column (" << cy << ", " << cz << ")";
                    return why.str();
                }
            }
        }
    }
    if (entries != expected_entries) {
        why << "columns hold " << entries << " entries, the objects' ranges " << expected_entries;
        return why.str();
    }
    return check_overlap_set(present, records_, overlaps_,
                             [](uint32_t, uint32_t, bool, std::ostream&) { return true; });
}

std::unique_ptr<BroadPhase> make_spacetime_sap() { return std::make_unique<SpacetimeSap>(); }

}  // namespace kairos::broadphase_detail
