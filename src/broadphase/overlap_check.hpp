// SPDX-License-Identifier: MIT
// The brute-force check of an overlap set, shared by the check_invariants of the broad phases
// that keep one (debug and tests only: O(n^2)). Internal to broadphase/ (namespace
// broadphase_detail).
#pragma once

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "broadphase/pair_set.hpp"

namespace kairos::broadphase_detail {

// Over every pair of `present` (ids into `records`) not both static: the pair is in `overlaps`
// exactly when its start boxes overlap, and `overlaps` holds nothing else. `per_pair(a, b,
// by_box, why)` adds a check of the pair (false: it wrote the fault to `why`). The empty string
// when all holds, else the first fault.
template <class Records, class PerPair>
std::string check_overlap_set(const std::vector<uint32_t>& present, const Records& records, const PairSet& overlaps,
                              PerPair per_pair) {
    std::ostringstream why;
    std::size_t expected = 0;
    for (std::size_t x = 0; x < present.size(); ++x) {
        for (std::size_t y = x + 1; y < present.size(); ++y) {
            const uint32_t a = present[x], b = present[y];
            if (records[a].is_static && records[b].is_static) continue;
            const bool by_box = boxes_overlap(records[a].box, records[b].box);
            if (!per_pair(a, b, by_box, why)) return why.str();
            if (by_box != overlaps.contains(pair_key(a, b))) {
                why << "pair " << a << "," << b << ": boxes overlap " << by_box << ", overlap set says " << !by_box;
                return why.str();
            }
            expected += by_box ? 1 : 0;
        }
    }
    if (expected != overlaps.size()) {
        why << "overlap set holds " << overlaps.size() << " pairs, brute force finds " << expected;
        return why.str();
    }
    return {};
}

}  // namespace kairos::broadphase_detail
