// SPDX-License-Identifier: MIT
// The extreme-point searches that seed quickhull (see quickhull.hpp).
#include "shapes/quickhull.hpp"

#include <cmath>

namespace kairos::hull_detail {

uint32_t farthest_from_line(const std::vector<Vec3>& p, const std::vector<uint32_t>& ids, Vec3 a, Vec3 b,
                            double& out_dist) {
    const Vec3 u = normalized_or(b - a, {1, 0, 0});
    uint32_t best = ids[0];
    out_dist = -1;
    for (uint32_t i : ids) {
        const double dist = length(cross(p[i] - a, u));
        if (dist > out_dist) {
            out_dist = dist;
            best = i;
        }
    }
    return best;
}

uint32_t farthest_from_plane(const std::vector<Vec3>& p, const std::vector<uint32_t>& ids, uint32_t a, uint32_t b,
                             uint32_t c, double& out_det) {
    uint32_t best = ids[0];
    out_det = -1;
    for (uint32_t i : ids) {
        const double det = std::fabs(orient(p[a], p[b], p[c], p[i]).value);
        if (det > out_det) {
            out_det = det;
            best = i;
        }
    }
    return best;
}

}  // namespace kairos::hull_detail
