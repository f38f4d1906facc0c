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

// After the first support call (unscaled): the pair's scale from its support points, and those
// points, w and the margin brought to it (exact: a power of two). The search direction needs no
// scaling.
template <class Pair>
inline void set_scale(Pair& pair, Vec3& a, Vec3& b, Vec3& w, double& margin, double& margin_sq) {
    const double sc = kernels::first_scale(pair, a, b);
    if (sc == 1) return;
    kernels::adopt_scale(pair, sc, a, b, margin);
    w = a - b;
    margin_sq = margin * margin;
}

// v of norm^2 nv touches the origin: within rounding of it relative to the simplex's size
// (max_norm_sq), or within the cores' margin.
inline bool touching(double nv, double max_norm_sq, double margin_sq) {
    return nv <= kNearContact * max_norm_sq || nv <= margin_sq;
}

// The distance loop keeps its best lower bound as (v.w)^2 / ||v||^2 = num / den, with the w that
// gave it and the direction v along which that support call proved it. A bound within 2^-30 of
// the estimate's length needs no better proof (prove_by_faces) and its direction is the axis
// (proven_axis): kProvenShare is that fraction.
inline constexpr double kProvenShare = 1 - 0x1p-30;
//
// At a rounding stop (no progress, Johnson failed) of shapes without radii whose bound is not
// within 2^-30 of the estimate ||v||^2 = vv: the planes of the triangles among the last points
// (pool), each checked by one support call, may prove a better one. The triangle Johnson's
// determinants could not decide is typically on a face of A - B, with the foot on or near one
// of its edges (a rod's corner over the centre of a plate's face: the foot on the face's
// diagonal), and its plane is that face's.
template <class Pair>
void prove_by_faces(Pair& pair, const Simplex& s, unsigned pool, double vv, double& num, double& den, Vec3& lower_w,
                    Vec3& lower_v) {
    if (!(num < (kProvenShare * kProvenShare) * vv * den)) return;
    for (unsigned sub = 7; sub < 15u; ++sub) {
        if (kBitCount[sub] != 3 || (sub & ~pool) != 0) continue;
        int k[3], m = 0;
        for (unsigned r = sub; r; r &= r - 1) k[m++] = std::countr_zero(r);
        Vec3 n = cross(s.y[k[1]] - s.y[k[0]], s.y[k[2]] - s.y[k[0]]);
        if (dot(n, s.y[k[0]]) < 0) n = -n;  // toward the points, away from the origin
        n = normalized_or(n, Vec3{});
        if (!(dot(n, n) > 0)) continue;
        Vec3 a, b;
        const Vec3 w = pair(-n, a, b);
        const double h = dot(n, w);
        if (h > 0 && h * h * den > num) num = h * h, den = 1, lower_w = w, lower_v = n;
    }
}

// The axis to report for shapes without radii, at the end of a separated query whose final
// estimate s.v is of plain magnitude, after a rounding stop or when s changed after the last
// search direction (an earlier run's estimate kept, a sub-simplex taken for its coordinates):
// zero to report v's direction. At the usual ends v proved the bound itself (the relative-error
// rule along v, or a repeated support point, whose plane holds v's foot). v's direction is the
// distance's to the accuracy stated, but v may come from a sub-simplex whose coordinates
// reproduce the triangle's projection, or from an earlier run nearer by rounding, and lie beside
// the foot by that rounding, which tilts it by as much over the distance: a needle's tip 1e-6
// over the centre of a unit box's face (the foot on the face's diagonal, the triangle a sliver of
// two rim points 2e-6 apart and a corner) gave an edge whose direction was 4.6e-6 rad off, and
// the face's corners fell short along it by 4.6e-6. The best lower bound's direction is proven
// to separate the shapes by that bound: it is the axis when the bound is within 2^-30 of the
// distance. Otherwise, unless the relative-error rule ended the loop (its v proves the distance
// within the tolerance), v's own direction gets a support call too, and the one that proves more
// is the axis.
template <class Pair>
Vec3 proven_axis(Pair& pair, const Simplex& s, bool after_rule_1, double num, double den, Vec3 lower_v) {
    if (!(num > 0) || lower_v == s.v) return {};  // the usual end: v proved the bound itself
    const double nv = dot(s.v, s.v);
    if (num >= (kProvenShare * kProvenShare) * nv * den) return normalized_or(-lower_v, Vec3{});
    if (after_rule_1) return {};
    Vec3 a, b;
    const double hv = dot(s.v, pair(-s.v, a, b));
    const bool v_proves_more = hv > 0 && hv * hv * den > num * nv;
    return normalized_or(v_proves_more ? -s.v : -lower_v, Vec3{});
}

}  // namespace kairos::gjk_detail
