// SPDX-License-Identifier: MIT
// Shape queries shared by every kind: bounds from support mappings.
#include <cmath>

#include "shapes/shape.hpp"

namespace kairos {

void bounds(const Shape& s, const Transform& pose, Vec3& out_min, Vec3& out_max) {
    // The extent along world axis e is e.support(e); the minimum is -(-e).support(-e).
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 e{};
        e[axis] = 1;
        const double hi = support(s, pose, e)[axis], lo = support(s, pose, -e)[axis];
        // Two separately rounded supports of a shape thinner than the rounding of its position
        // (a flat triangle far from the origin) may cross: the box is the pair's hull.
        out_max[axis] = std::fmax(hi, lo);
        out_min[axis] = std::fmin(hi, lo);
    }
}

}  // namespace kairos
