// SPDX-License-Identifier: MIT
// The core's query results in the C layout, shared by the single queries (queries.cpp) and the
// batches (batch.cpp) so that both write the same bits.
#pragma once

#include <cmath>

#include "boundary.hpp"
#include "casts/cast.hpp"
#include "gjk/gjk.hpp"

namespace kairos::capi {

// Results must be finite before they are written (the last guard, see boundary.hpp). One sum
// decides the common case: finite parts below 1e101 cannot add up to an overflow, so a
// non-finite sum means a non-finite part, or (never in range) an overflow the full test clears.
inline bool is_finite_result(const DistanceResult& r) {
    // Summed as a tree, not a chain: the test's latency is four additions, not nine.
    const double sum = ((r.distance + r.point_a.x) + (r.point_a.y + r.point_a.z)) +
                       ((r.point_b.x + r.point_b.y) + (r.point_b.z + r.axis.x)) + (r.axis.y + r.axis.z);
    return std::isfinite(sum) ||
           (std::isfinite(r.distance) && is_finite(r.point_a) && is_finite(r.point_b) && is_finite(r.axis));
}
inline bool is_finite_result(const CastResult& r) {
    return std::isfinite(r.toi) && is_finite(r.point) && is_finite(r.normal);
}

inline void write_c(const DistanceResult& r, kairos_distance_result& out) {
    out.distance = r.distance;
    out.point_a = to_c(r.point_a);
    out.point_b = to_c(r.point_b);
    out.axis = to_c(r.axis);
    out.intersecting = r.intersecting ? 1 : 0;
    out.iterations = r.iterations;
    out.termination = static_cast<int32_t>(r.termination);
}

inline void write_c(const CastResult& r, kairos_cast_result& out) {
    out.hit = r.hit ? 1 : 0;
    out.toi = r.toi;
    out.point = to_c(r.point);
    out.normal = to_c(r.normal);
    out.iterations = r.iterations;
    out.termination = static_cast<int32_t>(r.termination);
}

}  // namespace kairos::capi
