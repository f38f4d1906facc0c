// SPDX-License-Identifier: MIT
// Exact geometric predicates of the hull construction: orientation signs decided exactly (a
// floating-point filter, then floating-point expansions), and point distances used only for
// tolerance decisions. Internal to shapes/ (namespace hull_detail).
#pragma once

#include <cmath>

#include "math/math.hpp"

namespace kairos::hull_detail {

// det[b - a, c - a, q - a]: its exact sign and its value to within an ulp or two. Exact as long as
// no partial product underflows (coordinates are rescaled to magnitude < 1 first, so only
// differences below ~1e-100 could).
struct Orientation {
    double value;
    int sign;
};
Orientation orient_exact(Vec3 a, Vec3 b, Vec3 c, Vec3 q);

// det[b - a, c - a, q - a] (six times the signed volume; positive when q is above the plane of the
// counter-clockwise triangle a, b, c): its exact sign, and its value to within 0.1 %. Tolerance
// decisions divide the value by a face's area to get a distance; on a needle (a triangle 1e9
// times longer than wide) the rounded determinant can be all rounding, so where the filter
// leaves less than three correct digits the exact expansion gives the value too.
inline Orientation orient(Vec3 a, Vec3 b, Vec3 c, Vec3 q) {
    const Vec3 u = b - a, v = c - a, w = q - a;
    const double vywz = v.y * w.z, vzwy = v.z * w.y;
    const double vzwx = v.z * w.x, vxwz = v.x * w.z;
    const double vxwy = v.x * w.y, vywx = v.y * w.x;
    const double det = u.x * (vywz - vzwy) + u.y * (vzwx - vxwz) + u.z * (vxwy - vywx);
    const double permanent = std::fabs(u.x) * (std::fabs(vywz) + std::fabs(vzwy)) +
                             std::fabs(u.y) * (std::fabs(vzwx) + std::fabs(vxwz)) +
                             std::fabs(u.z) * (std::fabs(vxwy) + std::fabs(vywx));
    // Shewchuk's orient3d bound is (7 + 56 eps) eps * permanent with eps = 2^-53 (~7.8e-16);
    // 1e-15 covers it. Below 1e-280 the products may have lost bits to underflow: go exact.
    const double bound = 1e-15 * permanent;
    if (permanent > 1e-280 && std::fabs(det) > 1e3 * bound) return {det, det > 0 ? 1 : -1};
    return orient_exact(a, b, c, q);
}

// Exact sign of (a - o) x (b - o) in the plane (see hull_predicates.cpp).
int orient2d(double ox, double oy, double ax, double ay, double bx, double by);

// Distances (for tolerance decisions only; rounding here never shapes the mesh).
double point_segment_distance(Vec3 x, Vec3 a, Vec3 b);
double point_triangle_distance(Vec3 x, Vec3 a, Vec3 b, Vec3 c);

}  // namespace kairos::hull_detail
