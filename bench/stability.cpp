// SPDX-License-Identifier: MIT
// Stability catalogue (issue 12, item 3): families of hard cases run through every method, Kairos
// (through the public C API, kairos.h) and its peers (libccd, FCL, Bullet f64), with failure rates
// per method and family against exact truths:
//   - pair distance and intersection: the long-double polytope oracle (tests/support/oracle) on the shapes'
//     cores (polytope, segment or point) minus the radii, from the very doubles each method is given;
//   - translational casts and rays: the long-double cast oracle (tests/support/oracle/cast_oracle.hpp);
//   - rotating motions (a rod, box or capsule, against a ball): conservative advancement on the
//     exact point-to-core distance in long double (never skips a contact), see motion_truth().
// Every method call runs in a forked child (one child per method and family, restarted after a
// crash or hang), so a peer that aborts or loops costs failures, never the run.
//
// Usage: bench_stability [CSV]   (CSV defaults to bench/results/stability.csv under the cwd)
// Exit status: 0, or 2 when a family is one-sided (no judged case of one outcome).
#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <ccd/ccd.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include "kairos/kairos.h"
#include "oracle/cast_oracle.hpp"
#include "oracle/polytope_oracle.hpp"

namespace {

using oracle::P3;
using oracle::Real;

// ---- The bounds (identical for every method; stated in the README) ------------------------------
constexpr double kDistanceBound = 1e-9;  // |distance - truth| / size
constexpr double kBand = 1e-9;           // verdicts judged only when |gap| > kBand * size
constexpr double kLateBound = 1e-9;      // toi later than the truth by more than this (fraction of the step)
constexpr double kCaseTimeout = 3.0;     // seconds per case before it counts as a hang
constexpr int kMaxDeathsPerBatch = 6;    // crashes + hangs before the rest of a batch counts as failed

// ---- Shapes and poses (double: what every method is given) --------------------------------------
enum class Kind { Box, Hull, Sphere, Capsule, Cylinder };
using V3 = std::array<double, 3>;

struct Shape {
    Kind kind = Kind::Box;
    double a = 0, b = 0, c = 0;  // box half extents; sphere radius a; capsule, cylinder: radius a, half height b
    std::vector<V3> pts;         // hull points (local frame)
    int grid = 0;                // > 0: pts is the surface grid (grid^3 lattice) of the box a, b, c
};

struct Pose {
    V3 p{0, 0, 0};
    std::array<double, 4> q{0, 0, 0, 1};  // x y z w, unit
};

template <class T>
std::array<T, 9> quat_matrix(const std::array<double, 4>& qd) {
    T x = qd[0], y = qd[1], z = qd[2], w = qd[3];
    const T n = std::sqrt(x * x + y * y + z * z + w * w);
    x /= n, y /= n, z /= n, w /= n;
    return {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
            2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
}

V3 mul(const std::array<double, 9>& r, V3 v) {
    return {r[0] * v[0] + r[1] * v[1] + r[2] * v[2], r[3] * v[0] + r[4] * v[1] + r[5] * v[2],
            r[6] * v[0] + r[7] * v[1] + r[8] * v[2]};
}
V3 mul_t(const std::array<double, 9>& r, V3 v) {
    return {r[0] * v[0] + r[3] * v[1] + r[6] * v[2], r[1] * v[0] + r[4] * v[1] + r[7] * v[2],
            r[2] * v[0] + r[5] * v[1] + r[8] * v[2]};
}
V3 add(V3 a, V3 b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 scl(double s, V3 a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot3(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross3(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double len3(V3 a) { return std::sqrt(dot3(a, a)); }
V3 unit(V3 a) { return scl(1 / len3(a), a); }
double sgn(double v) { return v < 0 ? -1.0 : 1.0; }

// Support point in the local frame (test-side, double): the placement of cases and libccd's mapping.
V3 support_local(const Shape& s, V3 d) {
    const double l = len3(d);
    switch (s.kind) {
        case Kind::Box:
            return {sgn(d[0]) * s.a, sgn(d[1]) * s.b, sgn(d[2]) * s.c};
        case Kind::Sphere:
            return l > 0 ? scl(s.a / l, d) : V3{0, 0, s.a};
        case Kind::Capsule: {
            const V3 r = l > 0 ? scl(s.a / l, d) : V3{0, 0, s.a};
            return {r[0], r[1], r[2] + sgn(d[2]) * s.b};
        }
        case Kind::Cylinder: {
            const double rho = std::sqrt(d[0] * d[0] + d[1] * d[1]);
            const V3 r = rho > 0 ? V3{s.a * d[0] / rho, s.a * d[1] / rho, 0} : V3{s.a, 0, 0};
            return {r[0], r[1], sgn(d[2]) * s.b};
        }
        case Kind::Hull: {
            size_t best = 0;
            double bv = -INFINITY;
            for (size_t i = 0; i < s.pts.size(); ++i)
                if (dot3(d, s.pts[i]) > bv) bv = dot3(d, s.pts[i]), best = i;
            return s.pts[best];
        }
    }
    return {};
}
V3 support_world(const Shape& s, const Pose& p, V3 d) {
    const auto r = quat_matrix<double>(p.q);
    return add(mul(r, support_local(s, mul_t(r, d))), p.p);
}

// Bounding radius about the local origin: the "size" of the bounds.
double radius(const Shape& s) {
    switch (s.kind) {
        case Kind::Box:
            return std::sqrt(s.a * s.a + s.b * s.b + s.c * s.c);
        case Kind::Sphere:
            return s.a;
        case Kind::Capsule:
            return s.a + s.b;
        case Kind::Cylinder:
            return std::sqrt(s.a * s.a + s.b * s.b);
        case Kind::Hull: {
            double r = 0;
            for (const V3& q : s.pts) r = std::max(r, len3(q));
            return r;
        }
    }
    return 0;
}

Shape box(double a, double b, double c) { return {Kind::Box, a, b, c, {}, 0}; }
Shape sphere(double r) { return {Kind::Sphere, r, 0, 0, {}, 0}; }
Shape capsule(double r, double h) { return {Kind::Capsule, r, h, 0, {}, 0}; }
Shape cylinder(double r, double h) { return {Kind::Cylinder, r, h, 0, {}, 0}; }
Shape hull(std::vector<V3> pts) { return {Kind::Hull, 0, 0, 0, std::move(pts), 0}; }
// The points of an n x n x n lattice on the surface of the box [-a,a]x[-b,b]x[-c,c]: a hull of
// n^3 - (n-2)^3 points whose hull is exactly the box (corners included, every point on a face).
Shape grid_box(double a, double b, double c, int n) {
    Shape s{Kind::Hull, a, b, c, {}, n};
    auto coord = [n](int i, double h) { return i == 0 ? -h : i == n - 1 ? h : -h + 2 * h * i / (n - 1); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k)
                if (i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1)
                    s.pts.push_back({coord(i, a), coord(j, b), coord(k, c)});
    return s;
}

// ---- Cases -------------------------------------------------------------------------------------
enum class QType { Pair, Cast, Ray, Motion };

struct Truth {
    double size = 1;
    // Pair: signed distance (exact when >= 0, minus the penetration depth when known), depth.
    Real dist = 0;
    bool depth_known = false;
    Real depth = 0;
    // Cast, ray, motion.
    bool hit = false, grazing = false, decided = true;
    Real toi = 1;
};

struct Case {
    QType type = QType::Pair;
    Shape A, B;                   // Ray: A is the shape, B unused
    Pose pa, pb;                  // start poses (Ray: pb.p is the origin)
    Pose pa1, pb1;                // Motion: end poses
    V3 ta{0, 0, 0}, tb{0, 0, 0};  // Cast: translations; Ray: tb is the ray's translation
    Truth truth;
};

// ---- Exact truths (long double) ----------------------------------------------------------------
P3 lp(V3 v) { return {Real(v[0]), Real(v[1]), Real(v[2])}; }

// The core of a posed shape, in a frame shifted by -shift (exact: doubles subtracted in long double).
struct Core {
    oracle::Polytope poly;  // polytopes: faces; points and segments: vertices (and the edge) only
    int dim = 3;            // 0 point, 1 segment, 3 polytope
    Real r = 0;             // radius added to the core
};
Core core_of(const Shape& s, const Pose& p, V3 shift) {
    const auto R = quat_matrix<Real>(p.q);
    const P3 t = lp(p.p) - lp(shift);
    auto world = [&](P3 q) {
        return P3{R[0] * q.x + R[1] * q.y + R[2] * q.z + t.x, R[3] * q.x + R[4] * q.y + R[5] * q.z + t.y,
                  R[6] * q.x + R[7] * q.y + R[8] * q.z + t.z};
    };
    Core c;
    std::vector<P3> v;
    switch (s.kind) {
        case Kind::Sphere:
            c.dim = 0, c.r = s.a;
            c.poly.v = {t};
            return c;
        case Kind::Capsule:
            c.dim = 1, c.r = s.a;
            c.poly.v = {world({0, 0, -Real(s.b)}), world({0, 0, Real(s.b)})};
            c.poly.edges = {{0, 1}};
            return c;
        case Kind::Box:
            for (int i = 0; i < 8; ++i)
                v.push_back(
                    world({(i & 1 ? 1 : -1) * Real(s.a), (i & 2 ? 1 : -1) * Real(s.b), (i & 4 ? 1 : -1) * Real(s.c)}));
            break;
        case Kind::Cylinder:  // no polytope core: pairs of cylinders have their closed form
            std::abort();
        case Kind::Hull:
            if (s.grid > 0) {  // the hull is the box exactly
                for (int i = 0; i < 8; ++i)
                    v.push_back(world(
                        {(i & 1 ? 1 : -1) * Real(s.a), (i & 2 ? 1 : -1) * Real(s.b), (i & 4 ? 1 : -1) * Real(s.c)}));
            } else {
                for (const V3& q : s.pts) v.push_back(world(lp(q)));
            }
            break;
    }
    c.poly = oracle::make_polytope(std::move(v));
    return c;
}

// Two cylinders with the same orientation (parallel axes): A - B is the cylinder about the axis
// through their offset with the radii's and the half heights' sums, so the distance is that of the
// point (the axes' distance, the offset along the axis) to a rectangle: across, along, or to its
// corner; overlapping, the depth is the lesser push out (sideways or along the axis).
void parallel_cylinders_truth(Case& k) {
    Truth& t = k.truth;
    t.size = std::max(radius(k.A), radius(k.B));
    const auto R = quat_matrix<Real>(k.pa.q);
    const P3 u{R[2], R[5], R[8]};  // the common axis: the rotation's third column
    const P3 d = lp(k.pb.p) - lp(k.pa.p);
    const Real along = d.x * u.x + d.y * u.y + d.z * u.z;
    const P3 across{d.x - along * u.x, d.y - along * u.y, d.z - along * u.z};
    const Real apart = std::sqrt(across.x * across.x + across.y * across.y + across.z * across.z);
    if (k.A.kind != Kind::Cylinder || k.B.kind != Kind::Cylinder || k.pa.q != k.pb.q)
        std::abort();  // not the configuration this truth is for
    const Real gap_along = std::fabs(along) - Real(k.A.b) - Real(k.B.b), gap_across = apart - Real(k.A.a) - Real(k.B.a);
    if (gap_along <= 0 || gap_across <= 0)
        t.dist = std::max(gap_along, gap_across);
    else
        t.dist = std::sqrt(gap_along * gap_along + gap_across * gap_across);
    t.depth_known = true;
    t.depth = std::max(Real(0), -t.dist);
}

void pair_truth(Case& k) {
    if (k.A.kind == Kind::Cylinder || k.B.kind == Kind::Cylinder) return parallel_cylinders_truth(k);
    const Core a = core_of(k.A, k.pa, k.pa.p), b = core_of(k.B, k.pb, k.pa.p);
    Truth& t = k.truth;
    t.size = std::max(radius(k.A), radius(k.B));
    Real core_d = 0, depth = 0;
    bool inter = false;
    if (a.dim == 3 || b.dim == 3) {
        const oracle::Result r = oracle::distance(a.poly, b.poly);
        core_d = r.distance, inter = r.intersecting, depth = r.depth;
    } else {
        const auto& va = a.poly.v;
        const auto& vb = b.poly.v;
        Real d2;
        if (a.dim == 0 && b.dim == 0)
            d2 = oracle::dot(va[0] - vb[0], va[0] - vb[0]);
        else if (a.dim == 0)
            d2 = oracle::point_segment_sq(va[0], vb[0], vb[1]);
        else if (b.dim == 0)
            d2 = oracle::point_segment_sq(vb[0], va[0], va[1]);
        else
            d2 = oracle::segment_segment_sq(va[0], va[1], vb[0], vb[1]);
        core_d = std::sqrt(d2);
    }
    t.dist = inter ? -(depth + a.r + b.r) : core_d - a.r - b.r;
    if (a.dim == 3 && b.dim == 3) t.depth_known = true, t.depth = inter ? depth : 0;
    if (a.dim == 0 && b.dim == 0) t.depth_known = true, t.depth = std::max(Real(0), a.r + b.r - core_d);
}

cast_oracle::Body body_of(const Shape& s, const Pose& p, V3 shift) {
    using cast_oracle::Kind;
    cast_oracle::Body b;
    switch (s.kind) {
        case ::Kind::Box:
            b.kind = Kind::Box, b.half_extents = {Real(s.a), Real(s.b), Real(s.c)};
            break;
        case ::Kind::Hull:
            if (s.grid > 0)
                b.kind = Kind::Box, b.half_extents = {Real(s.a), Real(s.b), Real(s.c)};
            else {
                b.kind = Kind::Hull;
                for (const V3& q : s.pts) b.verts.push_back(lp(q));
            }
            break;
        case ::Kind::Sphere:
            b.kind = Kind::Sphere, b.radius = s.a;
            break;
        case ::Kind::Capsule:
            b.kind = Kind::Capsule, b.radius = s.a, b.half = s.b;
            break;
        case ::Kind::Cylinder:  // cylinders appear in pair cases only
            std::abort();
    }
    const auto R = quat_matrix<Real>(p.q);
    for (int i = 0; i < 9; ++i) b.R[i] = R[i];
    b.t = lp(p.p) - lp(shift);
    cast_oracle::finish_body(b);
    return b;
}

void cast_truth(Case& k) {
    const cast_oracle::Body a = body_of(k.A, k.pa, k.pa.p), b = body_of(k.B, k.pb, k.pa.p);
    const cast_oracle::Truth t = cast_oracle::toi(a, b, lp(k.ta), lp(k.tb));
    k.truth.size = std::max(radius(k.A), radius(k.B));
    k.truth.hit = t.hit, k.truth.toi = t.toi, k.truth.grazing = t.grazing;
}

// The pair's signed distance (pair oracle) at time t of a cast or ray.
double distance_at(const Case& k, double t) {
    Case p = k;
    p.type = QType::Pair;
    if (k.type == QType::Ray) p.B = sphere(1e-300);
    p.pa.p = add(k.pa.p, scl(t, k.ta)), p.pb.p = add(k.pb.p, scl(t, k.tb));
    pair_truth(p);
    return double(p.truth.dist);
}

// A cast or ray miss is judged only when its closest approach is beyond the band (the cast
// oracle's own grazing flag measures a miss by the gap of its entry and exit parameters, not by
// distance). Under translation the distance is convex in t, so golden-section search on the pair
// oracle finds the closest approach. A hit is checked at 64 times before its toi. A case where
// the cast and pair oracles disagree (a miss that overlaps, a hit overlapping earlier) is left
// unjudged; returns false then.
bool refine_cast_truth(Case& k) {
    const double band = kBand * k.truth.size;
    if (k.truth.hit) {
        for (int i = 0; i < 64; ++i) {
            const double t = double(k.truth.toi) * i / 64.0;
            if (t < double(k.truth.toi) - 1e-9 && distance_at(k, t) < -band) return false;
        }
        return true;
    }
    double lo = 0, hi = 1;
    const double phi = (std::sqrt(5.0) - 1) / 2;
    for (int i = 0; i < 80; ++i) {
        const double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
        if (distance_at(k, x1) < distance_at(k, x2))
            hi = x2;
        else
            lo = x1;
    }
    const double closest = std::min({distance_at(k, (lo + hi) / 2), distance_at(k, 0), distance_at(k, 1)});
    if (closest < -band) return false;
    k.truth.grazing = closest <= band;
    return true;
}

void ray_truth(Case& k) {
    const cast_oracle::Body a = body_of(k.A, k.pa, k.pa.p);
    cast_oracle::Body pt = cast_oracle::make_body(cast_oracle::Kind::Point);
    pt.t = lp(k.pb.p) - lp(k.pa.p);
    const cast_oracle::Truth t = cast_oracle::toi(a, pt, P3{}, lp(k.tb));
    k.truth.size = radius(k.A);
    k.truth.hit = t.hit, k.truth.toi = t.toi, k.truth.grazing = t.grazing;
}

// Motion: A (box or capsule) moves from pa to pa1, B (a ball) stays at pb. A's orientation turns at
// constant rate along the shortest arc from pa.q to pa1.q (the motion every method is told), its
// origin moves linearly. f(t) = distance from B's centre to A's core - radii, exact in long double,
// is Lipschitz with L = |dp| + rho * angle (rho: A's bounding radius), so no contact lies in
// [t, t + (f(t) - thr) / L): stepping by that much finds the first t with f <= thr, or proves none.
struct MotionFrame {
    P3 p0, dp, axis;
    Real angle = 0;
    std::array<Real, 9> R0{};
};
MotionFrame motion_frame(const Case& k) {
    MotionFrame m;
    m.p0 = lp(k.pa.p) - lp(k.pb.p);
    m.dp = lp(k.pa1.p) - lp(k.pa.p);
    m.R0 = quat_matrix<Real>(k.pa.q);
    // Relative rotation q1 * conj(q0), on q0's side (shortest arc).
    Real a[4], b[4];
    for (int i = 0; i < 4; ++i) a[i] = k.pa.q[i], b[i] = k.pa1.q[i];
    const Real na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]);
    const Real nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2] + b[3] * b[3]);
    for (int i = 0; i < 4; ++i) a[i] /= na, b[i] /= nb;
    if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] < 0)
        for (Real& x : b) x = -x;
    // r = b * conj(a): conj(a) = (-a.xyz, a.w).
    const Real ax = -a[0], ay = -a[1], az = -a[2], aw = a[3];
    const Real rx = b[3] * ax + b[0] * aw + b[1] * az - b[2] * ay;
    const Real ry = b[3] * ay - b[0] * az + b[1] * aw + b[2] * ax;
    const Real rz = b[3] * az + b[0] * ay - b[1] * ax + b[2] * aw;
    const Real rw = b[3] * aw - b[0] * ax - b[1] * ay - b[2] * az;
    const Real s = std::sqrt(rx * rx + ry * ry + rz * rz);
    m.angle = 2 * std::atan2(s, rw);
    m.axis = s > 0 ? P3{rx / s, ry / s, rz / s} : P3{0, 0, 1};
    return m;
}
// f(t): B's centre in A's local frame at t, its distance to A's core, minus the radii.
Real motion_gap(const Case& k, const MotionFrame& m, Real t) {
    // Rotation by angle*t about axis (Rodrigues), then R0.
    const Real th = m.angle * t, c = std::cos(th), s = std::sin(th), C = 1 - c;
    const P3 u = m.axis;
    const std::array<Real, 9> Q{c + u.x * u.x * C,       u.x * u.y * C - u.z * s, u.x * u.z * C + u.y * s,
                                u.y * u.x * C + u.z * s, c + u.y * u.y * C,       u.y * u.z * C - u.x * s,
                                u.z * u.x * C - u.y * s, u.z * u.y * C + u.x * s, c + u.z * u.z * C};
    std::array<Real, 9> R{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            R[3 * i + j] = Q[3 * i] * m.R0[j] + Q[3 * i + 1] * m.R0[3 + j] + Q[3 * i + 2] * m.R0[6 + j];
    // A's origin relative to B's centre at t; B's centre in A's frame is -R^T (that).
    const P3 o = m.p0 + t * m.dp;
    const P3 x{-(R[0] * o.x + R[3] * o.y + R[6] * o.z), -(R[1] * o.x + R[4] * o.y + R[7] * o.z),
               -(R[2] * o.x + R[5] * o.y + R[8] * o.z)};
    const Real rb = k.B.a;
    if (k.A.kind == Kind::Capsule) {
        const Real h = k.A.b, z = std::clamp(x.z, -h, h);
        return std::sqrt(x.x * x.x + x.y * x.y + (x.z - z) * (x.z - z)) - Real(k.A.a) - rb;
    }
    // Box: signed distance from the point.
    const Real qx = std::fabs(x.x) - k.A.a, qy = std::fabs(x.y) - k.A.b, qz = std::fabs(x.z) - k.A.c;
    const Real ox = std::max(qx, Real(0)), oy = std::max(qy, Real(0)), oz = std::max(qz, Real(0));
    const Real outside = std::sqrt(ox * ox + oy * oy + oz * oz), inside = std::min(std::max({qx, qy, qz}), Real(0));
    return outside + inside - rb;
}
// First t in [0, 1] with f(t) <= thr; -1 when none; -2 when the step budget ran out.
Real advance(const Case& k, const MotionFrame& m, Real thr, Real L) {
    Real t = 0;
    for (long i = 0; i < 2000000; ++i) {
        const Real f = motion_gap(k, m, t);
        if (f <= thr) return t;
        t += (f - thr) / L;
        if (t > 1) return motion_gap(k, m, 1) <= thr ? 1 : -1;
    }
    return -2;
}
void motion_truth(Case& k) {
    const MotionFrame m = motion_frame(k);
    const Real rho = radius(k.A);
    const Real L = oracle::norm(m.dp) + rho * std::fabs(m.angle) + Real(1e-300);
    const double size = std::max(radius(k.A), radius(k.B));
    k.truth.size = size;
    const Real contact_thr = Real(1e-14) * size, band = Real(kBand) * size;
    const Real t0 = advance(k, m, contact_thr, L);
    if (t0 == -2) {
        k.truth.decided = false;
        return;
    }
    k.truth.hit = t0 >= 0;
    k.truth.toi = t0 >= 0 ? t0 : 1;
    // Grazing (judged either way): a miss that comes within the band (conservative advancement to
    // the band), or a hit whose sampled overlap never goes deeper than the band (a sampled minimum
    // is an upper bound of the true one, so a hit called deep is deep; sampling may only call a
    // deep hit grazing, which leaves it unjudged).
    if (k.truth.hit) {
        Real lowest = 0;
        for (int i = 0; i <= 4000; ++i) lowest = std::min(lowest, motion_gap(k, m, t0 + (1 - t0) * Real(i) / 4000));
        k.truth.grazing = !(lowest < -band);
    } else {
        // The closest approach of a proven miss: the lowest of 4000 samples, refined by golden
        // section around it (an estimate; it only decides whether the miss is judged).
        int best = 0;
        Real lowest = motion_gap(k, m, 0);
        for (int i = 1; i <= 4000; ++i) {
            const Real g = motion_gap(k, m, Real(i) / 4000);
            if (g < lowest) lowest = g, best = i;
        }
        Real lo = std::max(0, best - 1) / Real(4000), hi = std::min(4000, best + 1) / Real(4000);
        const Real phi = (std::sqrt(Real(5)) - 1) / 2;
        for (int i = 0; i < 120; ++i) {
            const Real x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
            if (motion_gap(k, m, x1) < motion_gap(k, m, x2))
                hi = x2;
            else
                lo = x1;
        }
        lowest = std::min(lowest, motion_gap(k, m, (lo + hi) / 2));
        k.truth.grazing = lowest <= band;
    }
}

void compute_truth(Case& k) {
    switch (k.type) {
        case QType::Pair:
            pair_truth(k);
            break;
        case QType::Cast:
            cast_truth(k);
            break;
        case QType::Ray:
            ray_truth(k);
            break;
        case QType::Motion:
            motion_truth(k);
            break;
    }
}

// ---- Methods -----------------------------------------------------------------------------------
enum Method {
    K_DIST,
    K_INTER,
    K_RAY,
    K_SHAPE,
    K_MOTION,
    CCD_GJK,
    CCD_MPR,
    CCD_MPR_PEN,
    FCL_DIST_CCD,
    FCL_DIST_INDEP,
    FCL_CCD,
    BT_GJK,
    BT_SUBSIMPLEX,
    BT_CCC,
    K_SIGNED,    // appended: kairos_signed_distance (penetration depth)
    FCL_SIGNED,  // FCL's signed distance (libccd GJK + EPA)
    kMethods
};
const char* kMethodName[kMethods] = {
    "kairos_distance",   "kairos_intersect",  "kairos_ray_cast",     "kairos_shape_cast",   "kairos_motion_cast",
    "ccd_gjk_intersect", "ccd_mpr_intersect", "ccd_mpr_penetration", "fcl_distance_libccd", "fcl_distance_indep",
    "fcl_continuous",    "bullet_gjk_pair",   "bullet_subsimplex",   "bullet_continuous",  "kairos_signed_distance",
    "fcl_signed_distance"};

bool applies(Method m, QType t) {
    switch (t) {
        case QType::Pair:
            return m == K_DIST || m == K_INTER || m == CCD_GJK || m == CCD_MPR || m == CCD_MPR_PEN ||
                   m == FCL_DIST_CCD || m == FCL_DIST_INDEP || m == BT_GJK || m == K_SIGNED || m == FCL_SIGNED;
        case QType::Cast:
            return m == K_SHAPE || m == K_MOTION || m == FCL_CCD || m == BT_SUBSIMPLEX || m == BT_CCC;
        case QType::Ray:
            return m == K_RAY;
        case QType::Motion:
            return m == K_MOTION || m == FCL_CCD || m == BT_CCC;
    }
    return false;
}
bool is_distance(Method m) { return m == K_DIST || m == FCL_DIST_CCD || m == FCL_DIST_INDEP || m == BT_GJK; }
bool is_signed(Method m) { return m == K_SIGNED || m == FCL_SIGNED; }

// One answer. status: 0 answered, 1 error status or exception, 2 crash, 3 hang.
struct Answer {
    int status = 0;
    int verdict = 0;   // intersecting / hit
    double value = 0;  // distance, depth or toi
    int capped = 0;    // the method's iteration cap fired
};

// -- Kairos (C API) --
kairos_shape* kairos_make(const Shape& s) {
    kairos_shape* out = nullptr;
    int32_t st = KAIROS_ERROR_INTERNAL;
    switch (s.kind) {
        case Kind::Box:
            st = kairos_shape_box({s.a, s.b, s.c}, &out);
            break;
        case Kind::Sphere:
            st = kairos_shape_sphere(s.a, &out);
            break;
        case Kind::Capsule:
            st = kairos_shape_capsule(s.a, s.b, &out);
            break;
        case Kind::Cylinder:
            st = kairos_shape_cylinder(s.a, s.b, &out);
            break;
        case Kind::Hull: {
            std::vector<kairos_vec3> v;
            for (const V3& q : s.pts) v.push_back({q[0], q[1], q[2]});
            st = kairos_shape_convex_hull(v.data(), v.size(), &out);
            break;
        }
    }
    return st == KAIROS_OK ? out : nullptr;
}
kairos_pose kpose(const Pose& p) { return {{p.p[0], p.p[1], p.p[2]}, {p.q[0], p.q[1], p.q[2], p.q[3]}}; }
kairos_vec3 kv(V3 v) { return {v[0], v[1], v[2]}; }

Answer run_kairos(Method m, const Case& k) {
    Answer ans;
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    qs.tolerance = 1e-12;  // the tightest the contract documents meaningfully (tolerance in (0, 1))
    kairos_shape* a = kairos_make(k.A);
    kairos_shape* b = k.type == QType::Ray ? nullptr : kairos_make(k.B);
    if (!a || (k.type != QType::Ray && !b)) {
        kairos_shape_release(a), kairos_shape_release(b);
        ans.status = 1;
        return ans;
    }
    const kairos_pose pa = kpose(k.pa), pb = kpose(k.pb);
    int32_t st = KAIROS_OK;
    if (m == K_DIST || m == K_SIGNED) {
        kairos_distance_result r;
        st = m == K_DIST ? kairos_distance(a, &pa, b, &pb, &qs, &r) : kairos_signed_distance(a, &pa, b, &pb, &qs, &r);
        ans.value = r.distance, ans.verdict = r.intersecting,
        ans.capped = r.termination == KAIROS_TERMINATION_MAX_ITERATIONS;
    } else if (m == K_INTER) {
        int32_t hit = 0;
        st = kairos_intersect(a, &pa, b, &pb, nullptr, &hit);
        ans.verdict = hit;
    } else {
        kairos_cast_result r;
        if (m == K_RAY) {
            st = kairos_ray_cast(a, &pa, kv(k.pb.p), kv(k.tb), &qs, &r);
        } else if (m == K_SHAPE) {
            st = kairos_shape_cast(a, &pa, kv(k.ta), b, &pb, kv(k.tb), &qs, &r);
        } else {
            kairos_motion ma, mb;
            if (k.type == QType::Motion) {
                ma = {pa, kpose(k.pa1)}, mb = {pb, kpose(k.pb1)};
            } else {
                Pose ea = k.pa, eb = k.pb;
                ea.p = add(ea.p, k.ta), eb.p = add(eb.p, k.tb);
                ma = {pa, kpose(ea)}, mb = {pb, kpose(eb)};
            }
            st = kairos_motion_cast(a, &ma, b, &mb, &qs, &r);
        }
        ans.verdict = r.hit, ans.value = r.toi, ans.capped = r.termination == KAIROS_TERMINATION_MAX_ITERATIONS;
    }
    if (st != KAIROS_OK) ans.status = 1;
    kairos_shape_release(a), kairos_shape_release(b);
    return ans;
}

// -- libccd --
struct CcdObj {
    const Shape* s;
    Pose p;
    std::array<double, 9> R;
    V3 centre;
};
CcdObj ccd_obj(const Shape& s, const Pose& p) {
    CcdObj o{&s, p, quat_matrix<double>(p.q), p.p};
    if (s.kind == Kind::Hull) {  // MPR needs an interior point: the points' mean
        V3 c{0, 0, 0};
        for (const V3& q : s.pts) c = add(c, q);
        o.centre = add(mul(o.R, scl(1.0 / double(s.pts.size()), c)), p.p);
    }
    return o;
}
void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
    const CcdObj& o = *static_cast<const CcdObj*>(obj);
    const V3 w = add(mul(o.R, support_local(*o.s, mul_t(o.R, {dir->v[0], dir->v[1], dir->v[2]}))), o.p.p);
    out->v[0] = w[0], out->v[1] = w[1], out->v[2] = w[2];
}
void ccd_centre(const void* obj, ccd_vec3_t* out) {
    const CcdObj& o = *static_cast<const CcdObj*>(obj);
    out->v[0] = o.centre[0], out->v[1] = o.centre[1], out->v[2] = o.centre[2];
}
Answer run_ccd(Method m, const Case& k) {
    Answer ans;
    const CcdObj a = ccd_obj(k.A, k.pa), b = ccd_obj(k.B, k.pb);
    ccd_t c;
    CCD_INIT(&c);
    c.support1 = c.support2 = ccd_support;
    c.center1 = c.center2 = ccd_centre;
    c.max_iterations = 1000;  // the cap (default: unbounded); running out reads as "no intersection"
    c.mpr_tolerance = 1e-12;  // default 1e-4
    c.epa_tolerance = 1e-12;
    c.dist_tolerance = 1e-12;
    if (m == CCD_GJK)
        ans.verdict = ccdGJKIntersect(&a, &b, &c) != 0;
    else if (m == CCD_MPR)
        ans.verdict = ccdMPRIntersect(&a, &b, &c) != 0;
    else {
        ccd_real_t depth = 0;
        ccd_vec3_t dir, pos;
        ans.verdict = ccdMPRPenetration(&a, &b, &c, &depth, &dir, &pos) == 0;
        ans.value = ans.verdict ? double(depth) : 0;
    }
    return ans;
}

// -- FCL --
std::shared_ptr<fcl::CollisionGeometryd> fcl_geom(const Shape& s) {
    switch (s.kind) {
        case Kind::Box:
            return std::make_shared<fcl::Boxd>(2 * s.a, 2 * s.b, 2 * s.c);
        case Kind::Sphere:
            return std::make_shared<fcl::Sphered>(s.a);
        case Kind::Capsule:
            return std::make_shared<fcl::Capsuled>(s.a, 2 * s.b);
        case Kind::Cylinder:
            return std::make_shared<fcl::Cylinderd>(s.a, 2 * s.b);
        case Kind::Hull:
            break;
    }
    auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
    for (const V3& q : s.pts) verts->emplace_back(q[0], q[1], q[2]);
    auto faces = std::make_shared<std::vector<int>>();
    int nf = 0;
    if (s.grid > 0) {
        // The lattice's own triangulation (FCL walks the vertex graph above 32 vertices).
        const int n = s.grid;
        std::vector<int> index(size_t(n) * n * n, -1);
        int next = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                for (int k = 0; k < n; ++k)
                    if (i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1)
                        index[size_t((i * n + j) * n + k)] = next++;
        auto id = [&](int i, int j, int k) { return index[size_t((i * n + j) * n + k)]; };
        for (int axis = 0; axis < 3; ++axis)
            for (int side : {0, n - 1})
                for (int u = 0; u + 1 < n; ++u)
                    for (int v = 0; v + 1 < n; ++v) {
                        auto at = [&](int uu, int vv) {
                            int c[3];
                            c[axis] = side, c[(axis + 1) % 3] = uu, c[(axis + 2) % 3] = vv;
                            return id(c[0], c[1], c[2]);
                        };
                        const int q[4] = {at(u, v), at(u + 1, v), at(u + 1, v + 1), at(u, v + 1)};
                        // (axis+1, axis+2) is right-handed about +axis: keep on the + side, flip on the - side.
                        for (const auto& t :
                             {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
                            if (side == n - 1)
                                faces->insert(faces->end(), {3, t[0], t[1], t[2]});
                            else
                                faces->insert(faces->end(), {3, t[0], t[2], t[1]});
                            ++nf;
                        }
                    }
    } else {
        std::vector<P3> v;
        for (const V3& q : s.pts) v.push_back(lp(q));
        const oracle::Polytope poly = oracle::make_polytope(v);
        for (size_t f = 0; f < poly.faces.size(); ++f) {
            auto t = poly.faces[f];
            if (oracle::dot(oracle::cross(poly.v[t[1]] - poly.v[t[0]], poly.v[t[2]] - poly.v[t[0]]), poly.normals[f]) <
                0)
                std::swap(t[1], t[2]);
            faces->insert(faces->end(), {3, t[0], t[1], t[2]});
            ++nf;
        }
    }
    return std::make_shared<fcl::Convexd>(verts, nf, faces);
}
fcl::Transform3d fcl_tf(const Pose& p) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    const auto r = quat_matrix<double>(p.q);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t.linear()(i, j) = r[size_t(3 * i + j)];
    t.translation() = fcl::Vector3d(p.p[0], p.p[1], p.p[2]);
    return t;
}
Answer run_fcl(Method m, const Case& k) {
    Answer ans;
    const auto ga = fcl_geom(k.A), gb = fcl_geom(k.B);
    if (m == FCL_DIST_CCD || m == FCL_DIST_INDEP || m == FCL_SIGNED) {
        fcl::DistanceRequestd req;
        req.gjk_solver_type = m == FCL_DIST_INDEP ? fcl::GST_INDEP : fcl::GST_LIBCCD;
        req.enable_signed_distance = m == FCL_SIGNED;
        req.distance_tolerance = 1e-12;  // default 1e-6
        fcl::DistanceResultd res;
        const double d = fcl::distance(ga.get(), fcl_tf(k.pa), gb.get(), fcl_tf(k.pb), req, res);
        ans.value = m == FCL_SIGNED ? res.min_distance : d;  // unsigned: -1 when the shapes collide
        ans.verdict = ans.value <= 0;
        return ans;
    }
    fcl::ContinuousCollisionRequestd req;
    req.gjk_solver_type = fcl::GST_INDEP;
    req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    // Translation: CCDM_TRANS; rotation: CCDM_SCREW, FCL's only working rotation mode (docs/peers.md).
    req.ccd_motion_type = k.type == QType::Motion ? fcl::CCDM_SCREW : fcl::CCDM_TRANS;
    fcl::ContinuousCollisionResultd res;
    Pose ea = k.pa, eb = k.pb;
    if (k.type == QType::Motion)
        ea = k.pa1, eb = k.pb1;
    else
        ea.p = add(ea.p, k.ta), eb.p = add(eb.p, k.tb);
    fcl::continuousCollide(ga.get(), fcl_tf(k.pa), fcl_tf(ea), gb.get(), fcl_tf(k.pb), fcl_tf(eb), req, res);
    ans.verdict = res.is_collide;
    ans.value = res.is_collide ? res.time_of_contact : 1;
    return ans;
}

// -- Bullet f64 (margins 0 except the radius of spheres and capsules) --
std::unique_ptr<btConvexShape> bt_shape(const Shape& s) {
    std::unique_ptr<btConvexShape> out;
    switch (s.kind) {
        case Kind::Box:
            out = std::make_unique<btBoxShape>(btVector3(s.a, s.b, s.c));
            break;
        case Kind::Sphere:
            return std::make_unique<btSphereShape>(s.a);
        case Kind::Capsule:
            return std::make_unique<btCapsuleShapeZ>(s.a, 2 * s.b);
        case Kind::Cylinder:
            out = std::make_unique<btCylinderShapeZ>(btVector3(s.a, s.a, s.b));
            break;
        case Kind::Hull: {
            auto h = std::make_unique<btConvexHullShape>();
            for (const V3& q : s.pts) h->addPoint(btVector3(q[0], q[1], q[2]), false);
            h->recalcLocalAabb();
            out = std::move(h);
            break;
        }
    }
    out->setMargin(0);
    return out;
}
btTransform bt_tf(const Pose& p) {
    return btTransform(btQuaternion(p.q[0], p.q[1], p.q[2], p.q[3]), btVector3(p.p[0], p.p[1], p.p[2]));
}
Answer run_bullet(Method m, const Case& k) {
    Answer ans;
    const auto sa = bt_shape(k.A), sb = bt_shape(k.B);
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    if (m == BT_GJK) {
        btGjkPairDetector det(sa.get(), sb.get(), &simplex, &epa);
        btGjkPairDetector::ClosestPointInput in;
        in.m_transformA = bt_tf(k.pa);
        in.m_transformB = bt_tf(k.pb);
        btPointCollector out;
        det.getClosestPoints(in, out, nullptr);
        if (!out.m_hasResult) ans.status = 1;
        ans.value = out.m_distance;  // negative: penetration (EPA)
        ans.verdict = out.m_distance <= 0;
        ans.capped = det.m_curIter > 1000;  // Bullet's gGjkMaxIter
        return ans;
    }
    Pose ea = k.pa, eb = k.pb;
    if (k.type == QType::Motion)
        ea = k.pa1, eb = k.pb1;
    else
        ea.p = add(ea.p, k.ta), eb.p = add(eb.p, k.tb);
    btConvexCast::CastResult res;
    bool hit;
    if (m == BT_SUBSIMPLEX) {
        btSubsimplexConvexCast cast(sa.get(), sb.get(), &simplex);
        hit = cast.calcTimeOfImpact(bt_tf(k.pa), bt_tf(ea), bt_tf(k.pb), bt_tf(eb), res);
    } else {
        btContinuousConvexCollision cast(sa.get(), sb.get(), &simplex, &epa);
        hit = cast.calcTimeOfImpact(bt_tf(k.pa), bt_tf(ea), bt_tf(k.pb), bt_tf(eb), res);
    }
    ans.verdict = hit && res.m_fraction <= btScalar(1);
    ans.value = ans.verdict ? double(res.m_fraction) : 1;
    return ans;
}

Answer run_one(Method m, const Case& k) {
    try {
        switch (m) {
            case K_DIST:
            case K_INTER:
            case K_RAY:
            case K_SHAPE:
            case K_MOTION:
                return run_kairos(m, k);
            case CCD_GJK:
            case CCD_MPR:
            case CCD_MPR_PEN:
                return run_ccd(m, k);
            case K_SIGNED:
                return run_kairos(m, k);
            case FCL_DIST_CCD:
            case FCL_DIST_INDEP:
            case FCL_CCD:
            case FCL_SIGNED:
                return run_fcl(m, k);
            default:
                return run_bullet(m, k);
        }
    } catch (...) {
        Answer a;
        a.status = 1;
        return a;
    }
}

// A case with A and B exchanged (translations and motions follow their shapes).
Case swapped(const Case& k) {
    Case s = k;
    std::swap(s.A, s.B), std::swap(s.pa, s.pb), std::swap(s.pa1, s.pb1), std::swap(s.ta, s.tb);
    return s;
}

// ---- Judging -----------------------------------------------------------------------------------
struct Verdict {
    bool fail = false;
    const char* why = "";
    double err = 0;  // the judged error: |distance error| / size, |toi error|, or |gap| / size of a wrong verdict
    bool err_valid = false;
};

Verdict judge(Method m, const Case& k, const Answer& a) {
    Verdict v;
    const Truth& t = k.truth;
    if (a.status == 2) return {true, "crash", 0, false};
    if (a.status == 3) return {true, "hang", 0, false};
    if (a.status == 1) return {true, "error/exception", 0, false};
    if (!std::isfinite(a.value)) return {true, "non-finite", 0, false};
    if (a.capped) return {true, "iteration cap", 0, false};
    const double size = t.size;
    if (k.type == QType::Pair) {
        const double truth_d = double(std::max(t.dist, Real(0)));
        if (is_distance(m)) {
            const double got = std::max(a.value, 0.0);
            v.err = std::fabs(got - truth_d) / size, v.err_valid = true;
            if (v.err > kDistanceBound) v.fail = true, v.why = "distance error";
            return v;
        }
        // Signed distances: against the exact signed distance when it is known (apart, or a
        // depth the oracle gives), else the verdict only.
        if (is_signed(m) && (t.dist >= 0 || t.depth_known)) {
            v.err = std::fabs(a.value - double(t.dist)) / size, v.err_valid = true;
            if (v.err > kDistanceBound) v.fail = true, v.why = t.dist < 0 ? "penetration depth error" : "distance error";
            return v;
        }
        const bool judged = std::fabs(double(t.dist)) > kBand * size;
        const bool truth_in = t.dist < 0;
        if (judged && bool(a.verdict) != truth_in) {
            v.fail = true,
            v.why = truth_in ? "says separated, truth intersecting" : "says intersecting, truth separated";
            v.err = std::fabs(double(t.dist)) / size, v.err_valid = true;
            return v;
        }
        if (m == CCD_MPR_PEN && judged && truth_in && a.verdict && t.depth_known) {
            v.err = std::fabs(a.value - double(t.depth)) / size, v.err_valid = true;
            if (v.err > kDistanceBound) v.fail = true, v.why = "penetration depth error";
        }
        return v;
    }
    // Casts, rays, motions.
    if (!t.decided || t.grazing) return v;
    if (t.hit && !a.verdict) return {true, "miss (truth hits)", 0, false};
    if (!t.hit && a.verdict) return {true, "false hit (truth misses beyond the band)", 0, false};
    if (t.hit) {
        v.err = std::fabs(a.value - double(t.toi)), v.err_valid = true;
        if (a.value > double(t.toi) + kLateBound) v.fail = true, v.why = "late";
    }
    return v;
}

// Swap family: both orders judged, and their answers must agree within the same bounds.
Verdict judge_pair(Method m, const Case& k, const Answer& a, const Answer& b) {
    Verdict v0 = judge(m, k, a);
    if (v0.fail) return v0;
    Verdict v1 = judge(m, k, b);
    if (v1.fail) {
        v1.why = v1.why[0] ? v1.why : "swapped order";
        return v1;
    }
    Verdict v = v0.err >= v1.err ? v0 : v1;
    const Truth& t = k.truth;
    if (k.type == QType::Pair) {
        if (is_distance(m) && std::fabs(std::max(a.value, 0.0) - std::max(b.value, 0.0)) > kDistanceBound * t.size)
            v.fail = true, v.why = "orders disagree (distance)";
        else if (!is_distance(m) && a.verdict != b.verdict && std::fabs(double(t.dist)) > kBand * t.size)
            v.fail = true, v.why = "orders disagree (verdict)";
    } else if (t.decided && !t.grazing) {
        if (a.verdict != b.verdict)
            v.fail = true, v.why = "orders disagree (hit)";
        else if (a.verdict && std::fabs(a.value - b.value) > kLateBound)
            v.fail = true, v.why = "orders disagree (toi)";
    }
    return v;
}

// ---- Running a batch in a child process --------------------------------------------------------
struct Record {
    int32_t index;
    Answer a[2];
};

// Runs method m on cases[0..n) (both orders when swap), in forked children streaming records
// through a pipe. A child that dies marks its current case a crash; one silent for kCaseTimeout is
// killed and its case marked a hang; a new child goes on from the next case. After
// kMaxDeathsPerBatch deaths the remaining cases are marked with the last death's kind.
std::vector<Record> run_batch(Method m, const std::vector<Case>& cases, bool swap) {
    const int n = int(cases.size());
    std::vector<Record> out(static_cast<size_t>(n));
    int next = 0, deaths = 0;
    while (next < n) {
        int fd[2];
        if (pipe(fd) != 0) std::perror("pipe"), std::exit(1);
        std::fflush(stdout);
        const pid_t pid = fork();
        if (pid < 0) std::perror("fork"), std::exit(1);
        if (pid == 0) {
            close(fd[0]);
            for (int i = next; i < n; ++i) {
                Record r;
                r.index = i;
                r.a[0] = run_one(m, cases[size_t(i)]);
                if (swap) r.a[1] = run_one(m, swapped(cases[size_t(i)]));
                if (write(fd[1], &r, sizeof r) != ssize_t(sizeof r)) _exit(3);
            }
            _exit(0);
        }
        close(fd[1]);
        int death = 0;
        for (;;) {
            pollfd p{fd[0], POLLIN, 0};
            const int ready = poll(&p, 1, int(kCaseTimeout * 1000));
            if (ready == 0) {
                kill(pid, SIGKILL);
                death = 3;
                break;
            }
            Record r;
            const ssize_t got = read(fd[0], &r, sizeof r);
            if (got != ssize_t(sizeof r)) {
                death = next < n ? 2 : 0;
                break;
            }
            out[size_t(r.index)] = r;
            next = r.index + 1;
            if (next == n) break;
        }
        close(fd[0]);
        int st = 0;
        waitpid(pid, &st, 0);
        if (death && next < n) {
            out[size_t(next)].a[0].status = out[size_t(next)].a[1].status = death;
            ++next;
            if (++deaths >= kMaxDeathsPerBatch)
                for (; next < n; ++next) out[size_t(next)].a[0].status = out[size_t(next)].a[1].status = death;
        }
    }
    return out;
}

// ---- Case generation ---------------------------------------------------------------------------
using Rng = std::mt19937_64;
double uni(Rng& r, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(r); }
V3 rand_unit(Rng& r) {
    std::normal_distribution<double> g;
    for (;;) {
        const V3 v{g(r), g(r), g(r)};
        if (len3(v) > 1e-3) return unit(v);
    }
}
std::array<double, 4> rand_quat(Rng& r) {
    std::normal_distribution<double> g;
    std::array<double, 4> q{g(r), g(r), g(r), g(r)};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& x : q) x /= n;
    return q;
}
std::array<double, 4> axis_angle(V3 axis, double angle) {
    const V3 u = unit(axis);
    const double s = std::sin(angle / 2);
    return {u[0] * s, u[1] * s, u[2] * s, std::cos(angle / 2)};
}
std::array<double, 4> qmul(const std::array<double, 4>& a, const std::array<double, 4>& b) {
    return {
        a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1], a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
        a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3], a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}
V3 perpendicular(Rng& r, V3 u) {
    for (;;) {
        const V3 w = cross3(u, rand_unit(r));
        if (len3(w) > 0.1) return unit(w);
    }
}

std::vector<V3> random_points(Rng& r, int n, V3 ext) {
    std::vector<V3> p;
    for (int i = 0; i < n; ++i)
        p.push_back({uni(r, -ext[0], ext[0]), uni(r, -ext[1], ext[1]), uni(r, -ext[2], ext[2])});
    return p;
}
Shape random_shape(Rng& r, double s) {
    switch (std::uniform_int_distribution<int>(0, 3)(r)) {
        case 0:
            return box(s * uni(r, 0.3, 1.5), s * uni(r, 0.3, 1.5), s * uni(r, 0.3, 1.5));
        case 1:
            return hull(random_points(r, 12, {s * uni(r, 0.4, 1.5), s * uni(r, 0.4, 1.5), s * uni(r, 0.4, 1.5)}));
        case 2:
            return sphere(s * uni(r, 0.3, 1.2));
        default:
            return capsule(s * uni(r, 0.2, 0.6), s * uni(r, 0.3, 1.2));
    }
}

// B's position so that its support along -u lies g * u beyond A's support along u: the slab
// between the two support planes has width g, and the two support points are g apart along u,
// so the distance is g when g >= 0 (before rounding; the truth is computed from the rounded pose).
V3 place_at_gap(const Shape& A, const Pose& pa, const Shape& B, const std::array<double, 4>& qb, V3 u, double g) {
    const V3 sa = support_world(A, pa, u);
    Pose pb;
    pb.q = qb;
    const V3 sb = support_world(B, pb, scl(-1, u));  // pb.p = 0: relative to B's origin
    return sub(add(sa, scl(g, u)), sb);
}

struct Family {
    std::string name;
    std::vector<Case> cases;
    bool swap = false;
};

// The gaps of the near-contact families: +-1e-12 .. +-1e-2 of the size.
std::vector<double> signed_gaps() {
    std::vector<double> g;
    for (int e = -12; e <= -2; ++e) g.push_back(std::pow(10.0, e)), g.push_back(-std::pow(10.0, e));
    return g;
}

// A pair at relative gap g along u, and (when with_cast) a cast case whose relative motion reaches
// that configuration at t = lambda_end (1: it stops there; 0.5: it goes on into A), with a lateral
// slide and a random motion of A on top.
void add_gap_cases(Family& f, Rng& r, const Shape& A, const Pose& pa, const Shape& B, const std::array<double, 4>& qb,
                   V3 u, double g, bool with_cast, V3 offset = {0, 0, 0}) {
    const double size = std::max(radius(A), radius(B));
    Case k;
    k.type = QType::Pair;
    k.A = A, k.B = B, k.pa = pa, k.pb.q = qb;
    k.pb.p = place_at_gap(A, pa, B, qb, u, g * size);
    k.pa.p = add(k.pa.p, offset), k.pb.p = add(k.pb.p, offset);
    f.cases.push_back(k);
    if (!with_cast) return;
    Case c = k;
    c.type = QType::Cast;
    const double lambda_end = uni(r, 0, 1) < 0.5 ? 1.0 : 0.5;
    const V3 v = add(scl(-size * uni(r, 0.5, 2.0), u), scl(size * uni(r, 0, 1.0), perpendicular(r, u)));
    c.ta = scl(size * uni(r, 0, 1.0), rand_unit(r));
    c.tb = add(c.ta, v);
    c.pb.p = sub(k.pb.p, scl(lambda_end, v));
    f.cases.push_back(c);
}

Family near_contact(const char* name, uint64_t seed, double scale, double offset, int per_gap) {
    Family f{name, {}, false};
    Rng r(seed);
    for (double g : signed_gaps())
        for (int i = 0; i < per_gap; ++i) {
            const Shape A = random_shape(r, scale), B = random_shape(r, scale);
            Pose pa;
            pa.q = rand_quat(r);
            V3 off{0, 0, 0};
            if (offset > 0) off = scl(offset, rand_unit(r));
            add_gap_cases(f, r, A, pa, B, rand_quat(r), rand_unit(r), g, i % 2 == 0, off);
        }
    return f;
}

Family exact_touching() {
    Family f{"touching", {}, false};
    const std::array<double, 4> id{0, 0, 0, 1}, half_z{0, 0, 1, 0}, half_x{1, 0, 0, 0};  // exact 180 degree turns
    struct Conf {
        Shape A, B;
        V3 pb;    // B's position at exact contact (A at the origin, identity)
        V3 axis;  // unit contact axis, for the controls and the casts
        std::array<double, 4> qb;
    };
    // B's extent along d (exact for these axis-aligned shapes and exact turns).
    auto reach = [](const Shape& B, const std::array<double, 4>& q, V3 d) {
        Pose p;
        p.q = q;
        return dot3(d, support_world(B, p, d));
    };
    std::vector<Conf> confs;
    const Shape big = box(1, 1, 1), small = box(0.5, 0.25, 0.75);
    for (int ax = 0; ax < 3; ++ax)
        for (double s : {1.0, -1.0}) {
            V3 axis{0, 0, 0}, e1{0, 0, 0}, e2{0, 0, 0};
            axis[size_t(ax)] = s, e1[size_t((ax + 1) % 3)] = 1, e2[size_t((ax + 2) % 3)] = 1;
            for (const auto& q : {id, half_z, half_x}) {
                // Face on face; edge on edge (B's side face in A's side plane); corner on corner.
                const V3 face = scl(1 + reach(small, q, scl(-1, axis)), axis);
                const V3 edge = add(face, scl(1 + reach(small, q, scl(-1, e1)), e1));
                const V3 corner = add(edge, scl(1 + reach(small, q, scl(-1, e2)), e2));
                for (const V3& pb : {face, edge, corner}) confs.push_back({big, small, pb, axis, q});
            }
            confs.push_back({sphere(1), sphere(0.5), scl(1.5, axis), axis, id});
            confs.push_back({big, sphere(0.5), scl(1.5, axis), axis, id});
            confs.push_back(
                {big, capsule(0.5, 1), scl(1 + reach(capsule(0.5, 1), half_x, scl(-1, axis)), axis), axis, half_x});
            // The box's corners as a hull (8 points), face on face with the small box.
            confs.push_back({grid_box(1, 1, 1, 2), small, scl(1 + reach(small, id, scl(-1, axis)), axis), axis, id});
        }
    // A ball on a box edge: (0.375, 0.5) from the edge is 0.625 away (3-4-5), exactly.
    confs.push_back({big, sphere(0.625), {1.375, 1.5, 0.25}, unit({0.6, 0.8, 0}), id});
    const double shift = std::ldexp(1.0, -10);  // controls: 2^-10 apart or overlapping
    for (const Conf& c : confs) {
        for (int variant = 0; variant < 3; ++variant) {
            Case k;
            k.type = QType::Pair;
            k.A = c.A, k.B = c.B, k.pb.q = c.qb;
            k.pb.p = c.pb;
            if (variant == 1) k.pb.p = add(c.pb, scl(shift, c.axis));
            if (variant == 2) k.pb.p = sub(c.pb, scl(shift, c.axis));
            f.cases.push_back(k);
        }
        // Casts: B approaches along -axis and reaches the touching pose at t = 0.5 (then goes on),
        // or stops 2^-10 short of it at t = 1 (a miss).
        Case k;
        k.type = QType::Cast;
        k.A = c.A, k.B = c.B, k.pb.q = c.qb;
        k.pb.p = add(c.pb, c.axis);
        k.tb = scl(-2, c.axis);
        f.cases.push_back(k);
        k.tb = scl(-(1 - shift), c.axis);
        f.cases.push_back(k);
    }
    return f;
}

Family parallel_faces() {
    Family f{"parallel_faces", {}, false};
    Rng r(303);
    const Shape A = box(2, 2, 0.5), B = box(1, 1, 0.25);
    const double tilts[] = {0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
    int i = 0;
    for (double tilt : tilts)
        for (double g : signed_gaps())
            for (int rep = 0; rep < 4; ++rep, ++i) {
                // Half the cases keep B's edges parallel to A's (no yaw: a box stacked square on a
                // box, where the flat tetrahedra of the two top faces are; issue 12's 0.081 for
                // 5.6e-7 was one), tilted about x or a random horizontal axis.
                const double psi = rep == 0 ? 0.0 : uni(r, 0, 2 * M_PI);
                const auto yaw = axis_angle({0, 0, 1}, rep < 2 ? 0.0 : uni(r, 0, 2 * M_PI));
                const auto qb = tilt > 0 ? qmul(axis_angle({std::cos(psi), std::sin(psi), 0}, tilt), yaw) : yaw;
                Pose pa;
                // Lateral offset within the lower top face; placement along +z at the gap.
                const V3 lateral{uni(r, -0.5, 0.5), uni(r, -0.5, 0.5), 0};
                const double size = std::max(radius(A), radius(B));
                Case k;
                k.type = QType::Pair;
                k.A = A, k.B = B, k.pb.q = qb;
                Pose probe;
                probe.q = qb;
                const double low = support_world(B, probe, {0, 0, -1})[2];  // B's lowest z about its origin
                k.pb.p = {lateral[0], lateral[1], 0.5 + g * size - low};
                f.cases.push_back(k);
                if (i % 2 == 0) {
                    // Dropping along -z with a slide, reaching this pose at t = 1 (stops) or 0.5 (goes on).
                    Case c = k;
                    c.type = QType::Cast;
                    const double lambda_end = uni(r, 0, 1) < 0.5 ? 1.0 : 0.5;
                    const V3 v{uni(r, -0.3, 0.3), uni(r, -0.3, 0.3), -uni(r, 0.5, 2.0)};
                    c.tb = v;
                    c.pb.p = sub(k.pb.p, scl(lambda_end, v));
                    f.cases.push_back(c);
                }
            }
    return f;
}

// A family of gap cases: per signed gap, `reps` pairs from make(rep, i) (A, B), A at a random
// turn, B at another, along a random direction; half of them with casts.
template <class Make>
Family gap_family(const char* name, uint64_t seed, int reps, Make&& make) {
    Family f{name, {}, false};
    Rng r(seed);
    int i = 0;
    for (double g : signed_gaps())
        for (int rep = 0; rep < reps; ++rep, ++i) {
            const auto [A, B] = make(r, rep, i);
            Pose pa;
            pa.q = rand_quat(r);
            add_gap_cases(f, r, A, pa, B, rand_quat(r), rand_unit(r), g, rep % 2 == 0);
        }
    return f;
}

Family needles() {
    const double widths[] = {1e-2, 1e-4, 1e-6};
    auto needle = [&](Rng& r, double w) -> Shape {
        switch (std::uniform_int_distribution<int>(0, 2)(r)) {
            case 0:
                return box(1, w, w);
            case 1:
                return capsule(w, 1);
            default: {
                std::vector<V3> p;
                for (int i = 0; i < 8; ++i)
                    p.push_back({uni(r, -w, w), uni(r, -w, w), i < 2 ? (i ? 1.0 : -1.0) : uni(r, -1, 1)});
                return hull(p);
            }
        }
    };
    return gap_family("needles", 404, 8, [&](Rng& r, int rep, int i) {
        const Shape A = needle(r, widths[i % 3]);
        const Shape B = rep % 2 ? needle(r, widths[(i / 3) % 3]) : random_shape(r, 1.0);
        return std::pair<Shape, Shape>{A, B};
    });
}

Family flat_thin() {
    const double thick[] = {0, 1e-12, 1e-8, 1e-4};
    return gap_family("flat_thin_hulls", 505, 8, [&](Rng& r, int rep, int i) {
        auto flat = [&]() {
            const double t = thick[size_t(i + rep) % 4];
            std::vector<V3> p;
            for (int j = 0; j < 10; ++j) p.push_back({uni(r, -1, 1), uni(r, -1, 1), t * uni(r, -1, 1)});
            return hull(p);
        };
        const Shape A = flat();
        const Shape B = rep % 3 == 0 ? flat() : random_shape(r, 1.0);
        return std::pair<Shape, Shape>{A, B};
    });
}

// A pair case of two cylinders, radii and half heights 0.2 .. 1.2 (A's drawn first), not placed.
Case cylinder_pair(Rng& r) {
    Case k;
    k.type = QType::Pair;
    k.A = cylinder(uni(r, 0.2, 1.2), uni(r, 0.2, 1.2));
    k.B = cylinder(uni(r, 0.2, 1.2), uni(r, 0.2, 1.2));
    return k;
}

// Two parallel cylinders side by side at every gap (a line contact: GJK's simplex runs along the
// contact line, and an estimate within the tolerance of the gap leaves the axis free by
// sqrt(2 tolerance); bench_gjk and test_gjk_curved have the same case). Radii and half heights
// 0.2 .. 1.2, B's centre along the axis within 0.3 of the half heights' sum so that the sides meet.
// Truth: the closed form (parallel_cylinders_truth).
Family parallel_cylinders() {
    Family f{"parallel_cylinders", {}, false};
    Rng r(707);
    for (double g : signed_gaps())
        for (int i = 0; i < 8; ++i) {
            Case k = cylinder_pair(r);
            const double size = std::max(radius(k.A), radius(k.B));
            k.pa.q = k.pb.q = rand_quat(r);
            k.pa.p = {uni(r, -1, 1), uni(r, -1, 1), uni(r, -1, 1)};
            const double phi = uni(r, 0, 2 * M_PI), rho = k.A.a + k.B.a + g * size;
            const double dz = 0.3 * (k.A.b + k.B.b) * uni(r, -1, 1);
            k.pb.p = add(k.pa.p, mul(quat_matrix<double>(k.pa.q), V3{rho * std::cos(phi), rho * std::sin(phi), dz}));
            f.cases.push_back(k);
        }
    return f;
}

// Coaxial cylinders (the same orientation, the axes apart by 0 to 0.3 of the smaller radius):
// stacked end to end at every signed gap (flat ends facing), and deep overlaps with their ends
// inside each other or centred together (copies in half of them), where A - B's side meets its
// ends along a circle that an expansion can only approach. Radii and half heights 0.2 .. 1.2.
// Truth: the closed form (parallel_cylinders_truth).
Family coaxial_cylinders() {
    Family f{"coaxial_cylinders", {}, false};
    Rng r(708);
    const double offsets[] = {0, 1e-9, 1e-4, 0.3};
    const auto place = [&](Case& k, double off_share, double dz) {
        k.pa.q = k.pb.q = rand_quat(r);
        k.pa.p = {uni(r, -1, 1), uni(r, -1, 1), uni(r, -1, 1)};
        const double phi = uni(r, 0, 2 * M_PI), off = off_share * std::min(k.A.a, k.B.a);
        k.pb.p = add(k.pa.p, mul(quat_matrix<double>(k.pa.q), V3{off * std::cos(phi), off * std::sin(phi), dz}));
        f.cases.push_back(k);
    };
    for (double g : signed_gaps())
        for (int i = 0; i < 8; ++i) {
            Case k = cylinder_pair(r);
            const double size = std::max(radius(k.A), radius(k.B));
            place(k, offsets[i % 4], (i / 4 ? 1 : -1) * (k.A.b + k.B.b + g * size));
        }
    for (int i = 0; i < 96; ++i) {
        Case k;
        k.type = QType::Pair;
        k.A = cylinder(uni(r, 0.2, 1.2), uni(r, 0.2, 1.2));
        k.B = i % 2 ? cylinder(uni(r, 0.2, 1.2), uni(r, 0.2, 1.2)) : k.A;
        const double share = std::array{0.0, 0.5, 0.9}[size_t(i / 2 % 3)];
        place(k, offsets[i / 6 % 4], (i / 24 % 2 ? 1 : -1) * share * (k.A.b + k.B.b));
    }
    return f;
}

Family large_hulls() {
    return gap_family("large_hulls", 606, 6, [&](Rng& r, int rep, int) {
        const Shape A = grid_box(uni(r, 0.5, 1.5), uni(r, 0.5, 1.5), uni(r, 0.5, 1.5), 16);  // 1352 points
        const Shape B =
            rep % 4 == 0 ? grid_box(uni(r, 0.5, 1.5), uni(r, 0.5, 1.5), uni(r, 0.5, 1.5), 16) : random_shape(r, 1.0);
        return std::pair<Shape, Shape>{A, B};
    });
}

// Rays and casts passing a shape at distance delta (negative: cutting in by |delta|): the line
// lies in the plane delta beyond A's support plane along u, through the support point's offset.
Family grazing() {
    Family f{"grazing", {}, false};
    Rng r(707);
    int i = 0;
    for (double g : signed_gaps())
        for (int rep = 0; rep < 8; ++rep, ++i) {
            const Shape A = random_shape(r, 1.0);
            Pose pa;
            pa.q = rand_quat(r);
            const double size = radius(A);
            const V3 u = rand_unit(r), d = perpendicular(r, u);
            const V3 s = support_world(A, pa, u);
            const double l1 = size * uni(r, 0.5, 2), l2 = size * uni(r, 0.5, 2);
            Case k;
            k.type = QType::Ray;
            k.A = A, k.pa = pa;
            k.pb.p = sub(add(s, scl(g * size, u)), scl(l1, d));
            k.tb = scl(l1 + l2, d);
            f.cases.push_back(k);
            if (rep % 2 == 0) {
                const Shape B = random_shape(r, 1.0);
                Case c;
                c.type = QType::Cast;
                c.A = A, c.B = B, c.pa = pa, c.pb.q = rand_quat(r);
                const double sz = std::max(radius(A), radius(B));
                const V3 mid = place_at_gap(A, pa, B, c.pb.q, u, g * sz);
                c.ta = scl(sz * uni(r, 0, 1), rand_unit(r));
                const V3 v = scl(sz * uni(r, 1, 4), d);
                c.tb = add(c.ta, v);
                c.pb.p = sub(mid, scl(0.5, v));
                f.cases.push_back(c);
            }
        }
    return f;
}

Family casts_in_contact() {
    Family f{"cast_in_contact", {}, false};
    Rng r(808);
    const double gaps[] = {-1e-2, -1e-6, -1e-9, -1e-12, 0, 1e-12, 1e-9, 1e-6, 1e-3, 1e-2};
    for (double g : gaps)
        for (int motion = 0; motion < 3; ++motion)  // toward, away, tangential
            for (int rep = 0; rep < 4; ++rep) {
                const Shape A = random_shape(r, 1.0), B = random_shape(r, 1.0);
                Pose pa;
                pa.q = rand_quat(r);
                const V3 u = rand_unit(r);
                const double size = std::max(radius(A), radius(B));
                Case c;
                c.type = QType::Cast;
                c.A = A, c.B = B, c.pa = pa, c.pb.q = rand_quat(r);
                c.pb.p = place_at_gap(A, pa, B, c.pb.q, u, g * size);
                const V3 dir = motion == 0 ? scl(-1, u) : motion == 1 ? u : perpendicular(r, u);
                c.ta = scl(size * uni(r, 0, 0.5), rand_unit(r));
                c.tb = add(c.ta, scl(size * uni(r, 0.2, 2), dir));
                f.cases.push_back(c);
                if (rep < 2) {
                    // A ray from A's surface point (pushed by g along u).
                    Case k;
                    k.type = QType::Ray;
                    k.A = A, k.pa = pa;
                    k.pb.p = add(support_world(A, pa, u), scl(g * radius(A), u));
                    k.tb = scl(radius(A) * uni(r, 0.2, 2), dir);
                    f.cases.push_back(k);
                }
            }
    return f;
}

// Rotating rods (box or capsule, half length 1, along the frame's x) against a static ball, turning
// by turn(r, i) about the frame's z through the rod's centre.
// Without translation (rotation near +-pi; box and capsule rods): the ball in the sweep at a
// random angle (hits), just beyond the reach of the rod's tip (misses by 1e-1 .. 1e-8), or just
// within it (tip hits). With translation (tiny turns; capsule rods): the rod also moves along the
// turning axis, head on into a ball in its path (hits), or past a ball beside its tip at a gap of
// +-1e-12 .. 1e-2 of the size.
template <class Turn>
Family rotating(const char* name, uint64_t seed, Turn turn, bool translate) {
    Family f{name, {}, false};
    Rng r(seed);
    for (int i = 0; i < 160; ++i) {
        const double angle = turn(i);
        Case k;
        k.type = QType::Motion;
        const bool is_box = !translate && i % 2 == 0;
        k.A = is_box ? box(1, 0.05, 0.05) : capsule(0.05, 1);
        const double rb = uni(r, 0.1, 0.3);
        k.B = sphere(rb);
        const auto frame = rand_quat(r);
        const auto r0 = quat_matrix<double>(frame);
        const V3 e1 = mul(r0, {1, 0, 0}), e2 = mul(r0, {0, 1, 0}), zaxis = mul(r0, {0, 0, 1});
        // The capsule's axis (local z) turned onto the frame's x, like the box's long axis.
        const auto base = is_box ? frame : qmul(frame, axis_angle({0, 1, 0}, M_PI / 2));
        const double a0 = uni(r, 0, 2 * M_PI);
        k.pa.q = qmul(axis_angle(zaxis, a0), base);
        k.pa1.q = qmul(axis_angle(zaxis, a0 + angle), base);
        k.pa.p = k.pa1.p = {uni(r, -2, 2), uni(r, -2, 2), uni(r, -2, 2)};
        const double t_star = uni(r, 0.05, 0.95);
        if (!translate) {
            const double tip = is_box ? std::sqrt(1 + 0.05 * 0.05) : 1.05;  // in-plane reach of the rod
            double dist, phi = a0 + angle * t_star;
            switch (i % 4) {
                case 0:
                case 1:
                    dist = uni(r, 0.4, 0.8);
                    phi += sgn(angle) * std::asin((rb + 0.05) / dist);
                    break;
                case 2:
                    dist = tip + rb + std::pow(10.0, -uni(r, 1, 8));
                    break;
                default:
                    dist = tip + rb - std::pow(10.0, -uni(r, 1, 8));
                    break;
            }
            const double zoff = uni(r, -0.02, 0.02);
            k.pb.p =
                add(k.pa.p, add(add(scl(dist * std::cos(phi), e1), scl(dist * std::sin(phi), e2)), scl(zoff, zaxis)));
        } else {
            const V3 v = scl(uni(r, 0.5, 2), zaxis);
            const V3 along = add(scl(std::cos(a0), e1), scl(std::sin(a0), e2));
            const V3 centre_at = add(k.pa.p, scl(t_star, v));  // the rod's centre at t_star
            k.pa1.p = add(k.pa.p, v);
            const double size = 1.05;
            if (i % 3 == 0) {
                k.pb.p = add(centre_at, scl(uni(r, -0.8, 0.8), along));
            } else {
                const double g = signed_gaps()[size_t(i) % 22] * size;
                k.pb.p = add(centre_at, scl(1.05 + rb + g, along));
            }
        }
        k.pb1 = k.pb;
        f.cases.push_back(k);
    }
    return f;
}

// Argument-order swaps: cases drawn from the near-contact, needle and parallel-face generators,
// each run in both orders.
Family arg_swaps() {
    Family f{"arg_swap", {}, true};
    Family a = near_contact("x", 909, 1.0, 0, 2), b = needles(), c = parallel_faces();
    Rng r(910);
    for (const Family* src : {&a, &b, &c})
        for (size_t i = 0; i < src->cases.size(); ++i)
            if (std::uniform_real_distribution<double>(0, 1)(r) < 0.3) f.cases.push_back(src->cases[i]);
    return f;
}

// ---- Reporting ---------------------------------------------------------------------------------
std::string fmt(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}
std::string v3s(V3 v) { return "(" + fmt(v[0]) + "," + fmt(v[1]) + "," + fmt(v[2]) + ")"; }
std::string shape_str(const Shape& s) {
    switch (s.kind) {
        case Kind::Box:
            return "box(half=" + v3s({s.a, s.b, s.c}) + ")";
        case Kind::Sphere:
            return "sphere(r=" + fmt(s.a) + ")";
        case Kind::Capsule:
            return "capsule(r=" + fmt(s.a) + ",half_height=" + fmt(s.b) + ")";
        case Kind::Cylinder:
            return "cylinder(r=" + fmt(s.a) + ",half_height=" + fmt(s.b) + ")";
        case Kind::Hull:
            break;
    }
    if (s.grid > 0)
        return "hull(surface lattice " + std::to_string(s.grid) + "^3 of box half=" + v3s({s.a, s.b, s.c}) + ", " +
               std::to_string(s.pts.size()) + " points)";
    std::string o = "hull[" + std::to_string(s.pts.size()) + "]{";
    for (size_t i = 0; i < s.pts.size(); ++i) o += (i ? "," : "") + v3s(s.pts[i]);
    return o + "}";
}
std::string pose_str(const Pose& p) {
    return "p=" + v3s(p.p) + " q=(" + fmt(p.q[0]) + "," + fmt(p.q[1]) + "," + fmt(p.q[2]) + "," + fmt(p.q[3]) + ")";
}
std::string case_str(const Case& k) {
    std::string o;
    switch (k.type) {
        case QType::Pair:
            o = "pair A=" + shape_str(k.A) + " " + pose_str(k.pa) + " B=" + shape_str(k.B) + " " + pose_str(k.pb);
            o += " | truth distance " + fmt(double(k.truth.dist)) +
                 (k.truth.depth_known ? " depth " + fmt(double(k.truth.depth)) : "");
            break;
        case QType::Cast:
            o = "cast A=" + shape_str(k.A) + " " + pose_str(k.pa) + " ta=" + v3s(k.ta) + " B=" + shape_str(k.B) + " " +
                pose_str(k.pb) + " tb=" + v3s(k.tb);
            break;
        case QType::Ray:
            o = "ray S=" + shape_str(k.A) + " " + pose_str(k.pa) + " origin=" + v3s(k.pb.p) +
                " translation=" + v3s(k.tb);
            break;
        case QType::Motion:
            o = "motion A=" + shape_str(k.A) + " from " + pose_str(k.pa) + " to " + pose_str(k.pa1) +
                " B=" + shape_str(k.B) + " at " + pose_str(k.pb) + " (static)";
            break;
    }
    if (k.type != QType::Pair)
        o += " | truth " + std::string(k.truth.hit ? "hit toi " + fmt(double(k.truth.toi)) : "miss");
    return o + " size " + fmt(k.truth.size);
}
std::string answer_str(const Answer& a) {
    static const char* st[] = {"answered", "error", "crash", "hang"};
    return std::string(st[a.status]) + " verdict " + std::to_string(a.verdict) + " value " + fmt(a.value) +
           (a.capped ? " (cap)" : "");
}

}  // namespace

int main(int argc, char** argv) {
    const std::string csv = argc > 1 ? argv[1] : "bench/results/stability.csv";
    if (argc > 1 && argv[1][0] == '-') {
        std::printf("usage: bench_stability [CSV]   (default bench/results/stability.csv)\n");
        return 0;
    }
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Family> fams;
    fams.push_back(near_contact("near_contact", 101, 1.0, 0, 8));
    fams.push_back(exact_touching());
    fams.push_back(parallel_faces());
    fams.push_back(needles());
    fams.push_back(flat_thin());
    fams.push_back(near_contact("scale_1e-4", 111, 1e-4, 0, 6));
    fams.push_back(near_contact("scale_1e4", 112, 1e4, 0, 6));
    fams.push_back(near_contact("offset_1e6", 113, 1.0, 1e6, 6));
    fams.push_back(near_contact("offset_1e8", 114, 1.0, 1e8, 6));
    fams.push_back(large_hulls());
    fams.push_back(grazing());
    fams.push_back(casts_in_contact());
    fams.push_back(rotating(
        "rotation_near_pi", 121,
        [](int i) {
            const double eps = std::pow(10.0, -double(1 + (i / 4) % 9));  // 1e-1 .. 1e-9
            return (i / 36) % 2 ? M_PI - eps : -(M_PI - eps);
        },
        false));
    fams.push_back(rotating(
        "tiny_rotation", 122,
        [](int i) {
            const double a = std::pow(10.0, -double(3 + 3 * ((i / 3) % 5)));  // 1e-3 .. 1e-15
            return (i / 15) % 2 ? a : -a;
        },
        true));
    fams.push_back(arg_swaps());
    fams.push_back(parallel_cylinders());
    fams.push_back(coaxial_cylinders());

    // Truths, and the hit-rate bounds: every family must have judged cases of both outcomes.
    bool one_sided = false;
    for (Family& f : fams) {
        int pos[4] = {0, 0, 0, 0}, neg[4] = {0, 0, 0, 0}, unjudged[4] = {0, 0, 0, 0}, count[4] = {0, 0, 0, 0};
        int disagree = 0;
        for (Case& k : f.cases) {
            if (k.type == QType::Cast) {
                // Translations that are exactly end - start: methods told end poses (motion casts,
                // FCL, Bullet) then see the very motion the shape cast and the truth see.
                for (int i = 0; i < 3; ++i) {
                    k.ta[size_t(i)] = (k.pa.p[size_t(i)] + k.ta[size_t(i)]) - k.pa.p[size_t(i)];
                    k.tb[size_t(i)] = (k.pb.p[size_t(i)] + k.tb[size_t(i)]) - k.pb.p[size_t(i)];
                }
            }
            compute_truth(k);
            if ((k.type == QType::Cast || k.type == QType::Ray) && !refine_cast_truth(k))
                ++disagree, k.truth.decided = false;
            const int t = int(k.type);
            ++count[t];
            if (k.type == QType::Pair) {
                if (std::fabs(double(k.truth.dist)) <= kBand * k.truth.size)
                    ++unjudged[t];
                else
                    (k.truth.dist < 0 ? pos[t] : neg[t])++;
            } else if (!k.truth.decided || k.truth.grazing)
                ++unjudged[t];
            else
                (k.truth.hit ? pos[t] : neg[t])++;
        }
        static const char* tn[] = {"pairs", "casts", "rays", "motions"};
        std::printf("family %-17s", f.name.c_str());
        for (int t = 0; t < 4; ++t) {
            if (!count[t]) continue;
            std::printf("  %s %d (%s %d, %s %d, in the band %d)", tn[t], count[t], t ? "hit" : "intersecting", pos[t],
                        t ? "miss" : "separated", neg[t], unjudged[t]);
            if (pos[t] == 0 || neg[t] == 0) {
                std::printf(" ONE-SIDED");
                one_sided = true;
            }
        }
        if (disagree) std::printf("  [%d casts/rays: the cast and pair oracles disagree, left unjudged]", disagree);
        std::printf("\n");
        std::fflush(stdout);
    }
    std::fflush(stdout);

    // Run every applicable method on every family.
    FILE* out = std::fopen(csv.c_str(), "w");
    if (!out) {
        std::fprintf(stderr, "cannot write %s\n", csv.c_str());
        return 1;
    }
    std::fprintf(
        out, "method,family,cases,failures,failure_rate,worst_error,crashes,hangs,caps,method_index,family_index\n");
    std::vector<std::vector<double>> rate(kMethods, std::vector<double>(fams.size(), -1));
    std::vector<std::string> repro;
    for (int mi = 0; mi < kMethods; ++mi) {
        const Method m = Method(mi);
        for (size_t fi = 0; fi < fams.size(); ++fi) {
            const Family& f = fams[fi];
            std::vector<Case> cases;
            for (const Case& k : f.cases)
                if (applies(m, k.type)) cases.push_back(k);
            if (cases.empty()) continue;
            const std::vector<Record> rec = run_batch(m, cases, f.swap);
            int failures = 0, crashes = 0, hangs = 0, caps = 0;
            double worst = 0;
            bool first = true;
            for (size_t i = 0; i < cases.size(); ++i) {
                const Verdict v =
                    f.swap ? judge_pair(m, cases[i], rec[i].a[0], rec[i].a[1]) : judge(m, cases[i], rec[i].a[0]);
                crashes += rec[i].a[0].status == 2 || (f.swap && rec[i].a[1].status == 2);
                hangs += rec[i].a[0].status == 3 || (f.swap && rec[i].a[1].status == 3);
                caps += rec[i].a[0].capped || (f.swap && rec[i].a[1].capped);
                if (v.err_valid) worst = std::max(worst, v.err);
                if (!v.fail) continue;
                ++failures;
                if (first) {
                    first = false;
                    std::string line = "REPRO " + std::string(kMethodName[m]) + " " + f.name + " case " +
                                       std::to_string(i) + ": " + v.why + " | " + case_str(cases[i]) + " | answer " +
                                       answer_str(rec[i].a[0]);
                    if (f.swap) line += " | swapped answer " + answer_str(rec[i].a[1]);
                    repro.push_back(line);
                }
            }
            const double fr = double(failures) / double(cases.size());
            rate[size_t(mi)][fi] = fr;
            std::fprintf(out, "%s,%s,%zu,%d,%.6f,%.3g,%d,%d,%d,%d,%zu\n", kMethodName[m], f.name.c_str(), cases.size(),
                         failures, fr, worst, crashes, hangs, caps, mi, fi);
            std::fflush(out);
        }
    }
    std::fclose(out);

    // The table: methods as rows, families as columns, failure rates in percent.
    std::printf("\nfailure rate (%%) by method and family ('-': not applicable)\n%-20s", "method");
    for (const Family& f : fams) std::printf(" %9.9s", f.name.c_str());
    std::printf("\n");
    for (int mi = 0; mi < kMethods; ++mi) {
        std::printf("%-20s", kMethodName[mi]);
        for (size_t fi = 0; fi < fams.size(); ++fi) {
            const double fr = rate[size_t(mi)][fi];
            if (fr < 0)
                std::printf(" %9s", "-");
            else
                std::printf(" %9.1f", 100 * fr);
        }
        std::printf("\n");
    }
    std::printf("\nreproducers (first failing case per method and family, full precision):\n");
    for (const std::string& s : repro) std::printf("%s\n", s.c_str());
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("\nwrote %s in %.1f s\n", csv.c_str(), secs);
    if (one_sided) {
        std::printf("a family is one-sided (see the family lines above): the table would not mean anything\n");
        return 2;
    }
    return 0;
}
