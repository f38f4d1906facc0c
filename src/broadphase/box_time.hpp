// SPDX-License-Identifier: MIT
// Box helpers of the broad phases, beside the public ones of broadphase.hpp that box_time.cpp
// defines too (first_overlap_time, boxes_overlap, ordered_key, sort_pairs). Internal to broadphase/
// (namespace broadphase_detail).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "broadphase/pair_set.hpp"

namespace kairos::broadphase_detail {

// True if every coordinate is finite and min <= max on every axis (false for NaN).
bool valid_box(const Aabb& b);

// The smallest box holding both.
Aabb union_box(const Aabb& a, const Aabb& b);

}  // namespace kairos::broadphase_detail

namespace kairos {

// Inline: the sweeps call it once per candidate pair.
inline void BroadPhase::test_swept_pair(uint32_t a, uint32_t b, std::vector<uint64_t>& entered) {
    if (a > b) std::swap(a, b);
    ++counters_.crossing_tests;
    const Record& ra = records_[a];
    const Record& rb = records_[b];
    double t = 0;
    if (!first_overlap_time({ra.box, ra.box_end}, {rb.box, rb.box_end}, &t)) return;
    pairs_.push_back({a, b, t});
    if (boxes_overlap(ra.box_end, rb.box_end)) entered.push_back(broadphase_detail::pair_key(a, b));
}

}  // namespace kairos
