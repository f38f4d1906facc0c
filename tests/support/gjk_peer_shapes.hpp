// SPDX-License-Identifier: MIT
// Shape descriptions shared by the peer cross-checks and the GJK benchmark: one random pair
// generator for every library, test-side support mappings and membership tests written
// independently of the library (used to certify answers), and Kairos shapes built from them.
#pragma once

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "gjk_test_support.hpp"
#include "math/math.hpp"
#include "oracle/polytope_oracle.hpp"
#include "shapes/shape.hpp"

namespace peer {

using kairos::Vec3;

enum class Kind { Box, Hull, Sphere, Capsule, Cylinder, Cone };
inline const char* kind_name(Kind k) {
    static const char* names[] = {"box", "hull", "sphere", "capsule", "cylinder", "cone"};
    return names[static_cast<int>(k)];
}

// A posed shape. Box: half extents (a, b, c). Sphere: radius a. Capsule, cylinder, cone: radius a,
// half height b (Kairos frames: axis z; cone apex at +b). Hull: verts (local frame).
struct Spec {
    Kind kind = Kind::Box;
    double a = 0, b = 0, c = 0;
    gjk_test::Verts verts;
    oracle::Polytope local_poly;  // hulls and boxes: faces for membership tests and FCL
    kairos::Transform pose;
};

// ---- Test-side support mappings and signed excess (independent of src/) ------------------------

inline double sgn(double v) { return v < 0 ? -1.0 : 1.0; }

inline Vec3 local_support(const Spec& s, Vec3 d) {
    const double dl = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const double rl = std::sqrt(d.x * d.x + d.y * d.y);
    switch (s.kind) {
        case Kind::Box:
            return {sgn(d.x) * s.a, sgn(d.y) * s.b, sgn(d.z) * s.c};
        case Kind::Sphere:
            return dl > 0 ? Vec3{s.a * d.x / dl, s.a * d.y / dl, s.a * d.z / dl} : Vec3{0, 0, s.a};
        case Kind::Capsule: {
            const Vec3 cap = dl > 0 ? Vec3{s.a * d.x / dl, s.a * d.y / dl, s.a * d.z / dl} : Vec3{0, 0, s.a};
            return {cap.x, cap.y, cap.z + sgn(d.z) * s.b};
        }
        case Kind::Cylinder:
            return rl > 0 ? Vec3{s.a * d.x / rl, s.a * d.y / rl, sgn(d.z) * s.b} : Vec3{0, 0, sgn(d.z) * s.b};
        case Kind::Cone: {
            const double apex = d.z * s.b, rim = s.a * rl - d.z * s.b;
            if (apex >= rim) return {0, 0, s.b};
            return rl > 0 ? Vec3{s.a * d.x / rl, s.a * d.y / rl, -s.b} : Vec3{0, 0, -s.b};
        }
        case Kind::Hull: {
            size_t best = 0;
            double bd = -INFINITY;
            for (size_t i = 0; i < s.verts.size(); ++i) {
                const double v = d.x * s.verts[i][0] + d.y * s.verts[i][1] + d.z * s.verts[i][2];
                if (v > bd) {
                    bd = v;
                    best = i;
                }
            }
            return {s.verts[best][0], s.verts[best][1], s.verts[best][2]};
        }
    }
    return {};
}

inline Vec3 rotate(const kairos::Mat3& r, Vec3 v) {
    return {r.r[0].x * v.x + r.r[0].y * v.y + r.r[0].z * v.z, r.r[1].x * v.x + r.r[1].y * v.y + r.r[1].z * v.z,
            r.r[2].x * v.x + r.r[2].y * v.y + r.r[2].z * v.z};
}
inline Vec3 rotate_t(const kairos::Mat3& r, Vec3 v) {
    return {r.r[0].x * v.x + r.r[1].x * v.y + r.r[2].x * v.z, r.r[0].y * v.x + r.r[1].y * v.y + r.r[2].y * v.z,
            r.r[0].z * v.x + r.r[1].z * v.y + r.r[2].z * v.z};
}

inline Vec3 world_support(const Spec& s, Vec3 d) {
    const Vec3 p = local_support(s, rotate_t(s.pose.rotation, d));
    const Vec3 w = rotate(s.pose.rotation, p);
    return {w.x + s.pose.translation.x, w.y + s.pose.translation.y, w.z + s.pose.translation.z};
}

// <= 0 inside; > 0 outside (a lower bound of the distance to the shape, exact for the primitives).
inline double excess(const Spec& s, Vec3 world) {
    const Vec3 q{world.x - s.pose.translation.x, world.y - s.pose.translation.y, world.z - s.pose.translation.z};
    const Vec3 p = rotate_t(s.pose.rotation, q);
    switch (s.kind) {
        case Kind::Box:
            return std::fmax(std::fabs(p.x) - s.a, std::fmax(std::fabs(p.y) - s.b, std::fabs(p.z) - s.c));
        case Kind::Sphere:
            return std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) - s.a;
        case Kind::Capsule: {
            const double z = p.z - std::fmax(-s.b, std::fmin(s.b, p.z));
            return std::sqrt(p.x * p.x + p.y * p.y + z * z) - s.a;
        }
        case Kind::Cylinder:
            return std::fmax(std::sqrt(p.x * p.x + p.y * p.y) - s.a, std::fabs(p.z) - s.b);
        case Kind::Cone: {
            const double rho = std::sqrt(p.x * p.x + p.y * p.y);
            const double side = (rho * 2 * s.b + (p.z - s.b) * s.a) / std::sqrt(4 * s.b * s.b + s.a * s.a);
            return std::fmax(side, -s.b - p.z);
        }
        case Kind::Hull:
            return static_cast<double>(oracle::plane_excess(s.local_poly, {p.x, p.y, p.z}));
    }
    return 0;
}

// Size of the shape (bounding radius about its local origin).
inline double extent(const Spec& s) {
    switch (s.kind) {
        case Kind::Box:
            return std::sqrt(s.a * s.a + s.b * s.b + s.c * s.c);
        case Kind::Sphere:
            return s.a;
        case Kind::Capsule:
            return s.a + s.b;
        case Kind::Cylinder:
        case Kind::Cone:
            return std::sqrt(s.a * s.a + s.b * s.b);
        case Kind::Hull:
            return gjk_test::radius_of(s.verts);
    }
    return 0;
}

inline gjk_test::ShapePtr make_kairos(const Spec& s) {
    switch (s.kind) {
        case Kind::Box:
            return gjk_test::box({s.a, s.b, s.c});
        case Kind::Sphere:
            return gjk_test::ShapePtr(new kairos::SphereShape(s.a));
        case Kind::Capsule:
            return gjk_test::ShapePtr(new kairos::CapsuleShape(s.a, s.b));
        case Kind::Cylinder:
            return gjk_test::ShapePtr(new kairos::CylinderShape(s.a, s.b));
        case Kind::Cone:
            return gjk_test::ShapePtr(new kairos::ConeShape(s.a, s.b));
        case Kind::Hull:
            return gjk_test::hull(s.verts);
    }
    return nullptr;
}

inline Spec random_spec(std::mt19937_64& rng, Kind k, int hull_points = 0) {
    std::uniform_real_distribution<double> ext(0.3, 1.5);
    Spec s;
    s.kind = k;
    switch (k) {
        case Kind::Box:
            s.a = ext(rng), s.b = ext(rng), s.c = ext(rng);
            s.verts = gjk_test::box_vertices({s.a, s.b, s.c});
            s.local_poly = oracle::make_polytope(
                oracle::transform(s.verts, std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}.data(),
                                  std::array<double, 3>{0, 0, 0}.data()));
            break;
        case Kind::Hull: {
            std::uniform_int_distribution<int> n(8, 64);
            s.verts =
                gjk_test::random_points(rng, hull_points > 0 ? hull_points : n(rng), {ext(rng), ext(rng), ext(rng)});
            s.local_poly = oracle::make_polytope(
                oracle::transform(s.verts, std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}.data(),
                                  std::array<double, 3>{0, 0, 0}.data()));
            break;
        }
        default:
            s.a = 0.5 * ext(rng), s.b = ext(rng);
            break;
    }
    return s;
}

// A pair at random orientations, B at a random direction from A at a distance between the
// shapes' extents scaled by [0.2, 1.6]: roughly a third of the pairs overlap.
inline void place_pair(std::mt19937_64& rng, Spec& a, Spec& b) {
    std::uniform_real_distribution<double> gap(0.2, 1.6);
    a.pose = kairos::make_transform(0.2 * gjk_test::random_unit(rng), gjk_test::random_quat(rng));
    const double reach = (extent(a) + extent(b)) * gap(rng);
    b.pose =
        kairos::make_transform(a.pose.translation + reach * gjk_test::random_unit(rng), gjk_test::random_quat(rng));
}

struct Pair {
    Spec a, b;
};

// count pairs cycling through every combination of kinds, placed by place_pair.
inline std::vector<Pair> random_pairs(uint64_t seed, int count) {
    std::mt19937_64 rng(seed);
    std::vector<Pair> pairs;
    for (int i = 0; i < count; ++i) {
        const Kind ka = static_cast<Kind>(i % 6), kb = static_cast<Kind>((i / 6) % 6);
        Pair p{random_spec(rng, ka), random_spec(rng, kb)};
        place_pair(rng, p.a, p.b);
        pairs.push_back(std::move(p));
    }
    return pairs;
}

inline double pair_scale(const Pair& p) {
    return extent(p.a) + extent(p.b) + kairos::length(p.b.pose.translation - p.a.pose.translation);
}

inline bool is_polytope(const Spec& s) { return s.kind == Kind::Box || s.kind == Kind::Hull; }

// Independent certificates of a GJK answer, with the test-side supports:
// separated: both points on their shapes, |pb - pa| = d (an upper bound), and the plane normal to
// the reported axis separates (its gap, max_A n.x to min_B n.x, is a lower bound of the distance);
// intersecting: the reported point lies in both shapes.
struct Certificate {
    bool ok = false;
    double lower = 0, upper = 0;  // certified bounds of the distance (separated)
};
// point_tol: how far outside its shape a point may lie; rel: relative slack of the distance.
// The plane is the reported axis n (unit, from A toward B).
inline Certificate certify_separated(const Spec& a, const Spec& b, Vec3 pa, Vec3 pb, Vec3 n, double d, double point_tol,
                                     double rel) {
    Certificate c;
    const double len = kairos::length(pb - pa);
    const double max_a = kairos::dot(n, world_support(a, n));
    const double min_b = kairos::dot(n, world_support(b, -n));
    c.lower = min_b - max_a;
    c.upper = len;
    c.ok = excess(a, pa) <= point_tol && excess(b, pb) <= point_tol && std::fabs(len - d) <= point_tol + rel * d &&
           c.lower >= d - point_tol - rel * d;
    return c;
}
inline bool certify_intersecting(const Spec& a, const Spec& b, Vec3 p, double tol) {
    return excess(a, p) <= tol && excess(b, p) <= tol;
}

}  // namespace peer
