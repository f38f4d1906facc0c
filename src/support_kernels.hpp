// Support mappings of the shapes GJK and the casts specialise on, and the dispatch that picks
// one per shape: templates, so the inner loops inline the support with no virtual call.
//
// Spheres and capsules are a point or a segment plus a radius: the loops run on the core and fold
// the radius into their tests (fewer iterations on round shapes).
#pragma once

#include <cmath>
#include <cstddef>

#include "math.hpp"
#include "shape.hpp"

namespace kairos::kernels {

struct PointSupport {
    Vec3 operator()(Vec3) const { return {}; }
};
struct SegmentSupport {
    double h;
    Vec3 operator()(Vec3 d) const { return {0, 0, support_sign(d.z) * h}; }
};
struct BoxSupport {
    Vec3 h;
    Vec3 operator()(Vec3 d) const { return {support_sign(d.x) * h.x, support_sign(d.y) * h.y, support_sign(d.z) * h.z}; }
};
// Brute force over a small hull's vertices. Two interleaved running maxima and selects instead of
// branches: the winner changes unpredictably, and a mispredicted branch per vertex cost more than
// the dot product. Ties go to the lower index within each half-stream, then to the even one.
struct SmallHullSupport {
    const Vec3* v;
    size_t n;
    Vec3 operator()(Vec3 d) const {
        size_t best0 = 0, best1 = 0;
        double max0 = dot(d, v[0]), max1 = -INFINITY;
        size_t i = 1;
        for (; i + 1 < n; i += 2) {
            const double s1 = dot(d, v[i]), s0 = dot(d, v[i + 1]);
            best1 = s1 > max1 ? i : best1;
            max1 = s1 > max1 ? s1 : max1;
            best0 = s0 > max0 ? i + 1 : best0;
            max0 = s0 > max0 ? s0 : max0;
        }
        if (i < n) {
            const double s1 = dot(d, v[i]);
            best1 = s1 > max1 ? i : best1;
            max1 = s1 > max1 ? s1 : max1;
        }
        return v[max1 > max0 ? best1 : best0];
    }
};
struct GenericSupport {
    const Shape* s;
    Vec3 operator()(Vec3 d) const { return support(*s, d); }
};


// B's local frame in A's: x -> r x + t, with r = Ra^T Rb and t = Ra^T (tb - ta). The translation
// difference is taken before rotating, so shapes far from the world origin keep their relative
// precision. (GJK and the shape cast both start here.)
struct RelativeFrame {
    Mat3 r;
    Vec3 t;
};
inline RelativeFrame relative_frame(const Pose& pose_a, const Pose& pose_b) {
    return {transpose_mul(pose_a.rotation, pose_b.rotation), pose_a.to_local_direction(pose_b.translation - pose_a.translation)};
}

// Support of A - B in A's frame, where B's local frame maps into A's by x -> r x + t.
template <class SA, class SB>
struct PairSupport {
    SA sa;
    SB sb;
    Mat3 r;
    Vec3 t;
    // w = s_A(d) - s_B(-d); also returns the two support points (B's in A's frame).
    Vec3 operator()(Vec3 d, Vec3& out_a, Vec3& out_b) const {
        out_a = sa(d);
        out_b = r * sb(mul_transpose(r, -d)) + t;
        return out_a - out_b;
    }
};


enum class Core { Point, Segment, Box, SmallHull, Generic };

struct CoreOf {
    Core core;
    double radius;
};

inline CoreOf classify(const Shape& s) {
    switch (s.kind()) {
        case ShapeKind::Point:
            return {Core::Point, 0};
        case ShapeKind::Sphere:
            return {Core::Point, static_cast<const SphereShape&>(s).radius};
        case ShapeKind::Segment:
            return {Core::Segment, 0};
        case ShapeKind::Capsule:
            return {Core::Segment, static_cast<const CapsuleShape&>(s).radius};
        case ShapeKind::Box:
            return {Core::Box, 0};
        case ShapeKind::ConvexHull: {
            const auto& h = static_cast<const ConvexHullShape&>(s);
            if (!h.vertices.empty() && h.vertices.size() <= ConvexHullShape::kHillClimbThreshold) return {Core::SmallHull, 0};
            return {Core::Generic, 0};
        }
        default:
            return {Core::Generic, 0};
    }
}

template <class Fn>
auto with_support(const Shape& s, Core c, Fn&& fn) {
    switch (c) {
        case Core::Point:
            return fn(PointSupport{});
        case Core::Segment:
            return fn(SegmentSupport{s.kind() == ShapeKind::Capsule ? static_cast<const CapsuleShape&>(s).half_height
                                                                    : static_cast<const SegmentShape&>(s).half_length});
        case Core::Box:
            return fn(BoxSupport{static_cast<const BoxShape&>(s).half_extents});
        case Core::SmallHull: {
            const auto& h = static_cast<const ConvexHullShape&>(s);
            return fn(SmallHullSupport{h.vertices.data(), h.vertices.size()});
        }
        case Core::Generic:
            break;
    }
    return fn(GenericSupport{&s});
}

}  // namespace kairos::kernels
