// SPDX-License-Identifier: MIT
// SpacetimeSap's columns: the column index, an object's entries (place, list, unlist), the re-keying
// of the objects that moved, and per column the sort, the query of one entry and the exact test.
#include "broadphase/spacetime_sap.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "broadphase/box_time.hpp"
#include "broadphase/float_bounds.hpp"

namespace kairos::broadphase_detail {

// Cell indices are clamped to [-2^30, 2^30), so offset by 2^30 they fit 31 bits: a key is never
// the hash's empty marker.
uint64_t SpacetimeSap::column_key(int32_t cy, int32_t cz) {
    return (uint64_t{static_cast<uint32_t>(cy + 1073741824)} << 32) | static_cast<uint32_t>(cz + 1073741824);
}

int32_t SpacetimeSap::cell(double v) const {
    // floor(v / cell), monotone in v (so a point of a box lies in a cell of the box's range), and
    // clamped. A positive factor keeps the order; floor by truncation (std::floor is a library
    // call on baseline x86-64).
    const double x = v * inverse_cell_;
    if (!(x >= -1073741824.0)) return -1073741824;  // NaN cannot come: boxes are finite
    if (x >= 1073741823.0) return 1073741823;
    const auto i = static_cast<int32_t>(x);
    return i - (static_cast<double>(i) > x ? 1 : 0);  // a selection: negative x is common
}

uint32_t SpacetimeSap::column_at(int32_t cy, int32_t cz) {
    const uint64_t key = column_key(cy, cz);
    if (2 * (column_count_ + 1) > column_index_.size()) {
        std::vector<std::pair<uint64_t, uint32_t>> old;
        old.swap(column_index_);
        column_index_.assign(old.empty() ? 64 : 2 * old.size(), {PairSet::kEmpty, 0});
        for (const auto& kv : old) {
            if (kv.first == PairSet::kEmpty) continue;
            std::size_t i = column_home(kv.first);
            while (column_index_[i].first != PairSet::kEmpty) i = (i + 1) & (column_index_.size() - 1);
            column_index_[i] = kv;
        }
    }
    const std::size_t mask = column_index_.size() - 1;
    std::size_t i = column_home(key);
    for (; column_index_[i].first != PairSet::kEmpty; i = (i + 1) & mask) {
        if (column_index_[i].first == key) return column_index_[i].second;
    }
    columns_.emplace_back();
    column_index_[i] = {key, static_cast<uint32_t>(columns_.size() - 1)};
    ++column_count_;
    return static_cast<uint32_t>(columns_.size() - 1);
}

const SpacetimeSap::Column* SpacetimeSap::find_column(int32_t cy, int32_t cz) const {
    if (column_index_.empty()) return nullptr;
    const uint64_t key = column_key(cy, cz);
    const std::size_t mask = column_index_.size() - 1;
    for (std::size_t i = column_home(key); column_index_[i].first != PairSet::kEmpty; i = (i + 1) & mask) {
        if (column_index_[i].first == key) return &columns_[column_index_[i].second];
    }
    return nullptr;
}

SpacetimeSap::Entry SpacetimeSap::make_entry(uint32_t id, const Aabb& k) {
    return {
        k.min.x, k.max.x, {float_below(k.min.y), float_above(k.max.y), float_below(k.min.z), float_above(k.max.z)}, id};
}

void SpacetimeSap::queue(uint32_t column) {
    if (columns_[column].visited == pass_) return;
    columns_[column].visited = pass_;
    queued_.push_back(column);
}

void SpacetimeSap::unlist(uint32_t id) {
    Member& m = members_[id];
    if (!m.listed) return;
    m.listed = false;
    if (m.large) {
        large_.erase(std::find(large_.begin(), large_.end(), id));
        return;
    }
    const double lo = m.keyed.min.x;
    for_columns(id, [&](uint32_t c) {
        auto& v = list_of(columns_[c], m.in_statics);
        // Sorted by (lo, id): the entry is found by binary search on its key.
        auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(lo, id),
                                   [](const Entry& e, const std::pair<double, uint32_t>& k) {
                                       return e.lo < k.first || (e.lo == k.first && e.id < k.second);
                                   });
        v.erase(it);
    });
}

void SpacetimeSap::place(uint32_t id, const Aabb& k) {
    Member& m = members_[id];
    m.keyed = k;
    m.listed = true;
    m.in_statics = records_[id].is_static;
    m.y0 = cell(k.min.y);
    m.y1 = cell(k.max.y);
    m.z0 = cell(k.min.z);
    m.z1 = cell(k.max.z);
    const int64_t count = (int64_t{m.y1} - m.y0 + 1) * (int64_t{m.z1} - m.z0 + 1);
    entry_[id] = make_entry(id, k);
    m.large = count > kMaxColumns;
    m.cached = 0;
    if (m.large || count > 4) return;
    uint8_t n = 0;
    for (int32_t cy = m.y0; cy <= m.y1; ++cy)
        for (int32_t cz = m.z0; cz <= m.z1; ++cz) {
            const uint32_t c = column_at(cy, cz);
            members_[id].cols[n++] = c;  // column_at does not touch members_
        }
    members_[id].cached = n;
}

void SpacetimeSap::list(uint32_t id, const Aabb& k) {
    place(id, k);
    if (members_[id].large) {
        large_.insert(std::lower_bound(large_.begin(), large_.end(), id), id);
        return;
    }
    const Entry e = entry_[id];
    const bool is_static = members_[id].in_statics;
    for_columns(id, [&](uint32_t c) {
        auto& v = list_of(columns_[c], is_static);
        double& longest = max_len_of(columns_[c], is_static);
        longest = std::max(longest, e.hi - e.lo);
        v.insert(std::lower_bound(v.begin(), v.end(), e, entry_less), e);
    });
}

// Re-keys objects by new boxes, column by column rather than object by object:
// 1. each object's columns are compared with the new range: it leaves some, stays in some, and
//    enters some (most objects stay in all of theirs);
// 2. every column it leaves is compacted once, whatever the number of objects leaving it;
// 3. in the columns it stays in, its entry is overwritten in one pass over each column, and the
//    column is sorted again (the swaps of the step);
// 4. the entries entering a column are sorted and merged into it in one pass.
// Objects that become large or stop being large go through unlist/list.
void SpacetimeSap::rekey_all() {
    leave_.clear();
    enter_.clear();
    movers_between_.clear();
    for (uint32_t id : rekeys_) {
        const Record& r = records_[id];
        const Aabb k = moving_flag_[id] ? union_box(r.box, r.box_end) : r.box;
        Member& m = members_[id];
        // Never static: move() refuses static objects, and set_static re-lists an object by its
        // box and clears its stale flag (on_teleport), so none reaches rekeys_.
        assert(!m.in_statics);
        if (m.keyed.min == k.min && m.keyed.max == k.max) {
            // Same key (a move back to where the last step swept from, or a still object): the
            // entries stand, but a mover's columns must still be swept, and on_step groups the
            // movers only over queued columns.
            if (moving_flag_[id] && !m.large) for_columns(id, [&](uint32_t c) { queue(c); });
            continue;
        }
        const int32_t y0 = cell(k.min.y), y1 = cell(k.max.y), z0 = cell(k.min.z), z1 = cell(k.max.z);
        const bool large = (int64_t{y1} - y0 + 1) * (int64_t{z1} - z0 + 1) > kMaxColumns;
        if (large || m.large) {
            unlist(id);
            movers_between_.push_back({id, k});
            continue;
        }
        if (y0 == m.y0 && y1 == m.y1 && z0 == m.z0 && z1 == m.z1) {
            m.keyed = k;
            entry_[id] = make_entry(id, k);
            pending_[id] = 1;
            for_columns(id, [&](uint32_t c) { queue(c); });
            continue;
        }
        const int32_t oy0 = m.y0, oy1 = m.y1, oz0 = m.z0, oz1 = m.z1;
        for (int32_t cy = oy0; cy <= oy1; ++cy) {
            for (int32_t cz = oz0; cz <= oz1; ++cz) {
                if (cy < y0 || cy > y1 || cz < z0 || cz > z1) leave_.push_back({column_at(cy, cz), id});
            }
        }
        place(id, k);  // the new range, columns and entry
        pending_[id] = 1;
        // Columns of the new range that were in the old one keep the entry (overwritten below);
        // those that were not receive it.
        const Member& n = members_[id];
        for (int32_t cy = n.y0; cy <= n.y1; ++cy) {
            for (int32_t cz = n.z0; cz <= n.z1; ++cz) {
                const uint32_t c = column_at(cy, cz);
                queue(c);
                if (cy < oy0 || cy > oy1 || cz < oz0 || cz > oz1) enter_.push_back({c, entry_[id]});
            }
        }
    }
    // 2. Leaving: one compaction per column.
    std::sort(leave_.begin(), leave_.end());
    for (std::size_t i = 0; i < leave_.size();) {
        const uint32_t c = leave_[i].first;
        std::size_t j = i;
        for (; j < leave_.size() && leave_[j].first == c; ++j) leaving_[leave_[j].second] = 1;
        std::erase_if(columns_[c].entries, [&](const Entry& e) { return leaving_[e.id] != 0; });
        for (; i < j; ++i) leaving_[leave_[i].second] = 0;
    }
    // 3. Staying: rewrite and sort.
    for (uint32_t c : queued_) {
        double longest = columns_[c].max_len;
        for (Entry& e : columns_[c].entries) {
            if (!pending_[e.id]) continue;
            e = entry_[e.id];
            longest = std::max(longest, e.hi - e.lo);
        }
        columns_[c].max_len = longest;
        sort_column(columns_[c]);
    }
    for (uint32_t id : rekeys_) pending_[id] = 0;
    // 4. Entering: merged in order.
    std::sort(enter_.begin(), enter_.end(),
              [&](const std::pair<uint32_t, Entry>& x, const std::pair<uint32_t, Entry>& y) {
                  return x.first != y.first ? x.first < y.first : entry_less(x.second, y.second);
              });
    for (std::size_t i = 0; i < enter_.size();) {
        const uint32_t c = enter_[i].first;
        std::size_t j = i;
        while (j < enter_.size() && enter_[j].first == c) ++j;
        auto& v = columns_[c].entries;
        merged_.clear();
        merged_.reserve(v.size() + (j - i));
        std::size_t r = 0;
        for (; i < j; ++i) {
            const Entry& e = enter_[i].second;
            while (r < v.size() && entry_less(v[r], e)) merged_.push_back(v[r++]);
            merged_.push_back(e);
        }
        merged_.insert(merged_.end(), v.begin() + static_cast<std::ptrdiff_t>(r), v.end());
        v.swap(merged_);
        for (const Entry& e : v) columns_[c].max_len = std::max(columns_[c].max_len, e.hi - e.lo);
    }
    for (const auto& [id, k] : movers_between_) {
        list(id, k);
        if (members_[id].large) continue;
        for_columns(id, [&](uint32_t c) { queue(c); });
    }
    rekeys_.clear();
}

// Insertion sort by (lo, id): the order changes little from one step to the next.
void SpacetimeSap::sort_column(Column& c) {
    auto& v = c.entries;
    uint64_t swaps = 0;
    for (std::size_t i = 1; i < v.size(); ++i) {
        const Entry e = v[i];
        std::size_t j = i;
        while (j > 0 && entry_less(e, v[j - 1])) {
            v[j] = v[j - 1];
            --j;
        }
        if (j == i) continue;
        v[j] = e;
        swaps += i - j;
    }
    counters_.swaps += swaps;
}

// The candidates of one moving entry in a sorted column: entries whose lo lies in
// [m.lo - max_len, m.hi] (a few ulps lower, for the rounding of hi - lo and of the subtraction)
// hold every entry whose x interval meets m's. A pair of two moving entries is tested from the
// one with the smaller id.
void SpacetimeSap::query_column(const Column& c, uint32_t id, bool all_kinds) {
    const Entry& m = entry_[id];
    auto near = [&](const Entry& e) {
        if (e.id == id || e.hi < m.lo) return;
        if (e.span[0] > m.span[1] || m.span[0] > e.span[1] || e.span[2] > m.span[3] || m.span[2] > e.span[3]) return;
        if (moving_flag_[e.id] && e.id < id) return;
        candidates_.push_back({id, e.id});
    };
    if (all_kinds) for_near(c.entries, c.max_len, m.lo, m.hi, near);
    for_near(c.statics, c.static_max_len, m.lo, m.hi, near);
}

// Objects not yet flushed are in no column, large objects in large_; the rest are found in the
// columns the query's (y, z) cells cover (every column when those outnumber the columns there are).
// An object in several of them is reported from the first one it shares with the query.
void SpacetimeSap::on_query_box(const Aabb& q, std::vector<uint32_t>& out) const {
    const std::size_t from = out.size();
    for (uint32_t id : pending_adds_) {
        if (records_[id].state == State::PendingAdd && boxes_overlap(records_[id].box, q)) out.push_back(id);
    }
    // pending_adds_ may name an id twice (added, removed and added again before a flush).
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(from), out.end());
    out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(from), out.end()), out.end());
    for (uint32_t id : large_) {
        if (records_[id].state == State::Live && boxes_overlap(records_[id].box, q)) out.push_back(id);
    }
    if (column_count_ == 0) return;
    const int32_t y0 = cell(q.min.y), y1 = cell(q.max.y), z0 = cell(q.min.z), z1 = cell(q.max.z);
    const int64_t cells = (int64_t{y1} - y0 + 1) * (int64_t{z1} - z0 + 1);
    if (cells > static_cast<int64_t>(column_count_)) {
        for (const auto& [key, index] : column_index_) {
            if (key == PairSet::kEmpty) continue;
            const auto cy = static_cast<int32_t>(static_cast<int64_t>(key >> 32) - 1073741824);
            const auto cz = static_cast<int32_t>(static_cast<int64_t>(key & 0xffffffffu) - 1073741824);
            if (cy >= y0 && cy <= y1 && cz >= z0 && cz <= z1) query_column_box(columns_[index], cy, cz, y0, z0, q, out);
        }
        return;
    }
    for (int32_t cy = y0; cy <= y1; ++cy)
        for (int32_t cz = z0; cz <= z1; ++cz) {
            if (const Column* c = find_column(cy, cz)) query_column_box(*c, cy, cz, y0, z0, q, out);
        }
}

void SpacetimeSap::query_column_box(const Column& c, int32_t cy, int32_t cz, int32_t y0, int32_t z0, const Aabb& q,
                                    std::vector<uint32_t>& out) const {
    for_entries_near(c, q, [&](const Entry& e) {
        if (e.hi < q.min.x) return;
        const uint32_t id = e.id;
        const Member& m = members_[id];
        if (cy != std::max(m.y0, y0) || cz != std::max(m.z0, z0)) return;
        if (records_[id].state == State::Live && boxes_overlap(records_[id].box, q)) out.push_back(id);
    });
}

}  // namespace kairos::broadphase_detail
