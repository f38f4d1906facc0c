// SPDX-License-Identifier: MIT
// Test oracle: distance, intersection and penetration depth of two convex polytopes given by their
// vertices, by brute force in long double. Independent of the library (no GJK, no shape supports).
//
// Faces: every vertex triple whose plane has all vertices on one side (coplanar faces come out
// triangulated, diagonals included, which is harmless). Separated polytopes: the distance is the
// minimum over vertex/triangle and edge/edge pairs, which includes the closest feature pair.
// Intersection: separating axis theorem over face normals and edge cross products, whose minimum
// overlap is also the penetration depth.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace oracle {

using Real = long double;

struct P3 {
    Real x = 0, y = 0, z = 0;
};
inline P3 operator+(P3 a, P3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline P3 operator-(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline P3 operator*(Real s, P3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline Real dot(P3 a, P3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline P3 cross(P3 a, P3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Real norm(P3 a) { return std::sqrt(dot(a, a)); }

struct Polytope {
    std::vector<P3> v;
    std::vector<std::array<int, 3>> faces;
    std::vector<P3> normals;    // unit, outward
    std::vector<Real> offsets;  // normal . x <= offset inside
    std::vector<std::array<int, 2>> edges;
    Real scale = 0;  // largest |coordinate| (for tolerances)
};

// Maps local vertices by x -> R x + t in long double (R row-major, as given to the library).
inline std::vector<P3> transform(const std::vector<std::array<double, 3>>& local, const double r[9],
                                 const double t[3]) {
    std::vector<P3> out;
    out.reserve(local.size());
    for (const auto& p : local) {
        const Real x = p[0], y = p[1], z = p[2];
        out.push_back({Real(r[0]) * x + Real(r[1]) * y + Real(r[2]) * z + Real(t[0]),
                       Real(r[3]) * x + Real(r[4]) * y + Real(r[5]) * z + Real(t[1]),
                       Real(r[6]) * x + Real(r[7]) * y + Real(r[8]) * z + Real(t[2])});
    }
    return out;
}

inline Polytope make_polytope(std::vector<P3> pts) {
    Polytope p;
    p.v = std::move(pts);
    const size_t n = p.v.size();
    P3 lo = p.v[0], hi = p.v[0];
    for (const P3& q : p.v) {
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
        p.scale = std::max({p.scale, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    }
    // The vertices' mean (inside the hull; the bounding box's centre need not be: a sliver
    // tetrahedron's face then came out facing inward and was dropped, leaving an open polytope).
    P3 centre{0, 0, 0};
    for (const P3& q : p.v) centre = centre + q;
    centre = (Real(1) / Real(n)) * centre;
    const Real extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const Real tol = extent * Real(1e-12);
    std::vector<std::array<int, 2>> edges;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            for (size_t k = j + 1; k < n; ++k) {
                P3 nrm = cross(p.v[j] - p.v[i], p.v[k] - p.v[i]);
                const Real len = norm(nrm);
                if (!(len > extent * extent * Real(1e-14))) continue;  // collinear triple
                nrm = (Real(1) / len) * nrm;
                Real off = dot(nrm, p.v[i]);
                if (dot(nrm, centre) > off) {
                    nrm = Real(-1) * nrm;
                    off = -off;
                }
                bool face = true;
                for (size_t m = 0; m < n && face; ++m)
                    if (dot(nrm, p.v[m]) - off > tol) face = false;
                if (!face) continue;
                p.faces.push_back({int(i), int(j), int(k)});
                p.normals.push_back(nrm);
                p.offsets.push_back(off);
                edges.push_back({int(i), int(j)});
                edges.push_back({int(i), int(k)});
                edges.push_back({int(j), int(k)});
            }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    p.edges = std::move(edges);
    return p;
}

// Signed-ish distance of x to the polytope: max over face planes of normal.x - offset. Positive
// outside (a lower bound of the distance), <= 0 inside.
inline Real plane_excess(const Polytope& p, P3 x) {
    Real m = -std::numeric_limits<Real>::infinity();
    for (size_t f = 0; f < p.normals.size(); ++f) m = std::max(m, dot(p.normals[f], x) - p.offsets[f]);
    return m;
}

// Squared distance from x to the segment [a, b].
inline Real point_segment_sq(P3 x, P3 a, P3 b) {
    const P3 ab = b - a;
    const Real len2 = dot(ab, ab);
    Real t = len2 > 0 ? dot(x - a, ab) / len2 : 0;
    t = std::clamp(t, Real(0), Real(1));
    const P3 d = x - (a + t * ab);
    return dot(d, d);
}

// Squared distance from x to the triangle abc: the plane projection when it falls inside,
// otherwise the nearest edge.
inline Real point_triangle_sq(P3 x, P3 a, P3 b, P3 c) {
    const P3 n = cross(b - a, c - a);
    const Real n2 = dot(n, n);
    if (n2 > 0) {
        const Real h = dot(x - a, n) / n2;
        const P3 q = x - h * n;  // projection onto the plane
        const Real ua = dot(cross(b - q, c - q), n), ub = dot(cross(c - q, a - q), n), uc = dot(cross(a - q, b - q), n);
        if (ua >= 0 && ub >= 0 && uc >= 0) return h * h * n2;
    }
    return std::min({point_segment_sq(x, a, b), point_segment_sq(x, b, c), point_segment_sq(x, c, a)});
}

// Squared distance between segments [p1, q1] and [p2, q2]: the interior critical point when it
// exists, else the minimum over the four endpoint-to-segment distances.
inline Real segment_segment_sq(P3 p1, P3 q1, P3 p2, P3 q2) {
    const P3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const Real a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), c = dot(d1, r), f = dot(d2, r);
    Real best = std::min({point_segment_sq(p1, p2, q2), point_segment_sq(q1, p2, q2), point_segment_sq(p2, p1, q1),
                          point_segment_sq(q2, p1, q1)});
    const Real denom = a * e - b * b;
    if (denom > (a * e) * Real(1e-16)) {
        const Real s = (b * f - c * e) / denom, t = (a * f - b * c) / denom;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
            const P3 d = (p1 + s * d1) - (p2 + t * d2);
            best = std::min(best, dot(d, d));
        }
    }
    return best;
}

struct Result {
    Real distance = 0;  // 0 when intersecting
    Real depth = 0;     // penetration depth (minimum SAT overlap), 0 when separated
    bool intersecting = false;
};

// Projection interval of the polytope on axis n.
inline void project(const Polytope& p, P3 n, Real& lo, Real& hi) {
    lo = std::numeric_limits<Real>::infinity();
    hi = -lo;
    for (const P3& q : p.v) {
        const Real s = dot(n, q);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
    }
}

inline Result distance(const Polytope& a, const Polytope& b) {
    Result r;
    // Separating axis test; min_overlap ends as the penetration depth if nothing separates.
    Real min_overlap = std::numeric_limits<Real>::infinity();
    bool separated = false;
    auto test_axis = [&](P3 n) {
        Real alo, ahi, blo, bhi;
        project(a, n, alo, ahi);
        project(b, n, blo, bhi);
        const Real overlap = std::min(ahi - blo, bhi - alo);
        if (overlap < 0) separated = true;
        min_overlap = std::min(min_overlap, overlap);
    };
    for (const P3& n : a.normals) {
        test_axis(n);
        if (separated) break;
    }
    if (!separated)
        for (const P3& n : b.normals) {
            test_axis(n);
            if (separated) break;
        }
    if (!separated)
        for (const auto& ea : a.edges) {
            const P3 da = a.v[ea[1]] - a.v[ea[0]];
            for (const auto& eb : b.edges) {
                const P3 db = b.v[eb[1]] - b.v[eb[0]];
                P3 n = cross(da, db);
                const Real len = norm(n);
                if (!(len > norm(da) * norm(db) * Real(1e-9))) continue;
                test_axis((Real(1) / len) * n);
                if (separated) break;
            }
            if (separated) break;
        }
    if (!separated) {
        r.intersecting = true;
        r.depth = std::max(min_overlap, Real(0));
        r.distance = 0;
        return r;
    }
    Real best = std::numeric_limits<Real>::infinity();
    for (const P3& x : a.v)
        for (const auto& f : b.faces) best = std::min(best, point_triangle_sq(x, b.v[f[0]], b.v[f[1]], b.v[f[2]]));
    for (const P3& x : b.v)
        for (const auto& f : a.faces) best = std::min(best, point_triangle_sq(x, a.v[f[0]], a.v[f[1]], a.v[f[2]]));
    for (const auto& ea : a.edges)
        for (const auto& eb : b.edges)
            best = std::min(best, segment_segment_sq(a.v[ea[0]], a.v[ea[1]], b.v[eb[0]], b.v[eb[1]]));
    r.distance = std::sqrt(best);
    return r;
}

}  // namespace oracle
