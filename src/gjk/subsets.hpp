// SPDX-License-Identifier: MIT
// Compile-time tables over the subsets of GJK's simplex (at most four points, a 4-bit mask per
// subset), shared by Johnson's sub-algorithm (simplex.hpp) and the cast's rebuild (casts/rebuild.hpp).
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <utility>

namespace kairos::gjk_detail {

// Subsets of a 4-bit mask ordered by size (smallest first), the empty set included; built at
// compile time. Johnson's test is tried on smaller sub-simplices first, and determinants of a
// subset are computed after those of its own subsets.
struct SubsetTable {
    uint8_t subsets[16][16] = {};
    uint8_t count[16] = {};
    constexpr SubsetTable() {
        for (unsigned m = 0; m < 16; ++m) {
            unsigned n = 0;
            for (int size = 0; size <= 4; ++size)
                for (unsigned s = 0; s < 16; ++s)
                    if ((s & ~m) == 0 && std::popcount(s) == size) subsets[m][n++] = static_cast<uint8_t>(s);
            count[m] = static_cast<uint8_t>(n);
        }
    }
};
inline constexpr SubsetTable kSubsets{};

// Number of points in a 4-bit mask (std::popcount compiles to a library call without -mpopcnt).
inline constexpr int kBitCount[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

// The array of make.template operator()<S>() for S = 0 .. N-1: a member's instantiations per subset
// (each with its loops over the points unrolled at compile time), indexed by a mask known only at
// run time.
template <unsigned N = 16, class Make>
constexpr auto per_subset(Make make) {
    return [&]<unsigned... M>(std::integer_sequence<unsigned, M...>) {
        return std::array{make.template operator()<M>()...};
    }(std::make_integer_sequence<unsigned, N>{});
}

}  // namespace kairos::gjk_detail
