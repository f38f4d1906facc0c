// Shape queries shared by every kind: bounds from support mappings.
#include "shape.hpp"

namespace kairos {

void bounds(const Shape& s, const Pose& pose, Vec3& out_min, Vec3& out_max) {
    // The extent along world axis e is e.support(e); the minimum is -(-e).support(-e).
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 e{};
        e[axis] = 1;
        out_max[axis] = support(s, pose, e)[axis];
        out_min[axis] = support(s, pose, -e)[axis];
    }
}

}  // namespace kairos
