// SPDX-License-Identifier: MIT
// Poses of the core's benchmarks as the C API takes them, so a benchmark can time the public
// functions on the same queries as the core (bench_gjk, bench_cast).
#pragma once

#include <cmath>

#include "kairos/kairos.h"
#include "math/transform.hpp"

// The unit quaternion of a rotation matrix (Shepperd: the largest of w, x, y, z taken first).
inline kairos_quat quat_of(const kairos::Mat3& m) {
    const double tr = m.r[0].x + m.r[1].y + m.r[2].z;
    if (tr > 0) {
        const double s = 2 * std::sqrt(tr + 1);
        return {(m.r[2].y - m.r[1].z) / s, (m.r[0].z - m.r[2].x) / s, (m.r[1].x - m.r[0].y) / s, s / 4};
    }
    if (m.r[0].x > m.r[1].y && m.r[0].x > m.r[2].z) {
        const double s = 2 * std::sqrt(1 + m.r[0].x - m.r[1].y - m.r[2].z);
        return {s / 4, (m.r[0].y + m.r[1].x) / s, (m.r[0].z + m.r[2].x) / s, (m.r[2].y - m.r[1].z) / s};
    }
    if (m.r[1].y > m.r[2].z) {
        const double s = 2 * std::sqrt(1 + m.r[1].y - m.r[0].x - m.r[2].z);
        return {(m.r[0].y + m.r[1].x) / s, s / 4, (m.r[1].z + m.r[2].y) / s, (m.r[0].z - m.r[2].x) / s};
    }
    const double s = 2 * std::sqrt(1 + m.r[2].z - m.r[0].x - m.r[1].y);
    return {(m.r[0].z + m.r[2].x) / s, (m.r[1].z + m.r[2].y) / s, s / 4, (m.r[1].x - m.r[0].y) / s};
}

inline kairos_pose c_pose(const kairos::Transform& t) {
    return {{t.translation.x, t.translation.y, t.translation.z}, quat_of(t.rotation)};
}
