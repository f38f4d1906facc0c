// SPDX-License-Identifier: MIT
// The space-time sweep and prune in regions (BroadPhaseKind::SpacetimeSap, class SpacetimeSap), the
// default. Internal to broadphase/ (namespace broadphase_detail).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "broadphase/pair_set.hpp"

namespace kairos::broadphase_detail {

// ---- Space-time sweep in regions -------------------------------------------------------------
//
// One sorted list per axis makes every moving box pass every endpoint between its old and new
// place: in a uniform scene that grows as N^(2/3) per box (about 42 swaps per box per step at 10k
// boxes, 200 at 100k; docs/peers.md). Here space is cut into columns along x, a square grid of cells
// in (y, z). Each object is entered in every column its box swept over the step touches (closed
// intervals, so boxes that touch share a column), as its swept x interval with its swept y and z
// intervals as float spans. Per column a sweep and prune along x on the swept intervals gives the
// candidates; each candidate with a moving object gets the exact 4D test of brute force
// (first_overlap_time), so pairs and first times equal brute force's exactly. A pair overlapping
// at some moment overlaps at some point of space, whose column holds both objects, and their swept
// x intervals overlap there: no pair is missed. Columns with no moving object are not visited;
// pairs of objects that do not move keep their state in the overlap set, reported at t = 0.
// Static objects' entries are kept apart in each column (`statics`): a step never re-keys,
// compacts, merges or sweeps them; each moving entry finds the static ones near it by binary
// search, so a column of many static objects costs its movers a search each, not a pass.
// Objects whose swept box spans more than kMaxColumns columns are kept in a list of their own and
// tested against every candidate directly.
class SpacetimeSap final : public BroadPhase {
public:
    SpacetimeSap() : BroadPhase(BroadPhaseKind::SpacetimeSap) {}
    std::string check_invariants() const override;
    double query_cell_size() const override { return cell_size_; }
    // on_step dooms every pair of a moving object and re-keys it by its swept box.
    bool restarts_moving_objects() const override { return true; }

    static constexpr int64_t kMaxColumns = 64;

private:
    // One object in one column: its keyed box's x interval, and its y and z intervals rounded
    // outward to float. Columns are sorted by (lo, id).
    struct Entry {
        double lo, hi;
        float span[4];  // y lo, y hi, z lo, z hi
        uint32_t id;
    };
    // The order of a column's entries: by lo, ties by id. A function object, not a function:
    // std::sort and std::lower_bound then inline it (through a function pointer they may not).
    struct EntryLess {
        bool operator()(const Entry& x, const Entry& y) const { return x.lo < y.lo || (x.lo == y.lo && x.id < y.id); }
    };
    static constexpr EntryLess entry_less{};
    struct Column {
        std::vector<Entry> entries;  // objects that are not static
        std::vector<Entry> statics;  // static objects, sorted the same way
        uint32_t visited = 0;  // the pass that last queued it for a sweep
        double max_len = 0;    // at least the longest entry's hi - lo (local queries start there)
        double static_max_len = 0;  // the same for statics
        uint32_t movers = 0;   // this step: its moving entries, at column_movers_[first_mover...]
        uint32_t first_mover = 0;
    };
    // Per object: the box its entries were made from (its box, or the box swept over the last
    // step) and the columns they are in.
    struct Member {
        Aabb keyed;
        int32_t y0 = 0, y1 = -1, z0 = 0, z1 = -1;
        bool large = false;
        bool listed = false;  // in columns or in large_
        bool in_statics = false;  // its entries are in the columns' statics (static when listed)
        uint8_t cached = 0;   // columns in `cols` (0: more than fit, found by key)
        uint32_t cols[4] = {};
    };
    // Calls f(column index) for each column of a listed, not large object.
    template <class F>
    void for_columns(uint32_t id, F&& f) {
        const Member& m = members_[id];
        if (m.cached != 0) {
            for (uint8_t i = 0; i < m.cached; ++i) f(m.cols[i]);
            return;
        }
        for (int32_t cy = m.y0; cy <= m.y1; ++cy)
            for (int32_t cz = m.z0; cz <= m.z1; ++cz) f(column_at(cy, cz));
    }
    // Calls f(entry) for the entries of a sorted column whose x interval may reach q's (those
    // starting within the column's longest entry before q, a few ulps lower for rounding).
    template <class F>
    static void for_entries_near(const Column& c, const Aabb& q, F&& f) {
        for_near(c.entries, c.max_len, q.min.x, q.max.x, f);
        for_near(c.statics, c.static_max_len, q.min.x, q.max.x, f);
    }
    // The same in one sorted list of entries, for the x interval [lo, hi].
    template <class F>
    static void for_near(const std::vector<Entry>& v, double max_len, double lo, double hi, F&& f) {
        double from = lo - max_len;
        from -= (std::fabs(from) + max_len) * 0x1p-50;
        auto it = std::lower_bound(v.begin(), v.end(), from, [](const Entry& e, double x) { return e.lo < x; });
        for (; it != v.end() && !(it->lo > hi); ++it) f(*it);
    }
    // The entries of one kind (static or not) of a column, and the bound of their lengths.
    static std::vector<Entry>& list_of(Column& c, bool is_static) { return is_static ? c.statics : c.entries; }
    static double& max_len_of(Column& c, bool is_static) { return is_static ? c.static_max_len : c.max_len; }
    // Sets the member's columns from its keyed box (creating columns as needed).
    void place(uint32_t id, const Aabb& k);

    void on_flush() override;
    void on_teleport(uint32_t id, const Aabb& old_box) override;
    void on_step() override;
    void on_query_box(const Aabb& q, std::vector<uint32_t>& out) const override;
    void on_static_change(uint32_t id) override { on_teleport(id, records_[id].box); }
    // query_box in one column (cell cy, cz) of a query whose cells start at y0, z0.
    void query_column_box(const Column& c, int32_t cy, int32_t cz, int32_t y0, int32_t z0, const Aabb& q,
                          std::vector<uint32_t>& out) const;

    int32_t cell(double v) const;
    static uint64_t column_key(int32_t cy, int32_t cz);
    // Fibonacci hashing: the top bits of key * 2^64 / phi, as many as the table's size needs.
    std::size_t column_home(uint64_t key) const {
        const auto bits = static_cast<unsigned>(std::countr_zero(column_index_.size()));
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - bits));
    }
    uint32_t column_at(int32_t cy, int32_t cz);
    const Column* find_column(int32_t cy, int32_t cz) const;
    static Entry make_entry(uint32_t id, const Aabb& k);
    // Takes the object out of its columns (or the large list) and enters it under box k.
    void unlist(uint32_t id);
    void list(uint32_t id, const Aabb& k);
    // Re-keys the listed objects in rekeys_ (see rekey_all).
    void rekey_all();
    std::vector<uint32_t> rekeys_;  // objects to re-key: by their swept box if moving, else by their box
    std::vector<std::pair<uint32_t, Aabb>> movers_between_;
    std::vector<Entry> entry_;                          // by id: its entry in each of its columns (dense: the
                                                        // rewrite pass reads it for every moving entry)
    std::vector<uint8_t> pending_;                      // by id: re-keyed, entries to rewrite
    std::vector<uint8_t> leaving_;                      // by id: scratch of a column's compaction
    std::vector<std::pair<uint32_t, uint32_t>> leave_;  // (column, id)
    std::vector<std::pair<uint32_t, Entry>> enter_;     // (column, entry)
    std::vector<Entry> merged_;
    void queue(uint32_t column);
    void sort_column(Column& c);
    // Sweep and prune along x over one column: calls f(a, b) for each pair whose x intervals
    // and spans overlap and `wanted(a, b)` holds.
    template <class Wanted, class F>
    void sweep_column(const std::vector<Entry>& entries, Wanted&& wanted, F&& f);
    // Appends to candidates_ the pairs of a moving entry with the entries near it: those that are
    // not static (all_kinds) and the static ones.
    void query_column(const Column& c, uint32_t id, bool all_kinds);
    bool both_static(uint32_t a, uint32_t b) const { return records_[a].is_static && records_[b].is_static; }

    double cell_size_ = 0;  // chosen at the first insertion
    double inverse_cell_ = 1;
    std::vector<Member> members_;
    std::vector<Column> columns_;
    std::vector<std::pair<uint64_t, uint32_t>> column_index_;  // open addressing: key -> column
    std::size_t column_count_ = 0;
    std::vector<uint32_t> large_;
    PairSet overlaps_;  // pairs whose boxes overlap now, not both static
    std::vector<uint8_t> moving_flag_;
    std::vector<uint32_t> stale_;   // objects keyed by their last swept box (a teleport may leave
                                    // one listed here after re-keying it: then its flag is 0)
    std::vector<uint8_t> stale_flag_;  // by id: listed in stale_ and still keyed by the swept box
    std::vector<uint32_t> queued_;  // columns to sort and sweep
    uint32_t pass_ = 0;
    struct Active {
        double hi;
        float span[4];
        uint32_t id;
    };
    std::vector<Active> active_;
    std::vector<uint64_t> doomed_, entered_, kept_;
    std::vector<uint32_t> column_movers_;                    // moving ids grouped by column (see first_mover)
    std::vector<std::pair<uint32_t, uint32_t>> candidates_;  // pairs for the exact test
    std::vector<double> extents_;
};

}  // namespace kairos::broadphase_detail
