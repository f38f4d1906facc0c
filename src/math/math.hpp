// SPDX-License-Identifier: MIT
// Small fixed-size linear algebra for the core: vectors, 3x3 matrices, quaternions, poses.
#pragma once

#include <cmath>
#include <cstdint>

namespace kairos {

struct Vec3 {
    double x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) { return {s * a.x, s * a.y, s * a.z}; }
constexpr Vec3 operator/(Vec3 a, double s) { return {a.x / s, a.y / s, a.z / s}; }
inline Vec3& operator+=(Vec3& a, Vec3 b) {
    a = a + b;
    return a;
}
inline Vec3& operator-=(Vec3& a, Vec3 b) {
    a = a - b;
    return a;
}
constexpr bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
constexpr double length_sq(Vec3 a) { return dot(a, a); }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
// std::fmax and std::fmin's results (a NaN argument is ignored; NaN only when both are) by
// comparisons: the library functions are calls here (no -ffinite-math-only), on hot paths.
inline double max_of(double a, double b) { return (a >= b || std::isnan(b)) ? a : b; }
inline double min_of(double a, double b) { return (a <= b || std::isnan(b)) ? a : b; }
inline double max_abs(Vec3 a) { return max_of(std::fabs(a.x), max_of(std::fabs(a.y), std::fabs(a.z))); }
// The power of two 2^-ilogb(m) that brings m (finite, > 0) into [1, 2): multiplying by it is
// exact unless the product under- or overflows, and keeps a vector's direction to the bit.
inline double unit_scale(double m) { return std::ldexp(1.0, -std::ilogb(m)); }
inline bool is_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
inline Vec3 cwise_min(Vec3 a, Vec3 b) { return {min_of(a.x, b.x), min_of(a.y, b.y), min_of(a.z, b.z)}; }
inline Vec3 cwise_max(Vec3 a, Vec3 b) { return {max_of(a.x, b.x), max_of(a.y, b.y), max_of(a.z, b.z)}; }

// Unit vector along a, computed without overflow or underflow (scaled by the largest component
// first). A zero vector gives fallback(), called only then (a fallback that is itself a
// normalisation costs six divisions and a square root).
template <class Fallback>
inline Vec3 normalized_or_else(Vec3 a, Fallback&& fallback) {
    // Plain comparisons, not max_abs (curved supports normalise on every call): a NaN component
    // gives NaN or the fallback, never a number.
    const double ax = std::fabs(a.x), ay = std::fabs(a.y), az = std::fabs(a.z);
    const double mxy = ax > ay ? ax : ay;
    const double m = az > mxy ? az : mxy;
    if (!(m > 0)) return fallback();  // also catches NaN
    const Vec3 s = a / m;
    return s / length(s);
}
// The same with a fallback already at hand.
inline Vec3 normalized_or(Vec3 a, Vec3 fallback) {
    return normalized_or_else(a, [&] { return fallback; });
}
// a / |a| given |a|^2 (one square root, one division); when a is zero or its square under- or
// overflows, the careful normalisation of a, then of `fallback`, then +x.
inline Vec3 unit_or(Vec3 a, double norm_sq, Vec3 fallback) {
    if (norm_sq > 1e-200 && norm_sq < 1e200) return (1 / std::sqrt(norm_sq)) * a;
    return normalized_or(a, normalized_or(fallback, {1, 0, 0}));
}

// normalized_or({x, y, 0}, {}) bit for bit, for supports that normalise only a radial part
// (cylinders, cones): the zero third component changes no rounding (0 / m and adding +0 are
// exact), so dropping it saves two of the six divisions on every call. A zero or NaN (x, y)
// gives what normalized_or gives.
struct Planar {
    double x, y;
};
inline Planar radial_unit(double x, double y) {
    const double ax = std::fabs(x), ay = std::fabs(y);
    const double m = ax > ay ? ax : ay;
    if (!(m > 0)) return {0, 0};
    const double sx = x / m, sy = y / m;
    const double l = std::sqrt(sx * sx + sy * sy);
    return {sx / l, sy / l};
}

// Row-major 3x3 matrix.
struct Mat3 {
    Vec3 r[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static constexpr Mat3 identity() { return {}; }
    constexpr Vec3 col(int j) const { return {r[0][j], r[1][j], r[2][j]}; }
};
constexpr Vec3 operator*(const Mat3& m, Vec3 v) { return {dot(m.r[0], v), dot(m.r[1], v), dot(m.r[2], v)}; }
// m^T * v without forming the transpose.
constexpr Vec3 mul_transpose(const Mat3& m, Vec3 v) { return m.r[0] * v.x + m.r[1] * v.y + m.r[2] * v.z; }
inline Mat3 operator*(const Mat3& a, const Mat3& b) {
    Mat3 c;
    for (int i = 0; i < 3; ++i) c.r[i] = mul_transpose(b, a.r[i]);
    return c;
}
inline Mat3 transpose(const Mat3& m) {
    Mat3 t;
    t.r[0] = {m.r[0].x, m.r[1].x, m.r[2].x};
    t.r[1] = {m.r[0].y, m.r[1].y, m.r[2].y};
    t.r[2] = {m.r[0].z, m.r[1].z, m.r[2].z};
    return t;
}
// a^T * b without forming the transpose (row i of the product is sum_k a[k][i] b[k]). Written out
// component by component: a transpose built in memory and read back by rows stalls on store
// forwarding, which cost a fifth of a box/box distance query.
inline Mat3 transpose_mul(const Mat3& a, const Mat3& b) {
    Mat3 c;
    c.r[0] = a.r[0].x * b.r[0] + a.r[1].x * b.r[1] + a.r[2].x * b.r[2];
    c.r[1] = a.r[0].y * b.r[0] + a.r[1].y * b.r[1] + a.r[2].y * b.r[2];
    c.r[2] = a.r[0].z * b.r[0] + a.r[1].z * b.r[1] + a.r[2].z * b.r[2];
    return c;
}
inline double determinant(const Mat3& m) { return dot(m.r[0], cross(m.r[1], m.r[2])); }

struct Quat {
    double x = 0, y = 0, z = 0, w = 1;
};
inline Quat operator*(Quat a, Quat b) {
    return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
inline double norm(Quat q) { return std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w); }
inline Quat normalized(Quat q) {
    const double n = norm(q);
    return {q.x / n, q.y / n, q.z / n, q.w / n};
}
// Rotation matrix of a unit quaternion.
inline Mat3 to_matrix(Quat q) {
    const double xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    const double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
    const double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    Mat3 m;
    m.r[0] = {1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy)};
    m.r[1] = {2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx)};
    m.r[2] = {2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)};
    return m;
}

inline Quat conjugate(Quat q) { return {-q.x, -q.y, -q.z, q.w}; }

// Rotation by `angle` radians about unit `axis`.
inline Quat axis_angle(Vec3 axis, double angle) {
    const double s = std::sin(0.5 * angle);
    return {axis.x * s, axis.y * s, axis.z * s, std::cos(0.5 * angle)};
}

}  // namespace kairos
