// SPDX-License-Identifier: MIT
// Exact orientation predicates (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
// Robust Geometric Predicates", 1997) and the hull's point distances: see hull_predicates.hpp.
#include "shapes/hull_predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace kairos::hull_detail {

namespace {

// ---- Exact orientation ------------------------------------------------------------------------

// a + b = s + e exactly (Knuth's two-sum).
inline void two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bv = s - a;
    const double av = s - bv;
    e = (a - av) + (b - bv);
}
// a * b = p + e exactly (the fused multiply-add computes the rounding error exactly).
inline void two_product(double a, double b, double& p, double& e) {
    p = a * b;
    e = std::fma(a, b, -p);
}

// A nonoverlapping floating-point expansion in increasing magnitude, zeros removed. Its exact
// value is the sum of its components; its sign is that of its last (largest) component. Each
// add grows it by at most one component, and orient_exact adds 192 terms: 192 slots suffice.
struct Expansion {
    std::array<double, 192> c;
    int n = 0;
    // Shewchuk's Grow-Expansion: adds b exactly, keeps the expansion nonoverlapping.
    void add(double b) {
        double q = b;
        int out = 0;
        for (int i = 0; i < n; ++i) {
            double s, e;
            two_sum(q, c[static_cast<size_t>(i)], s, e);
            q = s;
            if (e != 0) c[static_cast<size_t>(out++)] = e;
        }
        if (q != 0) c[static_cast<size_t>(out++)] = q;
        n = out;
    }
    int sign() const { return n == 0 ? 0 : (c[static_cast<size_t>(n - 1)] > 0 ? 1 : -1); }
    // The value rounded (to within an ulp or two): components summed from the smallest.
    double approximate() const {
        double sum = 0;
        for (int i = 0; i < n; ++i) sum += c[static_cast<size_t>(i)];
        return sum;
    }
};

// Adds sign * x * y * z exactly, each factor given as a two-component exact value.
inline void add_triple(Expansion& acc, double sign, const double x[2], const double y[2], const double z[2]) {
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            double p, pe;
            two_product(x[i], y[j], p, pe);
            for (int k = 0; k < 2; ++k) {
                double q, qe, r, re;
                two_product(p, z[k], q, qe);
                two_product(pe, z[k], r, re);
                acc.add(sign * re);
                acc.add(sign * qe);
                acc.add(sign * r);
                acc.add(sign * q);
            }
        }
}

}  // namespace

Orientation orient_exact(Vec3 a, Vec3 b, Vec3 c, Vec3 q) {
    double u[3][2], v[3][2], w[3][2];
    for (int i = 0; i < 3; ++i) {
        two_sum(b[i], -a[i], u[i][0], u[i][1]);
        two_sum(c[i], -a[i], v[i][0], v[i][1]);
        two_sum(q[i], -a[i], w[i][0], w[i][1]);
    }
    // u . (v x w) as its six signed triple products.
    Expansion acc;
    add_triple(acc, +1, u[0], v[1], w[2]);
    add_triple(acc, -1, u[0], v[2], w[1]);
    add_triple(acc, +1, u[1], v[2], w[0]);
    add_triple(acc, -1, u[1], v[0], w[2]);
    add_triple(acc, +1, u[2], v[0], w[1]);
    add_triple(acc, -1, u[2], v[1], w[0]);
    return {acc.approximate(), acc.sign()};
}

// Exact sign of (a - o) x (b - o) in the plane: the filter bound is Shewchuk's orient2d error
// bound (3 + 16 eps) eps times the permanent, rounded up; below it, an exact expansion.
int orient2d(double ox, double oy, double ax, double ay, double bx, double by) {
    const double l = (ax - ox) * (by - oy), r = (ay - oy) * (bx - ox);
    const double det = l - r;
    const double bound = 1e-15 * (std::fabs(l) + std::fabs(r));
    if (std::fabs(l) + std::fabs(r) > 1e-280) {
        if (det > bound) return 1;
        if (det < -bound) return -1;
    }
    double u[2][2], v[2][2];  // the four differences, each exact as a two-component sum
    two_sum(ax, -ox, u[0][0], u[0][1]);
    two_sum(ay, -oy, u[1][0], u[1][1]);
    two_sum(bx, -ox, v[0][0], v[0][1]);
    two_sum(by, -oy, v[1][0], v[1][1]);
    const double one[2] = {1, 0};
    Expansion acc;
    add_triple(acc, +1, u[0], v[1], one);
    add_triple(acc, -1, u[1], v[0], one);
    return acc.sign();
}

double point_segment_distance(Vec3 x, Vec3 a, Vec3 b) {
    const Vec3 ab = b - a;
    const double len2 = length_sq(ab);
    const double t = len2 > 0 ? std::clamp(dot(x - a, ab) / len2, 0.0, 1.0) : 0.0;
    return length(x - (a + t * ab));
}

double point_triangle_distance(Vec3 x, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 n = cross(b - a, c - a);
    const double n2 = length_sq(n);
    if (n2 > 0 && dot(cross(b - a, x - a), n) >= 0 && dot(cross(c - b, x - b), n) >= 0 &&
        dot(cross(a - c, x - c), n) >= 0)
        return std::fabs(orient(a, b, c, x).value) / std::sqrt(n2);  // projects inside: the plane distance
    return std::min(
        {point_segment_distance(x, a, b), point_segment_distance(x, b, c), point_segment_distance(x, c, a)});
}

}  // namespace kairos::hull_detail
