// SPDX-License-Identifier: MIT
// Convex hulls as FCL's Convex takes them (vertices and outward triangles), for the campaign's
// random polytopes: incremental construction, each new point replacing the faces it sees by a fan
// over their horizon. Points are in general position here; near-degenerate sets are refused.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "campaign.hpp"

namespace kairos::fcl_check::campaign {

namespace {

struct V {
    double x, y, z;
};
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double len(V a) { return std::sqrt(dot(a, a)); }

struct Face {
    std::array<int, 3> v;
    V n;       // unit outward normal
    double d;  // n . x = d on the face
    bool alive = true;
};

}  // namespace

bool build_hull(const std::vector<Point>& points, std::vector<Point>& vertices,
                std::vector<std::array<int, 3>>& triangles) {
    const int n = static_cast<int>(points.size());
    if (n < 4) return false;
    std::vector<V> p(points.size());
    double scale = 0;
    for (int i = 0; i < n; ++i) {
        p[size_t(i)] = {points[size_t(i)][0], points[size_t(i)][1], points[size_t(i)][2]};
        scale = std::max({scale, std::fabs(p[size_t(i)].x), std::fabs(p[size_t(i)].y), std::fabs(p[size_t(i)].z)});
    }
    if (!(scale > 0) || !std::isfinite(scale)) return false;
    const double eps = 1e-10 * scale;
    const auto at = [&](int i) { return p[size_t(i)]; };

    // A first tetrahedron of well-spread points.
    int i0 = 0;
    for (int i = 1; i < n; ++i)
        if (at(i).x < at(i0).x) i0 = i;
    int i1 = -1, i2 = -1, i3 = -1;
    double best = 0;
    for (int i = 0; i < n; ++i)
        if (const double l = len(at(i) - at(i0)); l > best) best = l, i1 = i;
    if (i1 < 0 || best <= eps) return false;
    best = 0;
    for (int i = 0; i < n; ++i)
        if (const double l = len(cross(at(i1) - at(i0), at(i) - at(i0))) / len(at(i1) - at(i0)); l > best)
            best = l, i2 = i;
    if (i2 < 0 || best <= eps) return false;
    const V n012 = cross(at(i1) - at(i0), at(i2) - at(i0));
    best = 0;
    for (int i = 0; i < n; ++i)
        if (const double l = std::fabs(dot(n012, at(i) - at(i0))) / len(n012); l > best) best = l, i3 = i;
    if (i3 < 0 || best <= eps) return false;
    const V inside{(at(i0).x + at(i1).x + at(i2).x + at(i3).x) / 4, (at(i0).y + at(i1).y + at(i2).y + at(i3).y) / 4,
                   (at(i0).z + at(i1).z + at(i2).z + at(i3).z) / 4};

    std::vector<Face> faces;
    const auto add = [&](int a, int b, int c) {
        Face f;
        f.v = {a, b, c};
        V nn = cross(at(b) - at(a), at(c) - at(a));
        const double l = len(nn);
        if (!(l > 0)) return false;
        nn = {nn.x / l, nn.y / l, nn.z / l};
        f.n = nn;
        f.d = dot(nn, at(a));
        faces.push_back(f);
        return true;
    };
    const auto add_outward = [&](int a, int b, int c) {
        const V nn = cross(at(b) - at(a), at(c) - at(a));
        return dot(nn, inside - at(a)) < 0 ? add(a, b, c) : add(a, c, b);
    };
    if (!add_outward(i0, i1, i2) || !add_outward(i0, i1, i3) || !add_outward(i0, i2, i3) || !add_outward(i1, i2, i3))
        return false;

    for (int i = 0; i < n; ++i) {
        if (i == i0 || i == i1 || i == i2 || i == i3) continue;
        std::set<std::pair<int, int>> seen;  // directed edges of the visible faces
        bool any = false;
        for (Face& f : faces) {
            if (!f.alive || dot(f.n, at(i)) - f.d <= eps) continue;
            any = true;
            f.alive = false;
            for (int k = 0; k < 3; ++k) seen.insert({f.v[size_t(k)], f.v[size_t((k + 1) % 3)]});
        }
        if (!any) continue;
        // Horizon: a visible face's edge whose twin belongs to a face that stays.
        for (const auto& [a, b] : seen)
            if (!seen.count({b, a}) && !add(a, b, i)) return false;
    }

    // Keep the vertices the faces use, renumbered in input order.
    std::map<int, int> index;
    for (const Face& f : faces)
        if (f.alive)
            for (int v : f.v) index[v] = 0;
    vertices.clear();
    for (auto& [old, fresh] : index) {
        fresh = static_cast<int>(vertices.size());
        vertices.push_back(points[size_t(old)]);
    }
    triangles.clear();
    std::map<std::pair<int, int>, int> edges;
    for (const Face& f : faces) {
        if (!f.alive) continue;
        triangles.push_back({index[f.v[0]], index[f.v[1]], index[f.v[2]]});
        for (int k = 0; k < 3; ++k) ++edges[{f.v[size_t(k)], f.v[size_t((k + 1) % 3)]}];
        // Every input point must lie inside (a closed, convex result).
        for (int j = 0; j < n; ++j)
            if (dot(f.n, at(j)) - f.d > 1e3 * eps) return false;
    }
    // Closed and consistently oriented: each directed edge once, with its twin.
    for (const auto& [e, count] : edges)
        if (count != 1 || !edges.count({e.second, e.first})) return false;
    // Euler's formula for a sphere: V - E + F = 2.
    const long nv = long(vertices.size()), ne = long(edges.size()) / 2, nf = long(triangles.size());
    return nv - ne + nf == 2 && nv >= 4;
}

}  // namespace kairos::fcl_check::campaign
