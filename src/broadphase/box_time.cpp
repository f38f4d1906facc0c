// SPDX-License-Identifier: MIT
// Boxes and times: validity and union of boxes, the exact first overlap time of two swept boxes,
// the order-preserving key of a double, the radix sort of pairs.
#include "broadphase/box_time.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace kairos {

namespace broadphase_detail {

bool valid_box(const Aabb& b) {
    for (int k = 0; k < 3; ++k) {
        // Written so that NaN fails too.
        if (!(std::isfinite(b.min[k]) && std::isfinite(b.max[k]) && b.min[k] <= b.max[k])) return false;
    }
    return true;
}

// Boxes are finite (checked on entry), so plain comparisons serve (fmin/fmax are library calls).
Aabb union_box(const Aabb& a, const Aabb& b) {
    Aabb u;
    for (int k = 0; k < 3; ++k) {
        u.min[k] = std::min(a.min[k], b.min[k]);
        u.max[k] = std::max(a.max[k], b.max[k]);
    }
    return u;
}

}  // namespace broadphase_detail

uint64_t ordered_key(double x) {
    const auto u = std::bit_cast<uint64_t>(x + 0.0);  // + 0.0 turns -0.0 into +0.0
    return (u >> 63) != 0 ? ~u : u | (uint64_t{1} << 63);
}

// Sorts pairs by (a, b): an LSD radix sort on the 60-bit key a << 30 | b (ids are below 2^30),
// 12 bits per pass, stable; only as many passes as the largest key needs.
void sort_pairs(std::vector<BroadPhasePair>& pairs, std::vector<BroadPhasePair>& scratch) {
    if (pairs.size() < 64) {
        std::sort(pairs.begin(), pairs.end(),
                  [](const BroadPhasePair& p, const BroadPhasePair& q) { return p.a != q.a ? p.a < q.a : p.b < q.b; });
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

}  // namespace kairos
