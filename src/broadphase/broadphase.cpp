// Broad phase: the space-time sweep and prune (in regions, globally in one batch, and the talks'
// queued version), the encapsulating sweep, brute force.
//
// Measured (bench/bench_world.cpp, bench/results/world.csv): the queued sweep spends ~100-200 ns
// per swap on heap work and cache misses, and a uniform scene has ~42 swaps per moving box per
// step at 10k boxes; the global batch sweep does the same swaps at a few ns each; the region sweep
// makes the swaps local to columns (under one per box) and is the default (SpacetimeSap).
//
// Source: the talks' space-time sweep and prune (ALGORITHMS.md §5). Per axis a sorted array of
// endpoints; over the step every endpoint moves linearly from p0 (t = 0) to p1 (t = 1). Two
// adjacent endpoints L < R swap at the root of d(t) = (1 - t) d0 + t d1 with d0 = R.p0 - L.p0 and
// d1 = R.p1 - L.p1, that is t = d0 / (d0 - d1). Whether they swap at all depends only on the sign
// of d1, so the arrays end the step in exactly the order of the end positions.
#include "broadphase/broadphase.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace kairos {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool valid_box(const Aabb& b) {
    for (int k = 0; k < 3; ++k) {
        // Written so that NaN fails too.
        if (!(std::isfinite(b.min[k]) && std::isfinite(b.max[k]) && b.min[k] <= b.max[k])) return false;
    }
    return true;
}

bool same_box(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

// Boxes are finite (checked on entry), so plain comparisons serve (fmin/fmax are library calls).
Aabb union_box(const Aabb& a, const Aabb& b) {
    Aabb u;
    for (int k = 0; k < 3; ++k) {
        u.min[k] = std::min(a.min[k], b.min[k]);
        u.max[k] = std::max(a.max[k], b.max[k]);
    }
    return u;
}

uint64_t pair_key(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    return (uint64_t{a} << 32) | b;
}

// Set of pair keys: open addressing with linear probing and backward-shift deletion, so it never
// holds tombstones and allocates only when it grows.
class PairSet {
public:
    static constexpr uint64_t kEmpty = ~uint64_t{0};  // never a key: ids are below 2^30

    std::size_t size() const { return size_; }

    // Empties the set, keeping its capacity.
    void clear() {
        std::fill(slots_.begin(), slots_.end(), kEmpty);
        size_ = 0;
    }

    bool contains(uint64_t key) const {
        if (slots_.empty()) return false;
        for (std::size_t i = home(key);; i = (i + 1) & mask_) {
            if (slots_[i] == key) return true;
            if (slots_[i] == kEmpty) return false;
        }
    }

    bool insert(uint64_t key) {
        if (2 * (size_ + 1) > slots_.size()) grow();
        std::size_t i = home(key);
        for (; slots_[i] != kEmpty; i = (i + 1) & mask_) {
            if (slots_[i] == key) return false;
        }
        slots_[i] = key;
        ++size_;
        return true;
    }

    bool erase(uint64_t key) {
        if (slots_.empty()) return false;
        std::size_t i = home(key);
        for (; slots_[i] != key; i = (i + 1) & mask_) {
            if (slots_[i] == kEmpty) return false;
        }
        // Shift back the following entries of the cluster whose home is not in (i, j].
        for (std::size_t j = (i + 1) & mask_; slots_[j] != kEmpty; j = (j + 1) & mask_) {
            const std::size_t k = home(slots_[j]);
            const bool stays = i <= j ? (i < k && k <= j) : (i < k || k <= j);
            if (stays) continue;
            slots_[i] = slots_[j];
            i = j;
        }
        slots_[i] = kEmpty;
        --size_;
        return true;
    }

    template <class F>
    void for_each(F&& f) const {
        for (uint64_t k : slots_) {
            if (k != kEmpty) f(k);
        }
    }

private:
    std::size_t home(uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);  // Fibonacci hashing
    }

    void grow() {
        std::vector<uint64_t> old;
        old.swap(slots_);
        const std::size_t cap = old.empty() ? 16 : 2 * old.size();
        slots_.assign(cap, kEmpty);
        mask_ = cap - 1;
        shift_ = 64 - static_cast<unsigned>(std::countr_zero(cap));
        size_ = 0;
        for (uint64_t k : old) {
            if (k != kEmpty) insert(k);
        }
    }

    std::vector<uint64_t> slots_;
    std::size_t size_ = 0;
    std::size_t mask_ = 0;
    unsigned shift_ = 63;
};

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

// ---- Space-time sweep and prune --------------------------------------------------------------

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
        bool operator<(const SortItem& o) const {
            return key != o.key ? key < o.key : flag_owner < o.flag_owner;
        }
    };

    void on_flush() override;
    void on_teleport(uint32_t id, const Aabb& old_box) override;

    uint32_t& ep(uint32_t id, int axis, bool max) { return ep_[id][static_cast<std::size_t>(2 * axis + (max ? 1 : 0))]; }
    uint32_t ep(uint32_t id, int axis, bool max) const { return ep_[id][static_cast<std::size_t>(2 * axis + (max ? 1 : 0))]; }
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

// Float bounds of a double: a float <= x and a float >= x, within a few float ulps (infinite
// beyond the float range). x is lowered by more than half a float ulp (relative 2^-22, plus 2^-140
// for subnormals) and rounded to nearest, which can then not land above x. No branches: these run
// four times per moving object and step, on rounding directions that are random.
float float_below(double x) {
    double y = x - (std::fabs(x) * 0x1p-22 + 0x1p-140);
    y = y < -3.4028234663852886e38 ? -std::numeric_limits<double>::infinity() : y;
    y = y > 3.4028234663852886e38 ? 3.4028234663852886e38 : y;
    return static_cast<float>(y);
}
float float_above(double x) { return -float_below(-x); }

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
        doomed_.clear();
        overlaps_.for_each([&](uint64_t k) {
            if (removed(static_cast<uint32_t>(k >> 32)) || removed(static_cast<uint32_t>(k))) doomed_.push_back(k);
        });
        for (uint64_t k : doomed_) overlaps_.erase(k);
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
                if (!both_static(id, other) && overlap_on_other_axes(id, other, 0)) overlaps_.insert(pair_key(id, other));
            }
            if (fresh) {
                for (uint32_t other : active_all_) {
                    if (!both_static(id, other) && overlap_on_other_axes(id, other, 0)) overlaps_.insert(pair_key(id, other));
                }
            }
            auto& list = fresh ? active_new_ : active_all_;
            active_pos_[id] = static_cast<uint32_t>(list.size());
            list.push_back(id);
        }
    }
}

void QueuedSpacetimeSap::on_flush() {
    EndpointSap::on_flush();
    // Slot of the adjacent endpoints at i and i + 1 of an axis: 4 * i + axis.
    heap_.resize_slots(4 * axes_[0].size());
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
            if (id >= records_.size() || records_[id].state == State::Absent || records_[id].state == State::PendingAdd) {
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
                why << "axis " << axis << " index " << i << ": endpoint at " << e.p0 << "/" << e.p1 << ", box says " << want;
                return why.str();
            }
            const int j1 = (axis + 1) % 3, j2 = (axis + 2) % 3;
            if (!(e.span[0] <= b.min[j1] && e.span[1] >= b.max[j1] && e.span[2] <= b.min[j2] && e.span[3] >= b.max[j2])) {
                why << "axis " << axis << " index " << i << ": span of object " << id << " does not hold its box";
                return why.str();
            }
            if (i > 0 && before(e, arr[i - 1])) {
                why << "axis " << axis << " not sorted at index " << i;
                return why.str();
            }
        }
    }
    std::size_t expected = 0;
    for (std::size_t x = 0; x < present.size(); ++x) {
        for (std::size_t y = x + 1; y < present.size(); ++y) {
            const uint32_t a = present[x], b = present[y];
            if (both_static(a, b)) continue;
            const bool by_box = boxes_overlap(records_[a].box, records_[b].box);
            const bool by_index = overlap_on_axis(a, b, 0) && overlap_on_axis(a, b, 1) && overlap_on_axis(a, b, 2);
            if (by_box != by_index) {
                why << "pair " << a << "," << b << ": boxes overlap " << by_box << ", indices say " << by_index;
                return why.str();
            }
            if (by_box != overlaps_.contains(pair_key(a, b))) {
                why << "pair " << a << "," << b << ": boxes overlap " << by_box << ", overlap set says " << !by_box;
                return why.str();
            }
            expected += by_box ? 1 : 0;
        }
    }
    if (expected != overlaps_.size()) {
        why << "overlap set holds " << overlaps_.size() << " pairs, brute force finds " << expected;
        return why.str();
    }
    return {};
}

std::string QueuedSpacetimeSap::check_invariants() const {
    if (!heap_.empty()) return "event heap not empty between steps";
    return EndpointSap::check_invariants();
}

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
class SpacetimeSap final : public EndpointSap {
public:
    SpacetimeSap() : EndpointSap(BroadPhaseKind::SpacetimeSapGlobal) {}

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
void SpacetimeSap::crossing(const Endpoint& max_a, const Endpoint& min_b) {
    uint32_t a = owner(max_a), b = owner(min_b);
    if (a > b) std::swap(a, b);
    ++counters_.crossing_tests;
    const Record& ra = records_[a];
    const Record& rb = records_[b];
    double t = 0;
    if (!first_overlap_time({ra.box, ra.box_end}, {rb.box, rb.box_end}, &t)) return;
    pairs_.push_back({a, b, t});
    if (boxes_overlap(ra.box_end, rb.box_end)) entered_.push_back(pair_key(a, b));
}

// Insertion sort of a whole axis by end position: each endpoint that ends before its left
// neighbour moves left past every endpoint it crosses. O(n + swaps), sequential memory.
void SpacetimeSap::sort_axis(int axis) {
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
void SpacetimeSap::bubble_moving(int axis) {
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

void SpacetimeSap::on_step() {
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

// ---- Space-time sweep in regions -------------------------------------------------------------
//
// One sorted list per axis makes every moving box pass every endpoint between its old and new
// place: in a uniform scene that grows as N^(2/3) per box (about 42 swaps per box per step at 10k
// boxes, 200 at 100k; PEERS.md). Here space is cut into columns along x, a square grid of cells
// in (y, z). Each object is entered in every column its box swept over the step touches (closed
// intervals, so boxes that touch share a column), as its swept x interval with its swept y and z
// intervals as float spans. Per column a sweep and prune along x on the swept intervals gives the
// candidates; each candidate with a moving object gets the exact 4D test of brute force
// (first_overlap_time), so pairs and first times equal brute force's exactly. A pair overlapping
// at some moment overlaps at some point of space, whose column holds both objects, and their swept
// x intervals overlap there: no pair is missed. Columns with no moving object are not visited;
// pairs of objects that do not move keep their state in the overlap set, reported at t = 0.
// Objects whose swept box spans more than kMaxColumns columns are kept in a list of their own and
// tested against every candidate directly.
class RegionSap final : public BroadPhase {
public:
    RegionSap() : BroadPhase(BroadPhaseKind::SpacetimeSap) {}
    std::string check_invariants() const override;

    static constexpr int64_t kMaxColumns = 64;

private:
    // One object in one column: its keyed box's x interval, and its y and z intervals rounded
    // outward to float. Columns are sorted by (lo, id).
    struct Entry {
        double lo, hi;
        float span[4];  // y lo, y hi, z lo, z hi
        uint32_t id;
    };
    struct Column {
        std::vector<Entry> entries;
        uint32_t visited = 0;  // the pass that last queued it for a sweep
        double max_len = 0;    // at least the longest entry's hi - lo (local queries start there)
        uint32_t movers = 0;       // this step: its moving entries, at column_movers_[first_mover...]
        uint32_t first_mover = 0;
    };
    // Per object: the box its entries were made from (its box, or the box swept over the last
    // step) and the columns they are in.
    struct Member {
        Aabb keyed;
        int32_t y0 = 0, y1 = -1, z0 = 0, z1 = -1;
        bool large = false;
        bool listed = false;  // in columns or in large_
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
    // Sets the member's columns from its keyed box (creating columns as needed).
    void place(uint32_t id, const Aabb& k);

    void on_flush() override;
    void on_teleport(uint32_t id, const Aabb& old_box) override;
    void on_step() override;

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
    std::vector<Entry> entry_;      // by id: its entry in each of its columns (dense: the
                                    // rewrite pass reads it for every moving entry)
    std::vector<uint8_t> pending_;  // by id: re-keyed, entries to rewrite
    std::vector<uint8_t> leaving_;  // by id: scratch of a column's compaction
    std::vector<std::pair<uint32_t, uint32_t>> leave_;  // (column, id)
    std::vector<std::pair<uint32_t, Entry>> enter_;     // (column, entry)
    std::vector<Entry> merged_;
    void queue(uint32_t column);
    void sort_column(Column& c);
    // Sweep and prune along x over one column: calls f(a, b) for each pair whose x intervals
    // and spans overlap and `wanted(a, b)` holds.
    template <class Wanted, class F>
    void sweep_column(const Column& c, Wanted&& wanted, F&& f);
    void test_moving_pair(uint32_t a, uint32_t b);
    void query_column(const Column& c, uint32_t id);  // appends to candidates_
    bool both_static(uint32_t a, uint32_t b) const { return records_[a].is_static && records_[b].is_static; }

    double cell_size_ = 0;  // chosen at the first insertion
    double inverse_cell_ = 1;
    std::vector<Member> members_;
    std::vector<Column> columns_;
    std::vector<std::pair<uint64_t, uint32_t>> column_index_;  // open addressing: key -> column
    std::size_t column_count_ = 0;
    std::vector<uint32_t> large_;
    PairSet overlaps_;     // pairs whose boxes overlap now, not both static
    std::vector<uint8_t> moving_flag_;
    std::vector<uint32_t> stale_;  // objects keyed by their last swept box
    std::vector<uint32_t> queued_;  // columns to sort and sweep
    uint32_t pass_ = 0;
    struct Active {
        double hi;
        float span[4];
        uint32_t id;
    };
    std::vector<Active> active_;
    std::vector<uint64_t> doomed_, entered_, kept_;
    std::vector<uint32_t> column_movers_;  // moving ids grouped by column (see first_mover)
    std::vector<std::pair<uint32_t, uint32_t>> candidates_;  // pairs for the exact test
    std::vector<double> extents_;
};

// Cell indices are clamped to [-2^30, 2^30), so offset by 2^30 they fit 31 bits: a key is never
// the hash's empty marker.
uint64_t RegionSap::column_key(int32_t cy, int32_t cz) {
    return (uint64_t{static_cast<uint32_t>(cy + 1073741824)} << 32) | static_cast<uint32_t>(cz + 1073741824);
}

int32_t RegionSap::cell(double v) const {
    // floor(v / cell), monotone in v (so a point of a box lies in a cell of the box's range), and
    // clamped. A positive factor keeps the order; floor by truncation (std::floor is a library
    // call on baseline x86-64).
    const double x = v * inverse_cell_;
    if (!(x >= -1073741824.0)) return -1073741824;  // NaN cannot come: boxes are finite
    if (x >= 1073741823.0) return 1073741823;
    const auto i = static_cast<int32_t>(x);
    return i - (static_cast<double>(i) > x ? 1 : 0);  // a selection: negative x is common
}

uint32_t RegionSap::column_at(int32_t cy, int32_t cz) {
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

const RegionSap::Column* RegionSap::find_column(int32_t cy, int32_t cz) const {
    if (column_index_.empty()) return nullptr;
    const uint64_t key = column_key(cy, cz);
    const std::size_t mask = column_index_.size() - 1;
    for (std::size_t i = column_home(key); column_index_[i].first != PairSet::kEmpty; i = (i + 1) & mask) {
        if (column_index_[i].first == key) return &columns_[column_index_[i].second];
    }
    return nullptr;
}

RegionSap::Entry RegionSap::make_entry(uint32_t id, const Aabb& k) {
    return {k.min.x, k.max.x, {float_below(k.min.y), float_above(k.max.y), float_below(k.min.z), float_above(k.max.z)}, id};
}

void RegionSap::queue(uint32_t column) {
    if (columns_[column].visited == pass_) return;
    columns_[column].visited = pass_;
    queued_.push_back(column);
}

void RegionSap::unlist(uint32_t id) {
    Member& m = members_[id];
    if (!m.listed) return;
    m.listed = false;
    if (m.large) {
        large_.erase(std::find(large_.begin(), large_.end(), id));
        return;
    }
    const double lo = m.keyed.min.x;
    for_columns(id, [&](uint32_t c) {
        auto& v = columns_[c].entries;
        // Sorted by (lo, id): the entry is found by binary search on its key.
        auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(lo, id), [](const Entry& e, const std::pair<double, uint32_t>& k) {
            return e.lo < k.first || (e.lo == k.first && e.id < k.second);
        });
        v.erase(it);
    });
}

void RegionSap::place(uint32_t id, const Aabb& k) {
    Member& m = members_[id];
    m.keyed = k;
    m.listed = true;
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

void RegionSap::list(uint32_t id, const Aabb& k) {
    place(id, k);
    if (members_[id].large) {
        large_.insert(std::lower_bound(large_.begin(), large_.end(), id), id);
        return;
    }
    const Entry e = entry_[id];
    for_columns(id, [&](uint32_t c) {
        auto& v = columns_[c].entries;
        columns_[c].max_len = std::max(columns_[c].max_len, e.hi - e.lo);
        v.insert(std::lower_bound(v.begin(), v.end(), e, [](const Entry& x, const Entry& y) {
                     return x.lo < y.lo || (x.lo == y.lo && x.id < y.id);
                 }),
                 e);
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
void RegionSap::rekey_all() {
    leave_.clear();
    enter_.clear();
    movers_between_.clear();
    for (uint32_t id : rekeys_) {
        const Record& r = records_[id];
        const Aabb k = moving_flag_[id] ? union_box(r.box, r.box_end) : r.box;
        Member& m = members_[id];
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
    auto entry_less = [](const Entry& x, const Entry& y) { return x.lo < y.lo || (x.lo == y.lo && x.id < y.id); };
    std::sort(enter_.begin(), enter_.end(), [&](const std::pair<uint32_t, Entry>& x, const std::pair<uint32_t, Entry>& y) {
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
void RegionSap::sort_column(Column& c) {
    auto& v = c.entries;
    uint64_t swaps = 0;
    for (std::size_t i = 1; i < v.size(); ++i) {
        const Entry e = v[i];
        std::size_t j = i;
        while (j > 0 && (e.lo < v[j - 1].lo || (e.lo == v[j - 1].lo && e.id < v[j - 1].id))) {
            v[j] = v[j - 1];
            --j;
        }
        if (j == i) continue;
        v[j] = e;
        swaps += i - j;
    }
    counters_.swaps += swaps;
}

template <class Wanted, class F>
void RegionSap::sweep_column(const Column& c, Wanted&& wanted, F&& f) {
    // The active list holds copies of the entries whose x interval is still open, compacted as
    // it is read; the tests are written without branches but for the rare pair that meets.
    std::size_t n = 0;  // active entries: active_[0, n); the vector only grows
    for (const Entry& e : c.entries) {
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

// The candidates of one moving entry in a sorted column: entries whose lo lies in
// [m.lo - max_len, m.hi] hold every entry whose x interval meets m's. A pair of two moving
// entries is tested from the one with the smaller id.
void RegionSap::query_column(const Column& c, uint32_t id) {
    const Entry& m = entry_[id];
    // A few ulps lower, for the rounding of hi - lo and of the subtraction.
    double from = m.lo - c.max_len;
    from -= (std::fabs(from) + c.max_len) * 0x1p-50;
    auto it = std::lower_bound(c.entries.begin(), c.entries.end(), from, [](const Entry& e, double x) { return e.lo < x; });
    for (; it != c.entries.end() && !(it->lo > m.hi); ++it) {
        const Entry& e = *it;
        if (e.id == id || e.hi < m.lo) continue;
        if (e.span[0] > m.span[1] || m.span[0] > e.span[1] || e.span[2] > m.span[3] || m.span[2] > e.span[3]) continue;
        if (moving_flag_[e.id] && e.id < id) continue;
        candidates_.push_back({id, e.id});
    }
}

void RegionSap::test_moving_pair(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    ++counters_.crossing_tests;
    const Record& ra = records_[a];
    const Record& rb = records_[b];
    double t = 0;
    if (!first_overlap_time({ra.box, ra.box_end}, {rb.box, rb.box_end}, &t)) return;
    pairs_.push_back({a, b, t});
    if (boxes_overlap(ra.box_end, rb.box_end)) entered_.push_back(pair_key(a, b));
}

void RegionSap::on_flush() {
    if (members_.size() < records_.size()) {
        members_.resize(records_.size());
        moving_flag_.resize(records_.size(), 0);
        pending_.resize(records_.size(), 0);
        leaving_.resize(records_.size(), 0);
        entry_.resize(records_.size());
    }
    if (!pending_removes_.empty()) {
        auto removed = [&](uint32_t id) { return records_[id].state == State::PendingRemove; };
        doomed_.clear();
        overlaps_.for_each([&](uint64_t k) {
            if (removed(static_cast<uint32_t>(k >> 32)) || removed(static_cast<uint32_t>(k))) doomed_.push_back(k);
        });
        for (uint64_t k : doomed_) overlaps_.erase(k);
        for (uint32_t id : pending_removes_) unlist(id);
        std::erase_if(stale_, removed);
    }
    if (pending_adds_.empty()) return;
    if (cell_size_ == 0) {
        // Columns about four typical objects wide.
        extents_.clear();
        for (uint32_t id : pending_adds_) {
            const Aabb& b = records_[id].box;
            extents_.push_back(std::max(b.max.y - b.min.y, b.max.z - b.min.z));
        }
        std::nth_element(extents_.begin(), extents_.begin() + static_cast<std::ptrdiff_t>(extents_.size() / 2), extents_.end());
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
        for_columns(id, [&](uint32_t c) {
            columns_[c].entries.push_back(e);
            columns_[c].max_len = std::max(columns_[c].max_len, e.hi - e.lo);
            queue(c);
        });
    }
    auto found = [&](uint32_t a, uint32_t b) {
        if (boxes_overlap(records_[a].box, records_[b].box)) overlaps_.insert(pair_key(a, b));
    };
    for (uint32_t c : queued_) {
        auto& v = columns_[c].entries;
        std::sort(v.begin(), v.end(), [](const Entry& x, const Entry& y) { return x.lo < y.lo || (x.lo == y.lo && x.id < y.id); });
        sweep_column(columns_[c], [&](uint32_t a, uint32_t b) { return (is_new(a) || is_new(b)) && !both_static(a, b); }, found);
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

void RegionSap::on_teleport(uint32_t id, const Aabb& old_box) {
    (void)old_box;
    // Drop its pairs: partners share one of its columns (or it is large: all of them).
    Member& m = members_[id];
    auto drop = [&](uint32_t other) {
        if (other != id) overlaps_.erase(pair_key(id, other));
    };
    if (m.large) {
        for (uint32_t other = 0; other < members_.size(); ++other) {
            if (members_[other].listed) drop(other);
        }
    } else {
        for_columns(id, [&](uint32_t c) {
            for (const Entry& e : columns_[c].entries) drop(e.id);
        });
        for (uint32_t l : large_) drop(l);
    }
    unlist(id);
    const Aabb& b = records_[id].box;
    list(id, b);
    std::erase(stale_, id);
    auto add = [&](uint32_t other) {
        if (other != id && members_[other].listed && !both_static(id, other) && boxes_overlap(b, records_[other].box))
            overlaps_.insert(pair_key(id, other));
    };
    if (m.large) {
        for (uint32_t other = 0; other < members_.size(); ++other) add(other);
    } else {
        for_columns(id, [&](uint32_t c) {
            for (const Entry& e : columns_[c].entries) add(e.id);
        });
        for (uint32_t l : large_) add(l);
    }
}

void RegionSap::on_step() {
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
        if (!moving_flag_[id] && records_[id].state == State::Live) rekeys_.push_back(id);
    }
    rekeys_.insert(rekeys_.end(), moving_.begin(), moving_.end());
    stale_.assign(moving_.begin(), moving_.end());
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
        if (8 * col.movers >= col.entries.size()) {
            col.max_len = 0;
            for (const Entry& e : col.entries) col.max_len = std::max(col.max_len, e.hi - e.lo);
            sweep_column(col, wanted, collect);
        } else {
            for (uint32_t k = 0; k < col.movers; ++k) query_column(col, column_movers_[col.first_mover + k]);
        }
    }
    queued_.clear();
    // The exact tests, with the records of a later candidate loaded ahead (they are scattered).
    constexpr std::size_t kAhead = 8;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
        if (i + kAhead < candidates_.size()) {
            __builtin_prefetch(&records_[candidates_[i + kAhead].first]);
            __builtin_prefetch(&records_[candidates_[i + kAhead].second]);
        }
        test_moving_pair(candidates_[i].first, candidates_[i].second);
    }
    for (uint32_t l : large_) {
        for (uint32_t id = 0; id < members_.size(); ++id) {
            if (id == l || !members_[id].listed || !(moving_flag_[l] || moving_flag_[id])) continue;
            if (members_[id].large && id < l) continue;
            test_moving_pair(l, id);
        }
    }
    for (uint64_t k : entered_) overlaps_.insert(k);
    for (uint32_t id : moving_) moving_flag_[id] = 0;
}

std::string RegionSap::check_invariants() const {
    std::string base = BroadPhase::check_invariants();
    if (!base.empty()) return base;
    std::ostringstream why;
    std::vector<uint32_t> present;
    collect_present(present);
    std::size_t entries = 0;
    for (const Column& c : columns_) {
        entries += c.entries.size();
        for (std::size_t i = 1; i < c.entries.size(); ++i) {
            const Entry& p = c.entries[i - 1];
            const Entry& q = c.entries[i];
            if (!(p.lo < q.lo || (p.lo == q.lo && p.id < q.id))) return "a column is not sorted";
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
        if (m.large) {
            if (!std::binary_search(large_.begin(), large_.end(), id)) return "large object missing from the list";
            continue;
        }
        if (m.y0 != cell(m.keyed.min.y) || m.y1 != cell(m.keyed.max.y) || m.z0 != cell(m.keyed.min.z) || m.z1 != cell(m.keyed.max.z)) {
            why << "object " << id << " has a stale column range";
            return why.str();
        }
        const Entry want = make_entry(id, m.keyed);
        for (int32_t cy = m.y0; cy <= m.y1; ++cy) {
            for (int32_t cz = m.z0; cz <= m.z1; ++cz) {
                ++expected_entries;
                const Column* c = find_column(cy, cz);
                const bool ok = c != nullptr && std::any_of(c->entries.begin(), c->entries.end(), [&](const Entry& e) {
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
    std::size_t expected = 0;
    for (std::size_t x = 0; x < present.size(); ++x) {
        for (std::size_t y = x + 1; y < present.size(); ++y) {
            const uint32_t a = present[x], b = present[y];
            if (both_static(a, b)) continue;
            const bool by_box = boxes_overlap(records_[a].box, records_[b].box);
            if (by_box != overlaps_.contains(pair_key(a, b))) {
                why << "pair " << a << "," << b << ": boxes overlap " << by_box << ", overlap set says " << !by_box;
                return why.str();
            }
            expected += by_box ? 1 : 0;
        }
    }
    if (expected != overlaps_.size()) {
        why << "overlap set holds " << overlaps_.size() << " pairs, brute force finds " << expected;
        return why.str();
    }
    return {};
}

// ---- References ------------------------------------------------------------------------------

// Objects present, as a sorted list of ids kept by each flush.
class ListedBroadPhase : public BroadPhase {
protected:
    explicit ListedBroadPhase(BroadPhaseKind kind) : BroadPhase(kind) {}
    void on_flush() override {
        std::size_t w = 0;
        for (uint32_t id : ids_) {
            if (records_[id].state != State::PendingRemove) ids_[w++] = id;
        }
        ids_.resize(w);
        ids_.insert(ids_.end(), pending_adds_.begin(), pending_adds_.end());
        std::sort(ids_.begin(), ids_.end());
    }
    void on_teleport(uint32_t, const Aabb&) override {}
    std::vector<uint32_t> ids_;
};

class BruteForceBroadPhase final : public ListedBroadPhase {
public:
    BruteForceBroadPhase() : ListedBroadPhase(BroadPhaseKind::BruteForce) {}

private:
    void on_step() override {
        for (std::size_t x = 0; x < ids_.size(); ++x) {
            const Record& ra = records_[ids_[x]];
            const SweptAabb sa{ra.box, ra.box_end};
            for (std::size_t y = x + 1; y < ids_.size(); ++y) {
                const Record& rb = records_[ids_[y]];
                if (ra.is_static && rb.is_static) continue;
                double t = 0;
                if (first_overlap_time(sa, SweptAabb{rb.box, rb.box_end}, &t)) pairs_.push_back({ids_[x], ids_[y], t});
            }
        }
    }
};

// The talks' simple solution: sweep and prune along x on the boxes swept over the whole step.
class EncapsulatingSap final : public ListedBroadPhase {
public:
    EncapsulatingSap() : ListedBroadPhase(BroadPhaseKind::EncapsulatingSap) {}

private:
    void on_step() override {
        swept_.resize(records_.size());
        for (uint32_t id : ids_) swept_[id] = union_box(records_[id].box, records_[id].box_end);
        order_ = ids_;
        std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
            return swept_[a].min.x != swept_[b].min.x ? swept_[a].min.x < swept_[b].min.x : a < b;
        });
        active_.clear();
        for (uint32_t id : order_) {
            const Aabb& box = swept_[id];
            std::size_t w = 0;
            for (uint32_t other : active_) {
                const Aabb& ob = swept_[other];
                if (ob.max.x < box.min.x) continue;  // closed off for good: the mins only grow
                active_[w++] = other;
                if (records_[id].is_static && records_[other].is_static) continue;
                if (!boxes_overlap(box, ob)) continue;
                double t = kInf;
                const SweptAabb sa{records_[id].box, records_[id].box_end};
                const SweptAabb sb{records_[other].box, records_[other].box_end};
                if (!first_overlap_time(sa, sb, &t)) t = kInf;
                pairs_.push_back({std::min(id, other), std::max(id, other), t});
            }
            active_.resize(w);
            active_.push_back(id);
        }
    }
    std::vector<Aabb> swept_;
    std::vector<uint32_t> order_, active_;
};

}  // namespace

// ---- Free functions ----------------------------------------------------------------------------

bool first_overlap_time(const SweptAabb& a, const SweptAabb& b, double* out_t) {
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

bool boxes_overlap(const Aabb& a, const Aabb& b) {
    for (int k = 0; k < 3; ++k) {
        if (a.min[k] > b.max[k] || b.min[k] > a.max[k]) return false;
    }
    return true;
}

uint64_t ordered_key(double x) {
    const auto u = std::bit_cast<uint64_t>(x + 0.0);  // + 0.0 turns -0.0 into +0.0
    return (u >> 63) != 0 ? ~u : u | (uint64_t{1} << 63);
}

// Sorts pairs by (a, b): an LSD radix sort on the 60-bit key a << 30 | b (ids are below 2^30),
// 12 bits per pass, stable; only as many passes as the largest key needs.
void sort_pairs(std::vector<BroadPhasePair>& pairs, std::vector<BroadPhasePair>& scratch) {
    if (pairs.size() < 64) {
        std::sort(pairs.begin(), pairs.end(), [](const BroadPhasePair& p, const BroadPhasePair& q) {
            return p.a != q.a ? p.a < q.a : p.b < q.b;
        });
        return;
    }
    auto key = [](const BroadPhasePair& p) { return (uint64_t{p.a} << 30) | p.b; };
    uint64_t largest = 0;
    for (const BroadPhasePair& p : pairs) largest = std::max(largest, key(p));
    scratch.resize(pairs.size());
    std::array<uint32_t, 4096> count{};
    for (unsigned shift = 0; shift < 64 && (largest >> shift) != 0; shift += 12) {
        count.fill(0);
        for (const BroadPhasePair& p : pairs) ++count[(key(p) >> shift) & 4095];
        uint32_t sum = 0;
        for (uint32_t& c : count) {
            const uint32_t n = c;
            c = sum;
            sum += n;
        }
        for (const BroadPhasePair& p : pairs) scratch[count[(key(p) >> shift) & 4095]++] = p;
        pairs.swap(scratch);
    }
}

// ---- BroadPhase --------------------------------------------------------------------------------

const char* to_string(BroadPhaseKind kind) {
    switch (kind) {
        case BroadPhaseKind::SpacetimeSap: return "spacetime_sap";
        case BroadPhaseKind::SpacetimeSapQueued: return "spacetime_sap_queued";
        case BroadPhaseKind::SpacetimeSapGlobal: return "spacetime_sap_global";
        case BroadPhaseKind::EncapsulatingSap: return "encapsulating_sap";
        case BroadPhaseKind::BruteForce: return "brute_force";
    }
    return "unknown";
}

std::unique_ptr<BroadPhase> BroadPhase::create(BroadPhaseKind kind) {
    switch (kind) {
        case BroadPhaseKind::SpacetimeSap: return std::make_unique<RegionSap>();
        case BroadPhaseKind::SpacetimeSapGlobal: return std::make_unique<SpacetimeSap>();
        case BroadPhaseKind::SpacetimeSapQueued: return std::make_unique<QueuedSpacetimeSap>();
        case BroadPhaseKind::EncapsulatingSap: return std::make_unique<EncapsulatingSap>();
        case BroadPhaseKind::BruteForce: return std::make_unique<BruteForceBroadPhase>();
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
    if (r.state == State::Live) on_teleport(id, old);
    return true;
}

bool BroadPhase::move(uint32_t id, const Aabb& box_end) {
    if (!contains(id) || !valid_box(box_end) || records_[id].is_static) return false;
    Record& r = records_[id];
    r.box_end = box_end;
    if (!r.moving) {
        r.moving = true;
        moving_.push_back(id);
    }
    return true;
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
            if (!valid_box(r.box) || !valid_box(r.box_end)) return "object " + std::to_string(id) + " has an invalid box";
            if (r.is_static && !same_box(r.box, r.box_end)) return "static object " + std::to_string(id) + " moves";
        }
    }
    if (live != live_count_) return "live count " + std::to_string(live_count_) + ", records say " + std::to_string(live);
    return {};
}

}  // namespace kairos
