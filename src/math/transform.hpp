// SPDX-License-Identifier: MIT
// Rigid maps and poses: Transform, the map a pose stands for (rotation matrix and translation),
// used by every query; Pose, a body's position and orientation as the C API's kairos_pose gives
// them (world frame), from which a Transform is made once per query.
#pragma once

#include "math/math.hpp"

namespace kairos {

// Rigid transform x -> rotation * x + translation (rotation orthonormal).
struct Transform {
    Mat3 rotation;
    Vec3 translation;
    Vec3 apply(Vec3 x) const { return rotation * x + translation; }
    Vec3 apply_inverse(Vec3 x) const { return mul_transpose(rotation, x - translation); }
    Vec3 to_local_direction(Vec3 d) const { return mul_transpose(rotation, d); }
};
inline Transform make_transform(Vec3 position, Quat orientation) { return {to_matrix(orientation), position}; }

// Position and orientation of a body (the orientation kept as a unit quaternion, since motions
// interpolate it).
struct Pose {
    Vec3 position;
    Quat orientation;
};

// True when a and b are the same rotation bit for bit (q and -q alike). q_b * q_a^-1 would round
// to a turn by an angle near 1e-16 instead, and such a motion must take the exact translational
// path.
inline bool same_rotation(Quat a, Quat b) {
    return (a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w) ||
           (a.x == -b.x && a.y == -b.y && a.z == -b.z && a.w == -b.w);
}

}  // namespace kairos
