// SPDX-License-Identifier: MIT
// Shared helpers of the GJK tests: shape ownership, random poses and polytopes, oracle bodies.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "math/transform.hpp"
#include "oracle/polytope_oracle.hpp"
#include "shapes/shape.hpp"

namespace gjk_test {

struct ShapeRelease {
    void operator()(const kairos::Shape* s) const {
        if (s) s->release();
    }
};
using ShapePtr = std::unique_ptr<const kairos::Shape, ShapeRelease>;

using Verts = std::vector<std::array<double, 3>>;

inline ShapePtr box(kairos::Vec3 h) { return ShapePtr(new kairos::BoxShape(h)); }

// A hull through the library's builder when it works, else a ConvexHullShape holding the raw
// points (their support mapping is the hull's either way).
inline ShapePtr hull(const Verts& pts) {
    std::vector<kairos::Vec3> p;
    for (const auto& q : pts) p.push_back({q[0], q[1], q[2]});
    kairos::ConvexHullShape* out = nullptr;
    if (kairos::make_convex_hull(p.data(), p.size(), &out) == kairos::HullStatus::Ok && out) return ShapePtr(out);
    auto* h = new kairos::ConvexHullShape();
    h->vertices = p;
    return ShapePtr(h);
}

inline Verts box_vertices(kairos::Vec3 h) {
    Verts v;
    for (int i = 0; i < 8; ++i) v.push_back({(i & 1 ? 1 : -1) * h.x, (i & 2 ? 1 : -1) * h.y, (i & 4 ? 1 : -1) * h.z});
    return v;
}

inline kairos::Quat random_quat(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    kairos::Quat q{n(rng), n(rng), n(rng), n(rng)};
    return kairos::normalized(q);
}

inline kairos::Vec3 random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    for (;;) {
        const kairos::Vec3 v{n(rng), n(rng), n(rng)};
        const double l = kairos::length(v);
        if (l > 1e-3) return v / l;
    }
}

// n points: on an ellipsoid surface with radii `radii` (so most are hull vertices), jittered inward.
inline Verts random_points(std::mt19937_64& rng, int n, kairos::Vec3 radii) {
    std::uniform_real_distribution<double> u(0.8, 1.0);
    Verts v;
    for (int i = 0; i < n; ++i) {
        const kairos::Vec3 d = random_unit(rng);
        const double s = u(rng);
        v.push_back({s * d.x * radii.x, s * d.y * radii.y, s * d.z * radii.z});
    }
    return v;
}

// The polytope of local vertices at a pose, in long double (the pose's double matrix and
// translation are what the library uses too).
inline oracle::Polytope world_polytope(const Verts& local, const kairos::Transform& pose) {
    const double r[9] = {pose.rotation.r[0].x, pose.rotation.r[0].y, pose.rotation.r[0].z,
                         pose.rotation.r[1].x, pose.rotation.r[1].y, pose.rotation.r[1].z,
                         pose.rotation.r[2].x, pose.rotation.r[2].y, pose.rotation.r[2].z};
    const double t[3] = {pose.translation.x, pose.translation.y, pose.translation.z};
    return oracle::make_polytope(oracle::transform(local, r, t));
}

inline oracle::P3 to_p3(kairos::Vec3 v) { return {v.x, v.y, v.z}; }

inline double radius_of(const Verts& v) {
    double r = 0;
    for (const auto& p : v) r = std::fmax(r, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
    return r;
}

// The depth of a segment of half length `half` (its pose's z) in a box of half extents h, from the
// poses as placed, in long double: A - B is the sum of the segment and the box, whose facets are the
// box's faces and the parallelograms of the segment with each box edge, so the depth is the least
// support value of A - B over those normals, less the offset's. Pairs apart get a number below 0 that
// is not their distance (the largest separation over those normals).
inline double box_segment_depth(kairos::Vec3 h, const kairos::Transform& xs, double half, const kairos::Transform& xr) {
    using R = long double;
    const kairos::Vec3 cr = xs.to_local_direction(xr.translation - xs.translation);
    const kairos::Vec3 er = xs.to_local_direction(xr.rotation * kairos::Vec3{0, 0, 1});
    const auto push = [&](R nx, R ny, R nz) {  // the support value of A - B along n, less |c . n|
        const R len = std::sqrt(nx * nx + ny * ny + nz * nz);
        if (!(len > 0)) return R(INFINITY);
        nx /= len, ny /= len, nz /= len;
        const R boxes = h.x * std::fabs(nx) + h.y * std::fabs(ny) + h.z * std::fabs(nz);
        const R seg = half * std::fabs(er.x * nx + er.y * ny + er.z * nz);
        return boxes + seg - std::fabs(cr.x * nx + cr.y * ny + cr.z * nz);
    };
    R depth = INFINITY;
    for (int m = 0; m < 3; ++m) {
        R n[3] = {0, 0, 0};
        n[m] = 1;
        depth = std::min(depth, push(n[0], n[1], n[2]));
        // e x the box's edge along m.
        R x[3] = {er.x, er.y, er.z}, g[3];
        g[0] = x[1] * n[2] - x[2] * n[1], g[1] = x[2] * n[0] - x[0] * n[2], g[2] = x[0] * n[1] - x[1] * n[0];
        if (half > 0) depth = std::min(depth, push(g[0], g[1], g[2]));
    }
    return double(depth);
}

}  // namespace gjk_test
