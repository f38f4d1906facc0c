// SPDX-License-Identifier: MIT
// The GJK distance loop's rounding rules (gjk.cpp; docs/algorithms.md §2): the check of an
// estimate against the proven lower bound, the test that a rounding-limit stop is the answer and
// its floor per kind of support, and the long double coordinates of a poorly conditioned full
// simplex.
#pragma once

#include <bit>
#include <cmath>

#include "gjk/simplex.hpp"
#include "gjk/support_kernels.hpp"

namespace kairos::gjk_detail {

// Coordinates of the origin in a full simplex again, in long double from the support points,
// when the double ones do not put it at the origin (within 2^-40 of the simplex's size). On a
// sliver (a needle 1e6 long across a slab 1e-10 thick) the signed volumes of the rounded y_i
// carry errors of eps L / h, and the common point sum lambda_i a_i then lay outside B by far
// more than B's thickness. long double has a 64-bit significand on x86-64 (113 bits on
// aarch64; on targets where it is double this changes nothing). Rare: intersecting queries
// whose tetrahedron is poorly conditioned.
inline void refine_full_coordinates(Simplex& s) {
    if (s.bits != 15u || s.coordinates_reproduce_v(0x1p-80)) return;
    using L = long double;
    L y3[4][3];
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) y3[i][k] = L(s.pa[i][k]) - L(s.pb[i][k]);
    auto triple = [](const L* p, const L* q, const L* r) {
        return p[0] * (q[1] * r[2] - q[2] * r[1]) + p[1] * (q[2] * r[0] - q[0] * r[2]) +
               p[2] * (q[0] * r[1] - q[1] * r[0]);
    };
    L e[3][3];
    for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) e[j][k] = y3[j + 1][k] - y3[0][k];
    const L vol[4] = {triple(y3[1], y3[2], y3[3]), -triple(y3[0], e[1], e[2]), -triple(e[0], y3[0], e[2]),
                      -triple(e[0], e[1], y3[0])};
    L sum = 0;
    for (const L& x : vol) sum += x;
    if (!(std::fabs(sum) > 0)) return;
    double refined[4];
    for (int i = 0; i < 4; ++i) {
        const L l = vol[i] / sum;
        refined[i] = l > 0 ? double(l) : 0.0;
    }
    for (int i = 0; i < 4; ++i) s.lambda[i] = refined[i];
}

// Which side's support points give an intersecting pair's common point. In exact arithmetic
// sum lambda_i a_i = sum lambda_i b_i; with coordinates off by delta, each side's point moves by
// delta times the spread of that side's points. A hull 1e9 across crossed by a cone 2000 long
// (fuzzing) left delta at 5e-7 even in long double: A's side put the point 1.4e3 along the hull,
// out of the cone, while B's stayed within 1e-3 of both shapes. The side whose points lie closer
// together is the accurate one; its point also lies in its shape exactly (a convex combination).
inline bool common_point_on_b(const Simplex& s) {
    const int first = std::countr_zero(s.bits | 16u) & 3;
    double spread_a = 0, spread_b = 0;
    for (unsigned r = s.bits; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        spread_a = std::fmax(spread_a, max_abs(s.pa[i] - s.pa[first]));
        spread_b = std::fmax(spread_b, max_abs(s.pb[i] - s.pb[first]));
    }
    return spread_b < spread_a;
}

// True when sqrt(nv) < sqrt(lower_sq) - E, with E = 16 eps ||w|| the rounding allowance of the bound
// (v.w carries an absolute error of a few eps ||v|| ||w||). Squares only: lower_sq - nv =
// (L - |v|)(L + |v|) and L + |v| <= 2L, so (lower_sq - nv)^2 > 4 lower_sq E^2 implies L - |v| > E.
inline bool below_lower_bound(double nv, double lower_sq, double w_norm_sq) {
    constexpr double k = 16 * 2.220446049250313e-16;
    const double d = lower_sq - nv;
    return d > 0 && d * d > 4 * lower_sq * (k * k * w_norm_sq);
}

// True when a stop on a rounding-limit rule (no progress, Johnson failed, repeated support) is the
// answer: the gap between the upper bound ||v|| and the best lower bound is within the tolerance,
// or within what rounding allows the lower bound v.w / ||v||. v carries an absolute error of some
// eps of the simplex's size S, which tilts it by that over ||v||, so along a face of A - B the
// bound can fall short by eps S^2 / ||v|| however many iterations follow: the test is
// gap ||v|| <= floor S^2, with floor 2^-46 (64 eps) for polytope cores, whose support points are
// exact, and 2^-40 when a core is curved or general (the rounding of v.w on rims, about 1e-11 of
// the size on cylinders). A larger gap means the simplex went bad by rounding while a nearer
// point is still to be found: the loop recovers instead of stopping. The allowance never exceeds
// 2^-30 (about 1e-9) of the size: near contact (||v|| small, lower bound 0) it would otherwise
// accept any ||v|| up to sqrt(floor) S.
inline bool settled(double vv, double lower_sq, double size_sq, double margin, double tolerance, double floor) {
    const double upper = std::sqrt(vv);
    const double gap = upper - std::sqrt(lower_sq);
    return (gap * upper <= floor * size_sq && gap * gap <= 0x1p-60 * size_sq) || gap <= tolerance * (upper - margin);
}

// The floor of settled() for a pair support: exact supports (points, segments, boxes, small
// hulls) on both sides, or not.
template <class Pair>
constexpr double settle_floor =
    kernels::exact_support<decltype(Pair::sa)>&& kernels::exact_support<decltype(Pair::sb)> ? 0x1p-46 : 0x1p-40;

}  // namespace kairos::gjk_detail
