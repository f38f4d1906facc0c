// SPDX-License-Identifier: MIT
// Box helpers of the broad phases, beside the public ones of broadphase.hpp that box_time.cpp
// defines too (first_overlap_time, boxes_overlap, ordered_key, sort_pairs). Internal to broadphase/
// (namespace broadphase_detail).
#pragma once

#include "broadphase/broadphase.hpp"

namespace kairos::broadphase_detail {

// True if every coordinate is finite and min <= max on every axis (false for NaN).
bool valid_box(const Aabb& b);

// The smallest box holding both.
Aabb union_box(const Aabb& a, const Aabb& b);

}  // namespace kairos::broadphase_detail
