// SPDX-License-Identifier: MIT
// Shared by the cast tests, the long run and the cast benchmark: random shapes of every kind with
// their oracle bodies, random casts, and the comparison of a cast result with the oracle's truth.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "casts/cast.hpp"
#include "oracle/cast_oracle.hpp"
#include "shapes/shape.hpp"

namespace cast_test {

using cast_oracle::Body;
using cast_oracle::Kind;
using cast_oracle::P3;
using cast_oracle::Real;

struct ShapeRelease {
    void operator()(const kairos::Shape* s) const {
        if (s) s->release();
    }
};
using ShapePtr = std::unique_ptr<const kairos::Shape, ShapeRelease>;

// The loop's stops at the rounding limit (a stall, a repeated support, a failed sub-simplex),
// which the tests count to show that a case reaches the rules that act after them.
inline bool rounding_stop(kairos::Termination t) {
    return t == kairos::Termination::NoProgress || t == kairos::Termination::RepeatedSupport ||
           t == kairos::Termination::JohnsonFailed;
}

inline const char* kind_name(Kind k) {
    switch (k) {
        case Kind::Point:
            return "point";
        case Kind::Segment:
            return "segment";
        case Kind::Sphere:
            return "sphere";
        case Kind::Box:
            return "box";
        case Kind::Capsule:
            return "capsule";
        case Kind::Cylinder:
            return "cylinder";
        case Kind::Cone:
            return "cone";
        case Kind::Hull:
            return "hull";
    }
    return "?";
}
inline constexpr Kind kAllKinds[] = {Kind::Point,   Kind::Segment,  Kind::Sphere, Kind::Box,
                                     Kind::Capsule, Kind::Cylinder, Kind::Cone,   Kind::Hull};

inline kairos::Vec3 random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    for (;;) {
        const kairos::Vec3 v{n(rng), n(rng), n(rng)};
        const double l = kairos::length(v);
        if (l > 1e-3) return v / l;
    }
}
inline kairos::Quat random_quat(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    return kairos::normalized(kairos::Quat{n(rng), n(rng), n(rng), n(rng)});
}

// A shape and its oracle body (local frame; place() sets the pose).
struct Solid {
    ShapePtr shape;
    Body body;
    double radius = 0;  // bounding radius about the local origin
};

// Builds a hull shape from points (the library's builder; raw points if it refuses).
inline ShapePtr hull_shape(const std::vector<kairos::Vec3>& p) {
    kairos::ConvexHullShape* out = nullptr;
    if (kairos::make_convex_hull(p.data(), p.size(), &out) == kairos::HullStatus::Ok && out) return ShapePtr(out);
    auto* h = new kairos::ConvexHullShape();
    h->vertices = p;
    return ShapePtr(h);
}

// n points near an ellipsoid's surface (most of them hull vertices).
inline std::vector<kairos::Vec3> ellipsoid_points(std::mt19937_64& rng, int n, kairos::Vec3 radii) {
    std::uniform_real_distribution<double> u(0.8, 1.0);
    std::vector<kairos::Vec3> v;
    for (int i = 0; i < n; ++i) {
        const kairos::Vec3 d = random_unit(rng);
        const double s = u(rng);
        v.push_back({s * d.x * radii.x, s * d.y * radii.y, s * d.z * radii.z});
    }
    return v;
}

inline Solid make_solid(Kind k, double r, double h, kairos::Vec3 he, const std::vector<kairos::Vec3>& pts = {}) {
    Solid s;
    s.body = cast_oracle::make_body(k);
    switch (k) {
        case Kind::Point:
            s.shape.reset(new kairos::PointShape());
            break;
        case Kind::Segment:
            s.shape.reset(new kairos::SegmentShape(h));
            s.body.half = h;
            s.radius = h;
            break;
        case Kind::Sphere:
            s.shape.reset(new kairos::SphereShape(r));
            s.body.radius = r;
            s.radius = r;
            break;
        case Kind::Box:
            s.shape.reset(new kairos::BoxShape(he));
            s.body.half_extents = {he.x, he.y, he.z};
            s.radius = kairos::length(he);
            break;
        case Kind::Capsule:
            s.shape.reset(new kairos::CapsuleShape(r, h));
            s.body.radius = r;
            s.body.half = h;
            s.radius = r + h;
            break;
        case Kind::Cylinder:
            s.shape.reset(new kairos::CylinderShape(r, h));
            s.body.radius = r;
            s.body.half = h;
            s.radius = std::hypot(r, h);
            break;
        case Kind::Cone:
            s.shape.reset(new kairos::ConeShape(r, h));
            s.body.radius = r;
            s.body.half = h;
            s.radius = std::hypot(r, h);
            break;
        case Kind::Hull:
            s.shape = hull_shape(pts);
            for (const auto& p : pts) {
                s.body.verts.push_back({p.x, p.y, p.z});
                s.radius = std::max(s.radius, kairos::length(p));
            }
            break;
    }
    cast_oracle::finish_body(s.body);
    return s;
}

// A random shape of kind k, sizes in [0.2, 1.5] * scale. hull_points: vertex count of hulls.
inline Solid random_solid(std::mt19937_64& rng, Kind k, double scale = 1, int hull_points = 12) {
    std::uniform_real_distribution<double> ext(0.2, 1.5);
    const double r = ext(rng) * scale, h = ext(rng) * scale;
    const kairos::Vec3 he{ext(rng) * scale, ext(rng) * scale, ext(rng) * scale};
    std::vector<kairos::Vec3> pts;
    if (k == Kind::Hull)
        pts = ellipsoid_points(rng, hull_points, {ext(rng) * scale, ext(rng) * scale, ext(rng) * scale});
    return make_solid(k, r, h, he, pts);
}

inline void place(Body& b, const kairos::Transform& p) {
    for (int i = 0; i < 3; ++i) {
        b.R[3 * i + 0] = p.rotation.r[i].x;
        b.R[3 * i + 1] = p.rotation.r[i].y;
        b.R[3 * i + 2] = p.rotation.r[i].z;
    }
    b.t = {p.translation.x, p.translation.y, p.translation.z};
}

inline P3 p3(kairos::Vec3 v) { return {v.x, v.y, v.z}; }

// A random cast: A near `base`, B 1..3 radii away, B's relative motion aimed at A with a jitter
// that makes about half of the casts hit.
struct Cast {
    kairos::Transform pa, pb;
    kairos::Vec3 ta, tb;
};

inline Cast random_cast(std::mt19937_64& rng, const Solid& a, const Solid& b, kairos::Vec3 base = {},
                        double motion_scale = 1) {
    std::uniform_real_distribution<double> gap(1.0, 3.0), reach(0.6, 2.2), jitter(0, 2.5), small(-0.3, 0.3);
    Cast c;
    const double sum = a.radius + b.radius;
    c.pa = kairos::make_transform(base + small(rng) * sum * random_unit(rng), random_quat(rng));
    c.pb = kairos::make_transform(c.pa.translation + gap(rng) * sum * random_unit(rng), random_quat(rng));
    const kairos::Vec3 aim = (c.pa.translation - c.pb.translation) * reach(rng) + jitter(rng) * sum * random_unit(rng);
    c.ta = small(rng) * sum * motion_scale * random_unit(rng);
    c.tb = c.ta + aim * motion_scale;
    return c;
}

// ---- Comparing a result with the truth -----------------------------------------------------------

struct Verdict {
    bool miss = false;        // the oracle hits (not grazing), the library does not
    bool false_hit = false;   // the library hits, its contact point is far from both shapes at toi,
                              // and the oracle says miss (or hits much later)
    bool late = false;        // toi later than the truth by more than the allowance
    double toi_error = 0;     // |toi - truth|, both hitting
    double normal_gap = 0;    // (h_M(n) - n.(toi_true r)) / size: 0 when n is a normal of M at the true hit
    double normal_angle = 0;  // angle (rad) to the oracle's normal, both hitting past the start
    double point_error = 0;   // (dist(p, A(toi)) + dist(p, B(toi))) / size, library hits
    bool compared = false;    // both hit, not grazing, not at the start
};

// Distance from p to A and to B placed at lambda (A moved by lambda ta, B by lambda tb).
inline Real point_gap(const Body& a, const Body& b, P3 ta, P3 tb, Real lambda, P3 p) {
    return cast_oracle::point_distance(a, p - lambda * ta) + cast_oracle::point_distance(b, p - lambda * tb);
}

// allowance: how much later than the truth a toi may be (fraction of the step), and how far from
// the shapes a hit's contact point may be (relative to the size) before it counts as false.
inline Verdict judge(const Body& a, const Body& b, P3 ta, P3 tb, const cast_oracle::Truth& t,
                     const kairos::CastResult& r, double toi_allowance, double point_allowance) {
    Verdict v;
    const Real size = cast_oracle::size_of(a, b);
    const P3 rr = tb - ta;
    if (r.hit) {
        v.point_error = static_cast<double>(point_gap(a, b, ta, tb, r.toi, p3(r.point)) / size);
        if (!t.hit && v.point_error > point_allowance) v.false_hit = true;
    }
    if (t.hit && !r.hit && !t.grazing) v.miss = true;
    if (t.hit && r.hit) {
        v.toi_error = std::fabs(static_cast<double>(Real(r.toi) - t.toi));
        if (Real(r.toi) > t.toi + toi_allowance && !t.grazing) v.late = true;
        if (!t.start_overlap) {
            const P3 n = p3(r.normal);
            v.normal_gap =
                static_cast<double>((cast_oracle::support_m(a, b, n) - t.toi * cast_oracle::dot(n, rr)) / size);
            const Real nn = cast_oracle::norm(t.normal);
            if (nn > 0) {
                const Real c = std::clamp(cast_oracle::dot(n, t.normal) / nn, Real(-1), Real(1));
                v.normal_angle = static_cast<double>(std::acos(c));
            }
            v.compared = !t.grazing;
        }
        if (v.point_error > point_allowance && !t.grazing) v.false_hit = true;
    }
    return v;
}

inline double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}
inline double maximum(const std::vector<double>& v) { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }

}  // namespace cast_test
