// SPDX-License-Identifier: MIT
// The expander's ranking of its near faces (gjk/near_ranking.hpp) against the list it stands in
// for (expander.hpp's keep_near and its scan, written again here as the model), driven through
// the protocol the expander follows: faces put as they are made, the ranking started on a list,
// least-two queries with resolutions in between, expansions that rewrite, free and add slots, and
// the end of each step with a falling upper bound. The capacity is small, so that the heap fills
// and is rebuilt from the live faces many times; keys come from a coarse grid, so that ties
// (decided by the order faces entered the list) are common; and the bound sometimes falls below
// every key (no face near: both scan every face). Penetration.RankedNearFacesAreTheListsChoice
// checks whole expansions; this reaches the paths they seldom take.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "gjk/near_ranking.hpp"

namespace {

using kairos::epa_detail::NearRanking;

constexpr int kFaces = 24;  // the ranking's capacity: its heap holds 2 * kFaces entries

// The expander's scan for the least and second least key (strict comparisons, in the order given:
// a tie goes to the face met first).
void scan_least_two(const std::vector<int>& order, const double* key, int& first, int& second) {
    int f1 = order[0], f2 = -1;
    double m1 = key[f1], m2 = INFINITY;
    for (size_t j = 1; j < order.size(); ++j) {
        const int i = order[j];
        const double k = key[i];
        if (k < m1) {
            f2 = f1, m2 = m1, f1 = i, m1 = k;
        } else if (k < m2) {
            f2 = i, m2 = k;
        }
    }
    first = f1;
    second = f2;
}

std::vector<int> all_faces(int nf) {
    std::vector<int> order(size_t(nf), 0);
    for (int i = 0; i < nf; ++i) order[size_t(i)] = i;
    return order;
}

}  // namespace

TEST(NearRanking, PicksTheListsFacesThroughRebuildsTiesAndResolutions) {
    const uint64_t seed = 4411;
    std::mt19937_64 rng(seed);
    auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    auto grid_key = [&] { return 0.125 * pick(0, 40); };
    int queries = 0, mismatches = 0, steps = 0, empty_steps = 0, rebuilds = 0;
    int first_resolved_above = 0, second_resolved_above = 0, no_second = 0;
    auto mismatch = [&](int sequence, int step, const char* what, int got1, int got2, int want1, int want2) {
        if (++mismatches <= 10)
            ADD_FAILURE() << "seed " << seed << " sequence " << sequence << " step " << step << ": " << what << " ("
                          << got1 << ", " << got2 << ") where the list gives (" << want1 << ", " << want2 << ")";
    };
    for (int sequence = 0; sequence < 400; ++sequence) {
        double key[kFaces];
        bool resolved[kFaces];
        NearRanking<kFaces> ranking;
        int nf = pick(8, 16);
        std::vector<int> free_slots;
        for (int s = 0; s < nf; ++s) {
            key[s] = grid_key();
            resolved[s] = false;
            ranking.put(s, key);
        }
        // upper: C's smallest support value. It falls towards the depth (2.5 here), which is at
        // least every least key, but now and then rounding puts it below every key: from then on
        // no face is near.
        double upper = 4.5;
        std::vector<int> list;  // keep_near's first list: the faces at most upper, by slot
        for (int i = 0; i < nf; ++i)
            if (key[i] <= upper) list.push_back(i);
        std::vector<int16_t> near16(list.begin(), list.end());
        ranking.start(key, nf, near16.data(), int(near16.size()), upper);
        auto push = [&] { rebuilds += ranking.entries() == 2 * kFaces; };  // this push rebuilds
        for (int step = 0; step < 80; ++step) {
            ++steps;
            const bool empty = list.empty();
            empty_steps += empty;
            if (ranking.empty() != empty) mismatch(sequence, step, "emptiness", ranking.empty(), 0, empty, 0);
            // The expander's least_two with and without the ranking, then a resolution, until the
            // least is a resolved face.
            int f = -1;
            for (int round = 0; round < kFaces; ++round) {
                int got1 = -1, got2 = -1, want1 = -1, want2 = -1;
                if (ranking.empty() || !ranking.least_two(key, got1, got2))
                    scan_least_two(all_faces(nf), key, got1, got2);
                scan_least_two(empty ? all_faces(nf) : list, key, want1, want2);
                ++queries;
                if (got1 != want1 || got2 != want2) mismatch(sequence, step, "least two", got1, got2, want1, want2);
                first_resolved_above += !empty && key[want1] > upper;
                second_resolved_above += !empty && want2 >= 0 && key[want2] > upper;
                no_second += want2 < 0;
                f = want1;
                if (resolved[f]) break;
                const double was = key[f];
                key[f] += 0.125 * pick(0, 3);  // resolving raises a key, or leaves it
                resolved[f] = true;
                if (ranking.on() && key[f] != was) push();
                ranking.resolved(f, key[f] != was, key);
            }
            // An expansion from face f: the visible faces (f and a few others) give way to nh new
            // ones, in the visible slots, then freed ones, then new slots; spare visible slots are
            // freed. It is refused when the faces would not fit.
            std::vector<int> visible{f};
            for (int extra = pick(0, 5); extra > 0; --extra) {
                const int g = pick(0, nf - 1);
                if (key[g] < INFINITY && std::find(visible.begin(), visible.end(), g) == visible.end())
                    visible.push_back(g);
            }
            const int nh = pick(std::max(1, int(visible.size()) - 1), int(visible.size()) + 1);
            if (int(free_slots.size() + visible.size()) + (kFaces - nf) < nh) break;
            std::vector<int> written;
            for (int i = 0; i < nh; ++i) {
                int slot;
                if (i < int(visible.size())) {
                    slot = visible[size_t(i)];
                } else if (!free_slots.empty()) {
                    slot = free_slots.back();
                    free_slots.pop_back();
                } else {
                    slot = nf++;
                }
                written.push_back(slot);
            }
            for (size_t h = size_t(nh); h < visible.size(); ++h) {
                free_slots.push_back(visible[h]);
                key[visible[h]] = INFINITY;
            }
            const double base = key[f];
            for (const int slot : written) {
                // New faces lie beyond the one expanded: some towards the origin, whose keys stay
                // at most the depth (the least key is a lower bound of it), some on C's far side.
                key[slot] = base + 0.125 * pick(0, 20);
                if (pick(0, 1) == 0) key[slot] = std::min(key[slot], 2.5);
                resolved[slot] = false;
                push();
                ranking.put(slot, key);
            }
            upper = pick(0, 299) == 0 ? std::min(upper, *std::min_element(key, key + nf) - 0.125)
                                      : std::max(std::min(upper, 2.5), upper - 0.125 * pick(0, 2));
            // keep_near: the listed faces not rewritten and still at most upper, then the new ones.
            std::vector<int> next;
            for (const int i : list)
                if (std::find(written.begin(), written.end(), i) == written.end() && key[i] <= upper) next.push_back(i);
            for (const int w : written)
                if (key[w] <= upper) next.push_back(w);
            list = next;
            ranking.step_end(key, nf, upper);
        }
    }
    std::printf(
        "near ranking: %d queries over %d steps (%d with no face near), %d heap rebuilds; the least a "
        "resolved face above the bound %d times, the runner-up %d times, none %d times\n",
        queries, steps, empty_steps, rebuilds, first_resolved_above, second_resolved_above, no_second);
    EXPECT_EQ(mismatches, 0);
    // Every path is taken, and often: rebuilds of a full heap, the least and the runner-up found
    // among the faces resolved in the step, no runner-up, and steps where no face is near.
    EXPECT_GT(rebuilds, 200) << "seed " << seed;
    EXPECT_GT(first_resolved_above, queries / 50) << "seed " << seed;
    EXPECT_GT(second_resolved_above, queries / 50) << "seed " << seed;
    EXPECT_GT(no_second, 20) << "seed " << seed;
    EXPECT_GT(empty_steps, steps / 50) << "seed " << seed;
    EXPECT_LT(empty_steps, steps / 2) << "seed " << seed;
}
