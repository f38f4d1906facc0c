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

}  // namespace kairos
