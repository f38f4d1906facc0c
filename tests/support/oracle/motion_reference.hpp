// SPDX-License-Identifier: MIT
// Test reference for motion casts: the first contact of two shapes that translate and rotate over
// the step, proven by conservative sampling of their exact distance, independent of the cast.
//
// Motion (long double, written here again, not taken from the library's Motion): the local origin
// moves linearly; the orientation is the spherical linear interpolation of the two unit
// quaternions along the shortest arc, which is a constant angular velocity about a fixed world
// axis. Distance d(t) of the bodies: exact in long double for pairs of cores (points, segments,
// spheres, capsules), cores against polytopes (box, hull) and polytope pairs (polytope_oracle),
// cores against cylinders and cones (exact point distances minimised along the core); GJK,
// certified by its relative-error rule, only for cylinders and cones against boxes, hulls,
// cylinders and cones. Lipschitz bound:
// |d(t + h) - d(t)| <= L h with L = |dp_B - dp_A| + rho_A alpha_A + rho_B alpha_B (rho the exact
// extreme radius about the rotation axis, alpha the angle per step), so no contact lies in
// [t, t + d(t) / L): stepping by that much (conservative advancement on the exact distance)
// proves where the first contact is; the first t with d(t) <= 1e-12 * size is the reference time.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "gjk/gjk.hpp"
#include "math/math.hpp"
#include "oracle/cast_oracle.hpp"
#include "oracle/polytope_oracle.hpp"
#include "shapes/shape.hpp"
#include "world/world.hpp"

namespace motion_ref {

using cast_oracle::Body;
using cast_oracle::Kind;
using cast_oracle::P3;
using cast_oracle::Real;

struct LQuat {
    Real x = 0, y = 0, z = 0, w = 1;
};
inline Real qdot(LQuat a, LQuat b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
inline LQuat qnormalized(LQuat q) {
    const Real n = std::sqrt(qdot(q, q));
    return {q.x / n, q.y / n, q.z / n, q.w / n};
}

// One body's motion over the step, in long double.
struct LMotion {
    P3 p0, p1;
    LQuat q0, q1;      // unit; q1 on q0's side (q0.q1 >= 0): the shortest arc
    Real phi = 0;      // angle between q0 and q1 on the 4D sphere: half the rotation angle
    P3 axis{0, 0, 1};  // world rotation axis (unit)
    Real angle = 0;    // rotation per step, in [0, pi]

    LMotion() = default;
    LMotion(const kairos::Pose& s, const kairos::Pose& e) {
        p0 = {s.position.x, s.position.y, s.position.z};
        p1 = {e.position.x, e.position.y, e.position.z};
        q0 = qnormalized({s.orientation.x, s.orientation.y, s.orientation.z, s.orientation.w});
        q1 = qnormalized({e.orientation.x, e.orientation.y, e.orientation.z, e.orientation.w});
        // The shortest arc: q1 on q0's side. At exactly pi both ways are shortest; the tie follows
        // the sign the library's Motion reads (w of q_end q_start^-1 in double), so both turn
        // the same way.
        const kairos::Quat rel =
            e.orientation * kairos::Quat{-s.orientation.x, -s.orientation.y, -s.orientation.z, s.orientation.w};
        const Real side = std::fabs(qdot(q0, q1)) > Real(1e-12) ? qdot(q0, q1) : Real(rel.w);
        if (side < 0) q1 = {-q1.x, -q1.y, -q1.z, -q1.w};
        const LQuat dm{q1.x - q0.x, q1.y - q0.y, q1.z - q0.z, q1.w - q0.w};
        const LQuat dp{q1.x + q0.x, q1.y + q0.y, q1.z + q0.z, q1.w + q0.w};
        phi = 2 * std::atan2(std::sqrt(qdot(dm, dm)), std::sqrt(qdot(dp, dp)));
        angle = 2 * phi;
        // Axis of q1 q0^-1 (vector part of the relative rotation).
        const LQuat c{-q0.x, -q0.y, -q0.z, q0.w};
        const LQuat r{
            q1.w * c.x + q1.x * c.w + q1.y * c.z - q1.z * c.y, q1.w * c.y - q1.x * c.z + q1.y * c.w + q1.z * c.x,
            q1.w * c.z + q1.x * c.y - q1.y * c.x + q1.z * c.w, q1.w * c.w - q1.x * c.x - q1.y * c.y - q1.z * c.z};
        const Real s2 = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
        if (s2 > 0) axis = {r.x / s2, r.y / s2, r.z / s2};
    }

    P3 position(Real t) const { return p0 + t * (p1 - p0); }
    LQuat orientation(Real t) const {
        if (!(phi > 0)) return q0;
        const Real s = std::sin(phi);
        const Real wa = std::sin((1 - t) * phi) / s, wb = std::sin(t * phi) / s;
        return qnormalized(
            {wa * q0.x + wb * q1.x, wa * q0.y + wb * q1.y, wa * q0.z + wb * q1.z, wa * q0.w + wb * q1.w});
    }
    // Places the body at time t (row-major rotation).
    void place(Body& b, Real t) const {
        const LQuat q = orientation(t);
        const Real xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z, xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
        const Real wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
        const Real R[9] = {1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy), 2 * (xy + wz),    1 - 2 * (xx + zz),
                           2 * (yz - wx),     2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)};
        std::copy(R, R + 9, b.R);
        b.t = position(t);
    }
    // The same pose rounded to double, for GJK.
    kairos::Transform pose(Real t) const {
        Body tmp;
        place(tmp, t);
        kairos::Transform p;
        for (int i = 0; i < 3; ++i)
            p.rotation.r[i] = {double(tmp.R[3 * i]), double(tmp.R[3 * i + 1]), double(tmp.R[3 * i + 2])};
        p.translation = {double(tmp.t.x), double(tmp.t.y), double(tmp.t.z)};
        return p;
    }
};

// Distance of x from the line through the origin along unit u.
inline Real axis_distance(P3 x, P3 u) {
    const P3 r = x - cast_oracle::dot(x, u) * u;
    return cast_oracle::norm(r);
}
// Largest distance from the axis of the rim circles (radius r, heights +-h, axis z).
inline Real rim_distance(Real r, Real h, P3 u) {
    const Real s = std::sqrt(u.x * u.x + u.y * u.y);
    const Real nearest = std::max(Real(0), h * std::fabs(u.z) - r * s);
    return std::sqrt(std::max(Real(0), r * r + h * h - nearest * nearest));
}

// Exact extreme radius of the body about the unit local axis u (distance of a convex set's
// points from a line is convex, so its maximum is at a vertex, a rim point or the apex).
inline Real extreme_radius(const Body& b, P3 u) {
    const Real s = std::sqrt(u.x * u.x + u.y * u.y);
    switch (b.kind) {
        case Kind::Point:
            return 0;
        case Kind::Segment:
            return b.half * s;
        case Kind::Sphere:
            return b.radius;
        case Kind::Capsule:
            return b.half * s + b.radius;
        case Kind::Cylinder:
            return rim_distance(b.radius, b.half, u);
        case Kind::Cone:
            return std::max(b.half * s, rim_distance(b.radius, b.half, u));
        case Kind::Box:
        case Kind::Hull: {
            Real m = 0;
            for (const P3& v : b.local_poly.v) m = std::max(m, axis_distance(v, u));
            return m;
        }
    }
    return 0;
}

inline bool is_core(Kind k) { return cast_oracle::has_core(k); }
inline bool is_poly(Kind k) { return k == Kind::Box || k == Kind::Hull; }

// The local polytope moved to the world (faces, normals, edges kept).
inline oracle::Polytope world_polytope(const Body& b) {
    oracle::Polytope w = b.local_poly;
    for (P3& v : w.v) v = b.to_world(v);
    for (size_t f = 0; f < w.normals.size(); ++f) {
        const P3 n = w.normals[f];
        const P3 nw{b.R[0] * n.x + b.R[1] * n.y + b.R[2] * n.z, b.R[3] * n.x + b.R[4] * n.y + b.R[5] * n.z,
                    b.R[6] * n.x + b.R[7] * n.y + b.R[8] * n.z};
        w.normals[f] = nw;
        w.offsets[f] = w.offsets[f] + cast_oracle::dot(nw, b.t);
    }
    w.scale = 0;
    for (const P3& v : w.v) w.scale = std::max({w.scale, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    return w;
}

// A pair of shapes with their motions: the exact distance at any time and the reference contact.
struct Pair {
    const kairos::Shape* sa;
    const kairos::Shape* sb;
    Body a, b;  // local geometry; poses are set per evaluation
    LMotion ma, mb;
    Real size = 0;  // scale for tolerances: sum of the bounding radii
    Real lipschitz = 0;

    Pair(const kairos::Shape& shape_a, const Body& body_a, const kairos::Pose& a0, const kairos::Pose& a1,
         const kairos::Shape& shape_b, const Body& body_b, const kairos::Pose& b0, const kairos::Pose& b1)
        : sa(&shape_a), sb(&shape_b), a(body_a), b(body_b), ma(a0, a1), mb(b0, b1) {
        auto rho = [](const Body& body, const LMotion& m) {
            if (!(m.angle > 0)) return Real(0);
            Body placed = body;
            m.place(placed, 0);
            return extreme_radius(body, placed.dir_to_local(m.axis));
        };
        const P3 dv = (mb.p1 - mb.p0) - (ma.p1 - ma.p0);
        lipschitz = cast_oracle::norm(dv) + rho(a, ma) * ma.angle + rho(b, mb) * mb.angle;
        size = bounding(a) + bounding(b);
    }

    static Real bounding(const Body& body) {
        Real m = 0;
        for (const P3 d : {P3{1, 0, 0}, P3{0, 1, 0}, P3{0, 0, 1}, P3{-1, 0, 0}, P3{0, -1, 0}, P3{0, 0, -1}}) {
            const P3 s = cast_oracle::support_local(body, d);
            m = std::max(m, cast_oracle::norm(s));
        }
        // Supports along the axes bound each coordinate; their norms are within sqrt(3) of the radius.
        return m * std::sqrt(Real(3));
    }

    // Exact distance of the true shapes at time t (0 when they overlap).
    Real distance(Real t) const {
        Body pa = a, pb = b;
        ma.place(pa, t);
        mb.place(pb, t);
        if (is_core(a.kind) && is_core(b.kind)) {
            P3 a0, a1, b0, b1, c1, c2;
            Real ra, rb;
            cast_oracle::core_of(pa, a0, a1, ra);
            cast_oracle::core_of(pb, b0, b1, rb);
            cast_oracle::closest_segments(a0, a1, b0, b1, c1, c2);
            return std::max(cast_oracle::norm(c1 - c2) - ra - rb, Real(0));
        }
        if (is_core(a.kind) != is_core(b.kind) && (is_poly(a.kind) || is_poly(b.kind))) {
            const Body& core = is_core(a.kind) ? pa : pb;
            const Body& poly = is_core(a.kind) ? pb : pa;
            P3 p, q, c1, c2;
            Real r;
            cast_oracle::core_of(core, p, q, r);
            const cast_oracle::WorldPoly w = cast_oracle::world_poly(poly);
            return std::max(cast_oracle::segment_polytope(w, p, q, c1, c2) - r, Real(0));
        }
        if (is_poly(a.kind) && is_poly(b.kind)) {
            const oracle::Result r = oracle::distance(world_polytope(pa), world_polytope(pb));
            return r.intersecting ? Real(0) : r.distance;
        }
        // Points, spheres, segments and capsules against cylinders and cones: the exact distance
        // from a point to the body (cast_oracle), minimised along the core segment by ternary
        // search (the distance to a convex body is convex along a line).
        if (is_core(a.kind) || is_core(b.kind)) {
            const Body& core = is_core(a.kind) ? pa : pb;
            const Body& other = is_core(a.kind) ? pb : pa;
            P3 p, q;
            Real r;
            cast_oracle::core_of(core, p, q, r);
            auto f = [&](Real s) { return cast_oracle::point_distance(other, p + s * (q - p)); };
            Real lo = 0, hi = 1;
            if (cast_oracle::norm(q - p) > 0)
                for (int i = 0; i < 120 && hi - lo > Real(1e-18); ++i) {
                    const Real m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
                    if (f(m1) <= f(m2))
                        hi = m2;
                    else
                        lo = m1;
                }
            const Real best = std::min({f(0), f(1), f((lo + hi) / 2)});
            return std::max(best - r, Real(0));
        }
        // Cylinders and cones: GJK. When it stops on its relative-error rule (1) the distance is
        // certified: the truth lies in [(1 - tol) ||v||, ||v||], since that rule needs a separating
        // plane. Other stops are not trusted: GJK read a flat simplex on a cylinder's or cone's rim
        // as holding the origin (FullSimplex) for shapes 1e-6 apart at tolerance 1e-10 (a finding of
        // this reference). Several tolerances are tried; intersecting only when none certifies.
        // Near contact GJK stalls on curved surfaces before it certifies (about 1e-7 of the size):
        // there the dual below gives the distance.
        P3 seed{0, 0, 1};
        for (const double tol : {1e-9, 1e-7, 1e-5, 1e-3}) {
            const kairos::DistanceResult d = kairos::gjk_distance(*sa, ma.pose(t), *sb, mb.pose(t), tol, 1000);
            if (d.termination == kairos::Termination::RelativeError && !d.intersecting)
                return Real(d.distance) * (1 - Real(tol)) * (1 - Real(1e-12));
            if (!d.intersecting) seed = {d.axis.x, d.axis.y, d.axis.z};
        }
        return dual_distance(pa, pb, seed);
    }

    // The distance by duality: max over |n| <= 1 of sep(n) = -h_A(n) - h_B(-n), n from A toward
    // B, a concave function on a ball (0 when the shapes overlap). Every n gives a lower bound
    // (the separation along n), so the answer is safe however far the search got. The ellipsoid
    // method in three variables, on the exact long double supports, from a ball about `seed`.
    Real dual_distance(const Body& pa, const Body& pb, P3 seed) const {
        auto sep = [&](P3 n, P3& grad) {
            const P3 s_a = cast_oracle::support_world(pa, n), s_b = cast_oracle::support_world(pb, Real(-1) * n);
            grad = s_b - s_a;  // supergradient of the concave sep at n
            return cast_oracle::dot(n, s_b - s_a);
        };
        Real best = 0;
        P3 c = seed;
        const Real ls = cast_oracle::norm(c);
        if (ls > 0) c = (Real(1) / ls) * c;
        Real P[3][3] = {{Real(0.25), 0, 0}, {0, Real(0.25), 0}, {0, 0, Real(0.25)}};
        for (int it = 0; it < 1500; ++it) {
            P3 a;  // the cut keeps {x : a.(x - c) <= 0}
            if (cast_oracle::dot(c, c) > 1) {
                a = c;  // outside the ball
            } else {
                P3 g;
                best = std::max(best, sep(c, g));
                a = Real(-1) * g;
            }
            const Real pa3[3] = {P[0][0] * a.x + P[0][1] * a.y + P[0][2] * a.z,
                                 P[1][0] * a.x + P[1][1] * a.y + P[1][2] * a.z,
                                 P[2][0] * a.x + P[2][1] * a.y + P[2][2] * a.z};
            const Real apa = a.x * pa3[0] + a.y * pa3[1] + a.z * pa3[2];
            if (!(apa > 0)) break;
            const Real inv = 1 / std::sqrt(apa);
            const Real bvec[3] = {pa3[0] * inv, pa3[1] * inv, pa3[2] * inv};
            c = c - Real(0.25) * P3{bvec[0], bvec[1], bvec[2]};
            const Real k = Real(9) / Real(8);
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) P[i][j] = k * (P[i][j] - Real(0.5) * bvec[i] * bvec[j]);
            if (P[0][0] + P[1][1] + P[2][2] < Real(1e-34)) break;
        }
        return best;
    }
    bool uses_gjk() const { return !is_core(a.kind) && !is_core(b.kind) && !(is_poly(a.kind) && is_poly(b.kind)); }

    struct Contact {
        bool decided = true;  // false when the step budget ran out before a verdict
        bool hit = false;
        Real toi = 1;  // first sample with d <= eps * size (no contact before it)
        Real min_distance = std::numeric_limits<Real>::infinity();  // smallest sampled distance
        int steps = 0;
    };

    // Conservative advancement on the exact distance from t = 0.
    Contact first_contact(Real eps = Real(1e-12), int max_steps = 400000) const {
        Contact c;
        Real t = 0;
        const Real threshold = eps * size;
        for (;;) {
            if (c.steps >= max_steps) {
                c.decided = false;
                c.toi = t;
                return c;
            }
            ++c.steps;
            const Real d = distance(t);
            c.min_distance = std::min(c.min_distance, d);
            if (d <= threshold) {
                c.hit = true;
                c.toi = t;
                return c;
            }
            if (!(lipschitz > 0)) return c;  // nothing moves relative to the other
            // Double-precision supports of GJK: a hair shorter.
            const Real h = (uses_gjk() ? d - size * Real(1e-15) : d) / lipschitz;
            if (!(h > 0)) {
                c.decided = false;
                c.toi = t;
                return c;
            }
            if (t + h > 1) return c;
            // A step below the time resolution: the distance would stall above the threshold.
            if (t + h == t) {
                c.decided = false;
                c.toi = t;
                return c;
            }
            t += h;
        }
    }
};

}  // namespace motion_ref
