// SPDX-License-Identifier: MIT
// Test oracle for translational casts: the true first time of impact of two convex shapes moving by
// constant translations, in long double, independent of the library (no GJK, no library supports).
//
// A and B translate by ta and tb; they touch at lambda when lambda r is in M = A - B, r = tb - ta.
// Four independent ways to the truth:
// - polytopes (box, hull, point, segment): M is the intersection of the half-spaces n.z <= h_M(n)
//   over the candidate normals (faces of A, faces of B, cross products of their edges), which hold
//   every facet normal of M. The ray enters at max over n.r < 0 of h_M(n) / (n.r) (separating axes in
//   time): exact up to long double rounding, with the entering facet's normal.
// - sphere/sphere and sphere/box: closed forms (a quadratic; the ray against the rounded box as a
//   union of three slabs, twelve edge cylinders and eight corner balls).
// - spheres and capsules with polytopes or with each other: the distance between the cores moving
//   linearly is convex in lambda, so the first lambda where it reaches the sum of the radii is found
//   by ternary search for the minimum and bisection below it, on exact core distances.
// - anything (cylinders and cones included): by duality lambda_enter = -min over w perpendicular to r
//   of h_M(-r/|r| + w) / |r|, the minimum of a convex function of two variables, found by the
//   ellipsoid method on the exact support functions (the same for the exit with +r/|r|).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "oracle/polytope_oracle.hpp"

namespace cast_oracle {

using oracle::cross;
using oracle::dot;
using oracle::norm;
using oracle::P3;
using oracle::Real;

enum class Kind { Point, Segment, Sphere, Box, Capsule, Cylinder, Cone, Hull };

// A shape placed in the world: x_world = R x_local + t (R row-major, from the double pose).
struct Body {
    Kind kind = Kind::Point;
    Real radius = 0, half = 0;    // sphere/capsule/cylinder/cone radius; segment/capsule/cylinder/cone half height
    P3 half_extents;              // box
    std::vector<P3> verts;        // hull, local frame
    oracle::Polytope local_poly;  // hull (and box) faces for point distances, local frame
    Real R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    P3 t;

    P3 to_world(P3 q) const {
        return {R[0] * q.x + R[1] * q.y + R[2] * q.z + t.x, R[3] * q.x + R[4] * q.y + R[5] * q.z + t.y,
                R[6] * q.x + R[7] * q.y + R[8] * q.z + t.z};
    }
    P3 dir_to_local(P3 d) const {
        return {R[0] * d.x + R[3] * d.y + R[6] * d.z, R[1] * d.x + R[4] * d.y + R[7] * d.z,
                R[2] * d.x + R[5] * d.y + R[8] * d.z};
    }
    P3 to_local(P3 x) const { return dir_to_local(x - t); }
};

inline Body make_body(Kind k) {
    Body b;
    b.kind = k;
    return b;
}

// The faces (triangulated), outward normals, offsets and edges of the convex hull of `pts`, by
// brute force over every triple: a triple is a face when all points lie on one side of its
// plane, and that side decides the orientation (no reference point needed: a reference taken
// inside the bounding box can lie outside a thin hull and flip faces).
inline oracle::Polytope hull_polytope(const std::vector<P3>& pts) {
    oracle::Polytope p;
    p.v = pts;
    const size_t n = pts.size();
    Real extent = 0;
    for (const P3& a : pts)
        for (const P3& b : pts) extent = std::max(extent, norm(a - b));
    for (const P3& q : pts) p.scale = std::max({p.scale, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    const Real tol = extent * Real(1e-12);
    std::vector<std::array<int, 2>> edges;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k) {
                P3 nrm = cross(pts[j] - pts[i], pts[k] - pts[i]);
                const Real len = norm(nrm);
                if (!(len > extent * extent * Real(1e-14))) continue;  // collinear triple
                nrm = (Real(1) / len) * nrm;
                Real hi = -std::numeric_limits<Real>::infinity(), lo = std::numeric_limits<Real>::infinity();
                for (const P3& q : pts) {
                    const Real d = dot(nrm, q - pts[i]);
                    hi = std::max(hi, d);
                    lo = std::min(lo, d);
                }
                if (hi > tol && lo < -tol) continue;  // points on both sides: not a face
                if (hi > tol) nrm = Real(-1) * nrm;   // all below -> outward is +nrm; else -nrm
                p.faces.push_back({int(i), int(j), int(k)});
                p.normals.push_back(nrm);
                p.offsets.push_back(dot(nrm, pts[i]));
                edges.push_back({int(i), int(j)});
                edges.push_back({int(i), int(k)});
                edges.push_back({int(j), int(k)});
            }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    p.edges = std::move(edges);
    return p;
}

inline void finish_body(Body& b) {
    if (b.kind == Kind::Hull) b.local_poly = hull_polytope(b.verts);
    if (b.kind == Kind::Box) {
        std::vector<P3> v;
        for (int i = 0; i < 8; ++i)
            v.push_back({(i & 1 ? 1 : -1) * b.half_extents.x, (i & 2 ? 1 : -1) * b.half_extents.y,
                         (i & 4 ? 1 : -1) * b.half_extents.z});
        b.local_poly = hull_polytope(v);
    }
}

inline Real hypot2(Real x, Real y) { return std::sqrt(x * x + y * y); }

// Support point of the body in local direction n (local frame).
inline P3 support_local(const Body& b, P3 n) {
    auto sgn = [](Real v) { return v < 0 ? Real(-1) : Real(1); };
    switch (b.kind) {
        case Kind::Point:
            return {};
        case Kind::Segment:
            return {0, 0, sgn(n.z) * b.half};
        case Kind::Sphere: {
            const Real l = norm(n);
            return l > 0 ? (b.radius / l) * n : P3{0, 0, b.radius};
        }
        case Kind::Box:
            return {sgn(n.x) * b.half_extents.x, sgn(n.y) * b.half_extents.y, sgn(n.z) * b.half_extents.z};
        case Kind::Capsule: {
            const Real l = norm(n);
            const P3 c{0, 0, sgn(n.z) * b.half};
            return l > 0 ? c + (b.radius / l) * n : c;
        }
        case Kind::Cylinder: {
            const Real l = hypot2(n.x, n.y);
            const Real z = sgn(n.z) * b.half;
            return l > 0 ? P3{b.radius * n.x / l, b.radius * n.y / l, z} : P3{0, 0, z};
        }
        case Kind::Cone: {
            const Real l = hypot2(n.x, n.y);
            if (b.half * n.z >= b.radius * l - b.half * n.z) return {0, 0, b.half};
            return l > 0 ? P3{b.radius * n.x / l, b.radius * n.y / l, -b.half} : P3{0, 0, -b.half};
        }
        case Kind::Hull: {
            P3 best = b.verts[0];
            Real bd = dot(n, best);
            for (const P3& v : b.verts)
                if (dot(n, v) > bd) {
                    bd = dot(n, v);
                    best = v;
                }
            return best;
        }
    }
    return {};
}

inline P3 support_world(const Body& b, P3 n) { return b.to_world(support_local(b, b.dir_to_local(n))); }
inline Real support_value(const Body& b, P3 n) { return dot(n, support_world(b, n)); }

// ---- Exact distances from a point (world) to a body -----------------------------------------------

inline P3 closest_on_segment(P3 x, P3 a, P3 b) {
    const P3 ab = b - a;
    const Real l2 = dot(ab, ab);
    Real s = l2 > 0 ? dot(x - a, ab) / l2 : 0;
    s = std::clamp(s, Real(0), Real(1));
    return a + s * ab;
}

// Closest point of triangle abc to x (regions by barycentric tests on the plane).
inline P3 closest_on_triangle(P3 x, P3 a, P3 b, P3 c) {
    const P3 n = cross(b - a, c - a);
    const Real n2 = dot(n, n);
    if (n2 > 0) {
        const P3 q = x - (dot(x - a, n) / n2) * n;
        if (dot(cross(b - q, c - q), n) >= 0 && dot(cross(c - q, a - q), n) >= 0 && dot(cross(a - q, b - q), n) >= 0)
            return q;
    }
    P3 best = closest_on_segment(x, a, b);
    for (const P3 p : {closest_on_segment(x, b, c), closest_on_segment(x, c, a)})
        if (dot(p - x, p - x) < dot(best - x, best - x)) best = p;
    return best;
}

inline Real polytope_point_distance(const oracle::Polytope& p, P3 q) {
    if (oracle::plane_excess(p, q) <= 0) return 0;
    Real best = std::numeric_limits<Real>::infinity();
    for (const auto& f : p.faces) {
        const P3 c = closest_on_triangle(q, p.v[f[0]], p.v[f[1]], p.v[f[2]]);
        best = std::min(best, dot(c - q, c - q));
    }
    return std::sqrt(best);
}

// Distance from x (world) to the body; 0 inside.
inline Real point_distance(const Body& b, P3 x) {
    const P3 q = b.to_local(x);
    switch (b.kind) {
        case Kind::Point:
            return norm(q);
        case Kind::Segment:
            return norm(q - closest_on_segment(q, {0, 0, -b.half}, {0, 0, b.half}));
        case Kind::Sphere:
            return std::max(norm(q) - b.radius, Real(0));
        case Kind::Capsule:
            return std::max(norm(q - closest_on_segment(q, {0, 0, -b.half}, {0, 0, b.half})) - b.radius, Real(0));
        case Kind::Box: {
            const P3 e{std::max(std::fabs(q.x) - b.half_extents.x, Real(0)),
                       std::max(std::fabs(q.y) - b.half_extents.y, Real(0)),
                       std::max(std::fabs(q.z) - b.half_extents.z, Real(0))};
            return norm(e);
        }
        case Kind::Cylinder: {
            const Real dr = std::max(hypot2(q.x, q.y) - b.radius, Real(0)),
                       dz = std::max(std::fabs(q.z) - b.half, Real(0));
            return hypot2(dr, dz);
        }
        case Kind::Cone: {
            // In the half-plane (rho, z) through the axis and q: the triangle apex (0, h), rim
            // (r, -h), base centre (0, -h); the axis side is interior in 3D.
            const Real rho = hypot2(q.x, q.y), z = q.z, h = b.half, r = b.radius;
            const bool inside = z >= -h && z <= h && rho * (2 * h) <= r * (h - z);
            if (inside) return 0;
            const P3 p{rho, z, 0};
            const P3 c1 = closest_on_segment(p, {0, h, 0}, {r, -h, 0});
            const P3 c2 = closest_on_segment(p, {0, -h, 0}, {r, -h, 0});
            return std::sqrt(std::min(dot(c1 - p, c1 - p), dot(c2 - p, c2 - p)));
        }
        case Kind::Hull:
            return polytope_point_distance(b.local_poly, q);
    }
    return 0;
}

// ---- Truth ---------------------------------------------------------------------------------------

struct Truth {
    bool hit = false;
    Real toi = 1;  // first contact in [0, 1]
    P3 normal;     // unit, from A toward B (outward of M at the hit); zero when ambiguous
    bool start_overlap = false;
    Real chord = 0;        // (exit - enter) * |r| when the line meets M: small means a grazing ray
    bool grazing = false;  // hit or miss is within rounding of the other: skip classification
};

// Support function of M = A - B.
inline Real support_m(const Body& a, const Body& b, P3 n) {
    return support_value(a, n) + support_value(b, Real(-1) * n);
}
inline P3 support_point_m(const Body& a, const Body& b, P3 n) {
    return support_world(a, n) - support_world(b, Real(-1) * n);
}

inline Real size_of(const Body& a, const Body& b) {
    Real s = 0;
    for (const P3 d : {P3{1, 0, 0}, P3{0, 1, 0}, P3{0, 0, 1}}) {
        s = std::max(s, support_value(a, d) + support_value(a, Real(-1) * d));
        s = std::max(s, support_value(b, d) + support_value(b, Real(-1) * d));
    }
    return s;
}

// Classification from the line's entry and exit parameters (enter <= exit when it meets M).
inline Truth classify(Real enter, Real exit, P3 n_enter, Real rlen, Real size) {
    Truth t;
    t.chord = (exit - enter) * rlen;
    const Real band = size * Real(1e-9);
    if (!(enter <= exit) || enter > 1 || exit < 0) {
        t.hit = false;
        // Within the band of touching: the ray grazes M, or touches it at the end points.
        t.grazing =
            (enter <= exit + band / std::max(rlen, Real(1e-300)) && enter <= 1 + band / std::max(rlen, Real(1e-300)) &&
             exit >= -band / std::max(rlen, Real(1e-300))) ||
            (enter > exit && (enter - exit) * rlen < band);
        return t;
    }
    t.hit = true;
    t.toi = std::max(enter, Real(0));
    t.start_overlap = enter <= 0;
    t.normal = n_enter;
    t.grazing = t.chord < band || (1 - enter) * rlen < band || exit * rlen < band;
    return t;
}

// A convex polytope: vertices (world), face normals, edges.
struct Poly {
    std::vector<P3> v;
    std::vector<P3> normals;
    std::vector<std::array<int, 2>> edges;
};

inline Poly poly_of(const Body& b) {
    Poly p;
    switch (b.kind) {
        case Kind::Point:
            p.v.push_back(b.to_world({}));
            break;
        case Kind::Segment:
            p.v = {b.to_world({0, 0, -b.half}), b.to_world({0, 0, b.half})};
            p.edges = {{0, 1}};
            break;
        case Kind::Box:
        case Kind::Hull: {
            const oracle::Polytope& lp = b.local_poly;
            for (const P3& q : lp.v) p.v.push_back(b.to_world(q));
            for (const auto& f : lp.faces) p.normals.push_back(cross(p.v[f[1]] - p.v[f[0]], p.v[f[2]] - p.v[f[0]]));
            p.edges = lp.edges;
            break;
        }
        default:
            break;
    }
    return p;
}

inline bool is_polytope(Kind k) { return k == Kind::Point || k == Kind::Segment || k == Kind::Box || k == Kind::Hull; }

// Exact time of impact of two polytopes (separating axes in time over the candidate normals).
inline Truth polytope_toi(const Body& a, const Body& b, P3 r) {
    const Poly pa = poly_of(a), pb = poly_of(b);
    std::vector<P3> axes = pa.normals;
    axes.insert(axes.end(), pb.normals.begin(), pb.normals.end());
    for (const auto& ea : pa.edges)
        for (const auto& eb : pb.edges) axes.push_back(cross(pa.v[ea[1]] - pa.v[ea[0]], pb.v[eb[1]] - pb.v[eb[0]]));
    Real enter = -std::numeric_limits<Real>::infinity(), exit = std::numeric_limits<Real>::infinity();
    P3 n_enter{};
    bool never = false;
    // Both orientations of every candidate: each gives a supporting half-space of M.
    for (size_t k = 0; k < 2 * axes.size(); ++k) {
        const P3& n0 = axes[k / 2];
        const Real len = norm(n0);
        if (!(len > 0)) continue;
        const P3 n = (k % 2 ? Real(-1) : Real(1)) / len * n0;
        Real ha = -std::numeric_limits<Real>::infinity(), hb = -std::numeric_limits<Real>::infinity();
        for (const P3& q : pa.v) ha = std::max(ha, dot(n, q));
        for (const P3& q : pb.v) hb = std::max(hb, -dot(n, q));
        const Real h = ha + hb, nr = dot(n, r);
        if (nr < 0) {
            if (h / nr > enter) {
                enter = h / nr;
                n_enter = n;
            }
        } else if (nr > 0) {
            exit = std::min(exit, h / nr);
        } else if (h < 0) {
            never = true;
        }
    }
    const Real rlen = norm(r);
    if (never) {
        Truth t;
        t.grazing = false;
        return t;
    }
    if (rlen == 0) {  // no motion: enter/exit are +-infinity when overlapping
        Truth t;
        t.hit = true;
        t.toi = 0;
        t.start_overlap = true;
        return t;
    }
    return classify(enter, exit, n_enter, rlen, size_of(a, b));
}

// ---- Spheres and capsules: cores and radii ----------------------------------------------------

// Segment [p, q] against the polytope given by world vertices/faces: closest pair distance.
struct WorldPoly {
    std::vector<P3> v;
    std::vector<std::array<int, 3>> faces;
    std::vector<P3> normals;  // unit outward
    std::vector<Real> offsets;
    std::vector<std::array<int, 2>> edges;
};

inline WorldPoly world_poly(const Body& b) {
    WorldPoly w;
    const oracle::Polytope& lp = b.local_poly;
    for (const P3& q : lp.v) w.v.push_back(b.to_world(q));
    w.faces = lp.faces;
    w.edges = lp.edges;
    for (size_t f = 0; f < lp.faces.size(); ++f) {
        P3 n = cross(w.v[lp.faces[f][1]] - w.v[lp.faces[f][0]], w.v[lp.faces[f][2]] - w.v[lp.faces[f][0]]);
        n = (Real(1) / norm(n)) * n;
        // Orient outward: every vertex lies below.
        Real off = dot(n, w.v[lp.faces[f][0]]);
        Real mx = -std::numeric_limits<Real>::infinity();
        for (const P3& q : w.v) mx = std::max(mx, dot(n, q) - off);
        if (mx > std::fabs(off) * Real(1e-9) + Real(1e-30)) {
            n = Real(-1) * n;
            off = -off;
        }
        w.normals.push_back(n);
        w.offsets.push_back(off);
    }
    return w;
}

// Closest points of segments [p1, q1] and [p2, q2] (clamped parameters, long double).
inline void closest_segments(P3 p1, P3 q1, P3 p2, P3 q2, P3& c1, P3& c2) {
    const P3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const Real a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
    Real s = 0, t = 0;
    if (a <= 0 && e <= 0) {
        c1 = p1;
        c2 = p2;
        return;
    }
    if (a <= 0) {
        t = std::clamp(f / e, Real(0), Real(1));
    } else {
        const Real c = dot(d1, r);
        if (e <= 0) {
            s = std::clamp(-c / a, Real(0), Real(1));
        } else {
            const Real b = dot(d1, d2), denom = a * e - b * b;
            s = denom > 0 ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : 0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = std::clamp(-c / a, Real(0), Real(1));
            } else if (t > 1) {
                t = 1;
                s = std::clamp((b - c) / a, Real(0), Real(1));
            }
        }
    }
    c1 = p1 + s * d1;
    c2 = p2 + t * d2;
}

// Closest points between the segment [p, q] (a point when p == q) and the solid polytope.
inline Real segment_polytope(const WorldPoly& w, P3 p, P3 q, P3& on_seg, P3& on_poly) {
    // Clip the segment by the face planes: a non-empty piece means they intersect.
    Real lo = 0, hi = 1;
    const P3 d = q - p;
    for (size_t f = 0; f < w.normals.size() && lo <= hi; ++f) {
        const Real dn = dot(w.normals[f], d), s = w.offsets[f] - dot(w.normals[f], p);
        if (dn == 0) {
            if (s < 0) hi = -1;
        } else if (dn > 0) {
            hi = std::min(hi, s / dn);
        } else {
            lo = std::max(lo, s / dn);
        }
    }
    if (lo <= hi) {
        on_seg = on_poly = p + lo * d;
        return 0;
    }
    Real best = std::numeric_limits<Real>::infinity();
    auto consider = [&](P3 a, P3 b) {
        const Real d2 = dot(a - b, a - b);
        if (d2 < best) {
            best = d2;
            on_seg = a;
            on_poly = b;
        }
    };
    for (const auto& f : w.faces) {
        consider(p, closest_on_triangle(p, w.v[f[0]], w.v[f[1]], w.v[f[2]]));
        consider(q, closest_on_triangle(q, w.v[f[0]], w.v[f[1]], w.v[f[2]]));
    }
    for (const auto& e : w.edges) {
        P3 c1, c2;
        closest_segments(p, q, w.v[e[0]], w.v[e[1]], c1, c2);
        consider(c1, c2);
    }
    return std::sqrt(best);
}

inline bool is_round(Kind k) { return k == Kind::Sphere || k == Kind::Capsule; }
inline bool has_core(Kind k) { return k == Kind::Point || k == Kind::Segment || is_round(k); }

// The core segment (world; equal ends for points and spheres) and radius of a body with a core.
inline void core_of(const Body& b, P3& p, P3& q, Real& radius) {
    const Real h = (b.kind == Kind::Segment || b.kind == Kind::Capsule) ? b.half : 0;
    p = b.to_world({0, 0, -h});
    q = b.to_world({0, 0, h});
    radius = is_round(b.kind) ? b.radius : 0;
}

// Distance between the cores at lambda (A moved by lambda * ta, B by lambda * tb), closest points.
struct CorePair {
    const Body* a;
    const Body* b;
    P3 ta, tb;
    Real radius = 0;
    bool a_poly = false, b_poly = false;
    WorldPoly wa, wb;
    P3 ap, aq, bp, bq;

    Real distance(Real lambda, P3& ca, P3& cb) const {
        const P3 sa = lambda * ta, sb = lambda * tb;
        if (b_poly) {
            // A's core against polytope B: shift A's core by the relative motion instead.
            const P3 rel = sa - sb;
            P3 c1, c2;
            const Real d = segment_polytope(wb, ap + rel, aq + rel, c1, c2);
            ca = c1 - rel + sa;
            cb = c2 + sb;
            return d;
        }
        if (a_poly) {
            const P3 rel = sb - sa;
            P3 c1, c2;
            const Real d = segment_polytope(wa, bp + rel, bq + rel, c1, c2);
            cb = c1 - rel + sb;
            ca = c2 + sa;
            return d;
        }
        P3 c1, c2;
        closest_segments(ap + sa, aq + sa, bp + sb, bq + sb, c1, c2);
        ca = c1;
        cb = c2;
        return norm(c1 - c2);
    }
};

// First lambda in [0, 1] with core distance <= radius (convex in lambda).
inline Truth round_toi(const Body& a, const Body& b, P3 ta, P3 tb) {
    CorePair cp;
    cp.a = &a;
    cp.b = &b;
    cp.ta = ta;
    cp.tb = tb;
    Real ra = 0, rb = 0;
    if (has_core(a.kind))
        core_of(a, cp.ap, cp.aq, ra);
    else {
        cp.a_poly = true;
        cp.wa = world_poly(a);
    }
    if (has_core(b.kind))
        core_of(b, cp.bp, cp.bq, rb);
    else {
        cp.b_poly = true;
        cp.wb = world_poly(b);
    }
    const Real R = ra + rb;
    P3 ca, cb;
    auto f = [&](Real l) { return cp.distance(l, ca, cb) - R; };
    Truth t;
    const Real size = size_of(a, b);
    const Real f0 = f(0);
    auto normal_at = [&](Real l) {
        cp.distance(l, ca, cb);
        const P3 d = cb - ca;
        const Real n = norm(d);
        return n > 0 ? (Real(1) / n) * d : P3{};
    };
    if (f0 <= 0) {
        t.hit = true;
        t.toi = 0;
        t.start_overlap = true;
        t.grazing = f0 > -size * Real(1e-9);
        t.normal = normal_at(0);
        return t;
    }
    // Ternary search for the minimum of the convex f on [0, 1].
    Real lo = 0, hi = 1;
    for (int i = 0; i < 200 && hi - lo > Real(1e-19); ++i) {
        const Real m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (f(m1) <= f(m2))
            hi = m2;
        else
            lo = m1;
    }
    const Real lm = (lo + hi) / 2, fm = f(lm);
    if (fm > 0) {
        t.hit = false;
        t.grazing = fm < size * Real(1e-9);
        return t;
    }
    lo = 0;
    hi = lm;
    for (int i = 0; i < 200 && hi - lo > Real(0); ++i) {
        const Real m = (lo + hi) / 2;
        if (m == lo || m == hi) break;
        if (f(m) <= 0)
            hi = m;
        else
            lo = m;
    }
    t.hit = true;
    t.toi = hi;
    t.normal = normal_at(hi);
    t.grazing = fm > -size * Real(1e-9);
    return t;
}

// Sphere/sphere: |c + lambda r|... closed form quadratic. A and B both spheres.
inline Truth sphere_sphere_toi(const Body& a, const Body& b, P3 r) {
    // lambda r in A - B = ball(ca - cb, ra + rb): |lambda r - d|^2 = R^2 with d = ca - cb.
    const P3 d = a.t - b.t;
    const Real R = a.radius + b.radius;
    const Real A = dot(r, r), B = -2 * dot(r, d), C = dot(d, d) - R * R;
    Truth t;
    const Real size = size_of(a, b);
    if (C <= 0) {
        t.hit = true;
        t.toi = 0;
        t.start_overlap = true;
        const P3 n = b.t - a.t;
        t.normal = norm(n) > 0 ? (Real(1) / norm(n)) * n : P3{};
        return t;
    }
    const Real disc = B * B - 4 * A * C;
    if (A == 0 || disc < 0) {
        t.grazing = A > 0 && disc > -4 * A * size * size * Real(1e-9);
        return t;
    }
    const Real sq = std::sqrt(disc);
    // Smaller root, written without cancellation.
    const Real q = -(B - sq) / 2;  // B < 0 when approaching
    Real l0 = B < 0 ? C / q : (-B - sq) / (2 * A);
    const Real l1 = (-B + sq) / (2 * A);
    t.chord = (l1 - l0) * std::sqrt(A);
    if (l0 > 1 || l1 < 0) {
        t.grazing = (l0 - 1) * std::sqrt(A) < size * Real(1e-9);
        return t;
    }
    t.hit = true;
    t.toi = l0;
    const P3 n = l0 * r - d;  // outward normal of M at the hit
    t.normal = (Real(1) / norm(n)) * n;
    t.grazing = t.chord < size * Real(1e-9);
    return t;
}

// First entry of the ray p + l d (box frame) into the box of half extents h grown by radius R,
// l unbounded; +inf when never. Also returns the closest box point at the entry.
inline Real ray_rounded_box(P3 p, P3 d, P3 h, Real R, P3& box_point) {
    const Real inf = std::numeric_limits<Real>::infinity();
    auto comp = [](P3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); };
    Real best = inf;
    // Pieces: slab boxes (grown along one axis), edge cylinders, corner balls.
    auto slab = [&](P3 hh) {
        Real lo = -inf, hi = inf;
        for (int i = 0; i < 3; ++i) {
            const Real pi = comp(p, i), di = comp(d, i), hi_i = comp(hh, i);
            if (di == 0) {
                if (std::fabs(pi) > hi_i) return;
            } else {
                Real a = (-hi_i - pi) / di, b = (hi_i - pi) / di;
                if (a > b) std::swap(a, b);
                lo = std::max(lo, a);
                hi = std::min(hi, b);
            }
        }
        if (lo <= hi) best = std::min(best, lo);
    };
    slab({h.x + R, h.y, h.z});
    slab({h.x, h.y + R, h.z});
    slab({h.x, h.y, h.z + R});
    // Edge cylinders: along axis i, at (+-h_j, +-h_k).
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        for (int sj = -1; sj <= 1; sj += 2)
            for (int sk = -1; sk <= 1; sk += 2) {
                const Real oj = comp(p, j) - sj * comp(h, j), ok = comp(p, k) - sk * comp(h, k);
                const Real dj = comp(d, j), dk = comp(d, k);
                const Real A = dj * dj + dk * dk, B = 2 * (oj * dj + ok * dk), C = oj * oj + ok * ok - R * R;
                if (A == 0) continue;
                const Real disc = B * B - 4 * A * C;
                if (disc < 0) continue;
                const Real l = (-B - std::sqrt(disc)) / (2 * A);
                if (std::fabs(comp(p, i) + l * comp(d, i)) <= comp(h, i)) best = std::min(best, l);
            }
    }
    for (int c = 0; c < 8; ++c) {
        const P3 corner{(c & 1 ? 1 : -1) * h.x, (c & 2 ? 1 : -1) * h.y, (c & 4 ? 1 : -1) * h.z};
        const P3 o = p - corner;
        const Real A = dot(d, d), B = 2 * dot(o, d), C = dot(o, o) - R * R;
        if (A == 0) continue;
        const Real disc = B * B - 4 * A * C;
        if (disc < 0) continue;
        best = std::min(best, (-B - std::sqrt(disc)) / (2 * A));
    }
    if (best < inf) {
        const P3 x = p + best * d;
        box_point = {std::clamp(x.x, -h.x, h.x), std::clamp(x.y, -h.y, h.y), std::clamp(x.z, -h.z, h.z)};
    }
    return best;
}

// Sphere and box (either order): closed form.
inline Truth sphere_box_toi(const Body& a, const Body& b, P3 ta, P3 tb) {
    const bool a_sphere = a.kind == Kind::Sphere;
    const Body& s = a_sphere ? a : b;
    const Body& x = a_sphere ? b : a;
    const P3 ts = a_sphere ? ta : tb, tx = a_sphere ? tb : ta;
    const P3 p = x.to_local(s.t), d = x.dir_to_local(ts - tx);
    Truth t;
    const P3 h = x.half_extents;
    const Real size = size_of(a, b);
    // Inside at the start?
    const P3 e{std::max(std::fabs(p.x) - h.x, Real(0)), std::max(std::fabs(p.y) - h.y, Real(0)),
               std::max(std::fabs(p.z) - h.z, Real(0))};
    if (norm(e) <= s.radius) {
        t.hit = true;
        t.toi = 0;
        t.start_overlap = true;
        t.grazing = norm(e) > s.radius * (1 - Real(1e-9));
        return t;
    }
    P3 bp;
    const Real l = ray_rounded_box(p, d, h, s.radius, bp);
    if (!(l <= 1) || l < 0) {
        t.grazing = std::isfinite(static_cast<double>(l)) && (l - 1) * norm(d) < size * Real(1e-9);
        // A near-tangent miss is also grazing; measured by the distance of the whole segment.
        return t;
    }
    t.hit = true;
    t.toi = l;
    // Normal from the box toward the sphere's centre, then oriented from A toward B.
    const P3 c = p + l * d;
    P3 n_local = c - bp;
    n_local = (Real(1) / norm(n_local)) * n_local;
    P3 n{x.R[0] * n_local.x + x.R[1] * n_local.y + x.R[2] * n_local.z,
         x.R[3] * n_local.x + x.R[4] * n_local.y + x.R[5] * n_local.z,
         x.R[6] * n_local.x + x.R[7] * n_local.y + x.R[8] * n_local.z};
    t.normal = a_sphere ? Real(-1) * n : n;
    // Grazing: the entry is tangent when the approach is nearly perpendicular to the normal.
    t.grazing = std::fabs(dot(n_local, d)) < norm(d) * Real(1e-6);
    return t;
}

// ---- Any pair: the dual by the ellipsoid method ------------------------------------------------

// min over w in span(e1, e2) of h_M(n0 + w), with its argument; the ellipsoid method in two
// variables (starting disk of radius `reach`, so normals up to atan(reach) from n0).
inline Real dual_min(const Body& a, const Body& b, P3 n0, P3 e1, P3 e2, Real reach, int iterations, P3& out_n) {
    Real c0 = 0, c1 = 0;
    Real P00 = reach * reach, P01 = 0, P11 = reach * reach;
    Real best = std::numeric_limits<Real>::infinity();
    out_n = n0;
    for (int k = 0; k < iterations; ++k) {
        const P3 n = n0 + c0 * e1 + c1 * e2;
        const P3 s = support_point_m(a, b, n);
        const Real f = dot(n, s);
        if (f < best) {
            best = f;
            out_n = n;
        }
        const Real g0 = dot(s, e1), g1 = dot(s, e2);
        const Real pg0 = P00 * g0 + P01 * g1, pg1 = P01 * g0 + P11 * g1;
        const Real gpg = g0 * pg0 + g1 * pg1;
        if (!(gpg > 0)) break;  // zero subgradient: optimal
        const Real sq = std::sqrt(gpg);
        const Real u0 = pg0 / sq, u1 = pg1 / sq;  // P g~
        c0 -= u0 / 3;
        c1 -= u1 / 3;
        P00 = Real(4) / 3 * (P00 - Real(2) / 3 * u0 * u0);
        P01 = Real(4) / 3 * (P01 - Real(2) / 3 * u0 * u1);
        P11 = Real(4) / 3 * (P11 - Real(2) / 3 * u1 * u1);
        if (P00 + P11 < reach * reach * Real(1e-44)) break;
    }
    return best;
}

inline Truth dual_toi(const Body& a, const Body& b, P3 r) {
    const Real rlen = norm(r);
    Truth t;
    if (!(rlen > 0)) return t;  // callers handle r = 0
    const P3 u = (Real(1) / rlen) * r;
    const P3 helper = std::fabs(u.x) < Real(0.6) ? P3{1, 0, 0} : P3{0, 1, 0};
    P3 e1 = cross(u, helper);
    e1 = (Real(1) / norm(e1)) * e1;
    const P3 e2 = cross(u, e1);
    const Real reach = 1e6;
    P3 n_in, n_out;
    const Real h_in = dual_min(a, b, Real(-1) * u, e1, e2, reach, 1200, n_in);
    const Real h_out = dual_min(a, b, u, e1, e2, reach, 1200, n_out);
    const Real enter = -h_in / rlen, exit = h_out / rlen;
    return classify(enter, exit, (Real(1) / norm(n_in)) * n_in, rlen, size_of(a, b));
}

// The truth for any pair, by the most exact method that applies.
inline Truth toi(const Body& a, const Body& b, P3 ta, P3 tb) {
    const P3 r = tb - ta;
    if (a.kind == Kind::Sphere && b.kind == Kind::Sphere) return sphere_sphere_toi(a, b, r);
    if ((a.kind == Kind::Sphere && b.kind == Kind::Box) || (a.kind == Kind::Box && b.kind == Kind::Sphere))
        return sphere_box_toi(a, b, ta, tb);
    if (is_polytope(a.kind) && is_polytope(b.kind)) return polytope_toi(a, b, r);
    const bool a_ok = is_polytope(a.kind) || is_round(a.kind), b_ok = is_polytope(b.kind) || is_round(b.kind);
    if (a_ok && b_ok && (has_core(a.kind) || has_core(b.kind))) return round_toi(a, b, ta, tb);
    return dual_toi(a, b, r);
}

}  // namespace cast_oracle
