// SPDX-License-Identifier: MIT
// A large expanding polytope's near faces (gjk/expander.hpp, keep_near; docs/algorithms.md §2b):
// the faces whose key was at most upper (C's smallest support value seen) when the last expansion
// step ended, and those resolved since, found in a binary heap over every face by (key, age).
// The age is the order in which faces entered the expander's list of near faces, so the heap
// picks the face the list's scan picks, ties included. Entries go stale rather than being removed
// (a face rewritten, freed or resolved to a larger key is pushed anew), and a step costs the
// logarithm of the polytope, not its size: a near-concentric pair of curved shapes, whose depth is
// reached along a whole circle of axes, keeps most of its hundreds of faces near, and the scans
// over them made its expansion quadratic (world steps doing thousands of them, found by fuzzing
// the world). Keys are read from the expander's array (any indexable of doubles).
#pragma once

#include <cmath>
#include <cstdint>

namespace kairos::epa_detail {

// MaxF: the expander's face capacity (1 for an expander that never ranks).
template <int MaxF>
class NearRanking {
public:
    bool on() const { return on_; }
    // The heap's entries, stale ones included (for tests: it is rebuilt when full, at 2 MaxF).
    int entries() const { return n_rank_; }
    // No face was near when the step began: the expander scans every face instead.
    bool empty() const { return empty_; }

    // Slot s holds a new face (key[s] set).
    template <class Keys>
    void put(int s, const Keys& key) {
        nf_ = s < nf_ ? nf_ : s + 1;  // new slots are put in increasing order: all below are faces
        seq_[s] = next_seq_++;
        stamp_[s] = 0;  // step_ is at least 1 once on
        if (on_) rank(s, key);
    }
    // From here on: the list's faces take its order as their age, the others (all above upper)
    // come after.
    template <class Keys>
    void start(const Keys& key, int nf, const int16_t* near, int n_near, double upper) {
        nf_ = nf;
        for (int i = 0; i < nf; ++i) seq_[i] = uint32_t(n_near + i), stamp_[i] = 0;
        for (int j = 0; j < n_near; ++j) seq_[near[j]] = uint32_t(j);
        next_seq_ = uint32_t(n_near + nf);
        on_ = true;
        rank_all(key);
        step_end(key, nf, upper);
    }
    // After each expansion step: the near faces are those at most upper.
    template <class Keys>
    void step_end(const Keys& key, int nf, double upper) {
        nf_ = nf;
        upper_ = upper;
        ++step_;
        n_resolved_ = 0;
        drop_stale(key);
        empty_ = n_rank_ == 0 || !(rank_[0].key <= upper);
    }
    // Face f was resolved, its key now key[f] (grew: larger than before): near for the rest of
    // the step. A NaN key is not ranked: it is never least.
    template <class Keys>
    void resolved(int f, bool grew, const Keys& key) {
        stamp_[f] = step_;
        resolved_[n_resolved_++] = int16_t(f);
        if (grew && !std::isnan(key[f])) rank(f, key);
    }
    // The least and the runner-up near faces (second -1: none); false when none is near.
    template <class Keys>
    bool least_two(const Keys& key, int& first, int& second) {
        drop_stale(key);
        if (n_rank_ == 0 || !near(rank_[0].face, key)) {
            // Only faces resolved in this step are near: the others near lie at most upper, below it.
            first = least_resolved(-1, key);
            if (first < 0) return false;
            second = least_resolved(first, key);
            return true;
        }
        const Ranked top = rank_[0];
        first = top.face;
        unrank_top();
        drop_stale(key);
        second = n_rank_ > 0 && near(rank_[0].face, key) ? rank_[0].face : least_resolved(first, key);
        rank(first, key);
        return true;
    }
    // A copy of another expander's ranking for nf faces (its heap's stale entries left behind).
    template <int M, class Keys>
    void take(const NearRanking<M>& from, const Keys& key, int nf) {
        on_ = from.on_, empty_ = from.empty_, upper_ = from.upper_, step_ = from.step_;
        next_seq_ = from.next_seq_, nf_ = nf;
        if (!on_) return;
        for (int i = 0; i < nf; ++i) seq_[i] = from.seq_[i], stamp_[i] = from.stamp_[i];
        n_resolved_ = from.n_resolved_;
        for (int i = 0; i < n_resolved_; ++i) resolved_[i] = from.resolved_[i];
        rank_all(key);
    }

private:
    template <int>
    friend class NearRanking;
    struct Ranked {
        double key;
        uint32_t seq;
        int16_t face;
    };
    static constexpr int kCap = 2 * MaxF;  // full: rebuilt from the live faces (fewer than MaxF)
    static bool before(double ka, uint32_t sa, double kb, uint32_t sb) { return ka < kb || (ka == kb && sa < sb); }
    static bool before(const Ranked& a, const Ranked& b) { return before(a.key, a.seq, b.key, b.seq); }
    template <class Keys>
    bool live(const Ranked& e, const Keys& key) const {
        return e.seq == seq_[e.face] && e.key == key[e.face];
    }
    template <class Keys>
    bool near(int f, const Keys& key) const {
        return stamp_[f] == step_ || key[f] <= upper_;
    }
    template <class Keys>
    void rank(int f, const Keys& key) {
        if (n_rank_ == kCap) return rank_all(key);  // which ranks f as it is now
        int at = n_rank_++;
        const Ranked e{key[f], seq_[f], int16_t(f)};
        while (at > 0) {
            const int parent = (at - 1) / 2;
            if (!before(e, rank_[parent])) break;
            rank_[at] = rank_[parent];
            at = parent;
        }
        rank_[at] = e;
    }
    template <class Keys>
    void rank_all(const Keys& key) {
        n_rank_ = 0;
        for (int i = 0; i < nf_; ++i)
            if (key[i] < INFINITY) rank(i, key);
    }
    void unrank_top() {
        const Ranked e = rank_[--n_rank_];
        int at = 0;
        for (;;) {
            int child = 2 * at + 1;
            if (child >= n_rank_) break;
            if (child + 1 < n_rank_ && before(rank_[child + 1], rank_[child])) ++child;
            if (!before(rank_[child], e)) break;
            rank_[at] = rank_[child];
            at = child;
        }
        if (n_rank_ > 0) rank_[at] = e;
    }
    template <class Keys>
    void drop_stale(const Keys& key) {
        while (n_rank_ > 0 && !live(rank_[0], key)) unrank_top();
    }
    // The least of the faces resolved in this step other than `except`, by key and age; -1: none.
    template <class Keys>
    int least_resolved(int except, const Keys& key) const {
        int best = -1;
        for (int j = 0; j < n_resolved_; ++j) {
            const int f = resolved_[j];
            if (f != except && (best < 0 || before(key[f], seq_[f], key[best], seq_[best]))) best = f;
        }
        return best;
    }

    bool on_ = false, empty_ = false;
    double upper_ = INFINITY;
    uint32_t step_ = 0, next_seq_ = 0;
    int nf_ = 0;
    // Written before read, and left uninitialised (no zeroing): seq_ and stamp_ by put or start,
    // the heap up to n_rank_, resolved_ up to n_resolved_.
    uint32_t seq_[MaxF];    // age: the order faces entered the near faces
    uint32_t stamp_[MaxF];  // == step_: resolved in this step
    Ranked rank_[kCap];
    int16_t resolved_[MaxF];
    int n_rank_ = 0, n_resolved_ = 0;
};

}  // namespace kairos::epa_detail
