// SPDX-License-Identifier: MIT
// Shared by the rigid placement tests: long double maps of the doubles a query sees, and the
// placements they draw from.
#pragma once

#include <random>

#include "gjk_test_support.hpp"
#include "math/math.hpp"
#include "oracle/polytope_oracle.hpp"

namespace rigid_test {

// m x + t in long double from m's and t's doubles.
inline oracle::P3 map(const kairos::Mat3& m, oracle::P3 x, kairos::Vec3 t) {
    using oracle::Real;
    const Real tv[3] = {t.x, t.y, t.z};
    Real o[3];
    for (int i = 0; i < 3; ++i) o[i] = Real(m.r[i].x) * x.x + Real(m.r[i].y) * x.y + Real(m.r[i].z) * x.z + tv[i];
    return {o[0], o[1], o[2]};
}

// k = 0: the identity; 1: an exact quarter turn about z; else a random rotation.
inline kairos::Mat3 placement_rotation(std::mt19937_64& rng, int k) {
    if (k == 0) return kairos::Mat3::identity();
    if (k == 1) {
        kairos::Mat3 m;
        m.r[0] = {0, -1, 0};
        m.r[1] = {1, 0, 0};
        m.r[2] = {0, 0, 1};
        return m;
    }
    return kairos::to_matrix(gjk_test::random_quat(rng));
}

}  // namespace rigid_test
