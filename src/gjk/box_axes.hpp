// SPDX-License-Identifier: MIT
// The separating axes of two boxes, shared by the closed-form distance (box_pair_distance.cpp)
// and the closed-form cast (casts/box_cast.cpp) so that both form each axis's offset and widths
// with the same operations. Box A (half extents ha) sits at the origin of its frame; box B (half
// extents hb) has axes the columns of m (m[r][c]: row r of column c) in that frame. abs_m holds
// |m| entrywise: for an exact rotation |L.e_k| and |L.b_k| of every axis below are its entries.
#pragma once

#include "math/math.hpp"

namespace kairos::box_axes {

// Both boxes' half widths summed along A's face normal e_i.
inline double face_a_width(const double (&ha)[3], const double (&hb)[3], const double (&abs_m)[3][3], int i) {
    return ha[i] + hb[0] * abs_m[i][0] + hb[1] * abs_m[i][1] + hb[2] * abs_m[i][2];
}
// Both boxes' half widths summed along B's face normal b_j.
inline double face_b_width(const double (&ha)[3], const double (&hb)[3], const double (&abs_m)[3][3], int j) {
    return hb[j] + ha[0] * abs_m[0][j] + ha[1] * abs_m[1][j] + ha[2] * abs_m[2][j];
}

// The edge axis L = e_i x b_j (not unit: |L| is the sine of the edges' angle). Its components
// are l1 at index i1 = i + 1 and l2 at i2 = i + 2 (mod 3), 0 at i.
struct EdgeAxis {
    double l1, l2, len_sq;
};
inline EdgeAxis edge_axis(const double (&m)[3][3], int i, int j) {
    const double l1 = -m[(i + 2) % 3][j], l2 = m[(i + 1) % 3][j];
    return {l1, l2, l1 * l1 + l2 * l2};
}
// The same axis as a vector (its component i +0).
inline Vec3 edge_axis_vector(const double (&m)[3][3], int i, int j) {
    const EdgeAxis l = edge_axis(m, i, j);
    Vec3 v{};
    v[(i + 1) % 3] = l.l1;
    v[(i + 2) % 3] = l.l2;
    return v;
}
// Both boxes' half widths summed along the edge axis e_i x b_j. Apart from the axis's test for
// parallel edges, which skips an axis before its widths are needed.
inline double edge_width(const double (&ha)[3], const double (&hb)[3], const double (&abs_m)[3][3], int i, int j) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    return ha[i1] * abs_m[i2][j] + ha[i2] * abs_m[i1][j] + hb[j1] * abs_m[i][j2] + hb[j2] * abs_m[i][j1];
}

// The midpoints of the two edges an edge axis's contact lies on, n along that axis from A toward
// B: A's edge along e_i farthest along n (A's frame), and B's along b_j farthest along -n, with
// B's axes the columns of rot and its centre at cb.
inline Vec3 edge_mid_a(Vec3 ha, int i, Vec3 n) {
    Vec3 a0{};
    for (int k = 0; k < 3; ++k)
        if (k != i) a0[k] = n[k] >= 0 ? ha[k] : -ha[k];
    return a0;
}
inline Vec3 edge_mid_b(Vec3 hb, const Mat3& rot, Vec3 cb, int j, Vec3 n) {
    Vec3 b0 = cb;
    for (int k = 0; k < 3; ++k)
        if (k != j) b0 += (dot(rot.col(k), n) > 0 ? -hb[k] : hb[k]) * rot.col(k);
    return b0;
}

}  // namespace kairos::box_axes
