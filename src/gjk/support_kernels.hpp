// SPDX-License-Identifier: MIT
// Support mappings of the shapes GJK and the casts specialise on, and the dispatch that picks
// one per shape: templates, so the inner loops inline the support with no virtual call.
//
// Spheres and capsules are a point or a segment plus a radius: the loops run on the core and fold
// the radius into their tests (fewer iterations on round shapes).
#pragma once

#include <cmath>
#include <cstddef>
#include <type_traits>

#include "math/math.hpp"
#include "shapes/shape.hpp"
#include "shapes/small_hull.hpp"

namespace kairos::kernels {

struct PointSupport {
    Vec3 operator()(Vec3) const { return {}; }
};
struct SegmentSupport {
    double h;
    Vec3 operator()(Vec3 d) const { return {0, 0, toward(d.z, h)}; }
};
struct BoxSupport {
    Vec3 h;
    Vec3 operator()(Vec3 d) const { return {toward(d.x, h.x), toward(d.y, h.y), toward(d.z, h.z)}; }
};
// Brute force over a small hull's vertices, structure-of-arrays (shapes/small_hull.hpp: the
// lowest index among the best, the same vertex on every instruction set).
struct SmallHullSupport {
    const Vec3* v;
    const double* xyz;
    size_t n;
    Vec3 operator()(Vec3 d) const { return small_hull::best_point(v, xyz, n, d); }
};
// A cylinder or a cone: no switch on the kind per call (the flag is the same on every call, so
// its branch predicts). Curved: its points are rounded, as GenericSupport's may be.
struct RevolutionSupport {
    double radius, half_height;
    bool cone;
    [[gnu::always_inline]] Vec3 operator()(Vec3 d) const {
        return cone ? cone_support(radius, half_height, d) : cylinder_support(radius, half_height, d);
    }
};
struct GenericSupport {
    const Shape* s;
    Vec3 operator()(Vec3 d) const { return support(*s, d); }
};

// Supports whose points are exact (points, segments, boxes, small hulls); cylinders and cones go
// through RevolutionSupport, other curved and general shapes through GenericSupport.
template <class S>
constexpr bool exact_support = !std::is_same_v<S, GenericSupport> && !std::is_same_v<S, RevolutionSupport>;

// B's local frame in A's: x -> r x + t, with r = Ra^T Rb and t = Ra^T (tb - ta). The translation
// difference is taken before rotating, so shapes far from the world origin keep their relative
// precision. (GJK and the shape cast both start here.)
struct RelativeFrame {
    Mat3 r;
    Vec3 t;
};
inline RelativeFrame relative_frame(const Transform& pose_a, const Transform& pose_b) {
    return {transpose_mul(pose_a.rotation, pose_b.rotation),
            pose_a.to_local_direction(pose_b.translation - pose_a.translation)};
}

// Support of A - B in A's frame, where B's local frame maps into A's by x -> r x + t.
template <class SA, class SB>
struct PairSupport {
    static constexpr bool exact = exact_support<SA> && exact_support<SB>;
    SA sa;
    SB sb;
    Mat3 r;
    Vec3 t;
    // A power of two every point is multiplied by (exact): GJK on shapes 1e-160 or 1e99 in size
    // runs at unit scale, where its squares and determinants (up to sixth powers of the size)
    // neither underflow nor overflow. 1 for shapes of ordinary size.
    double scale = 1;
    // w = s_A(d) - s_B(-d); also returns the two support points (B's in A's frame, times scale).
    [[gnu::always_inline]] Vec3 operator()(Vec3 d, Vec3& out_a, Vec3& out_b) const {
        out_a = sa(d);
        out_b = r * sb(mul_transpose(r, -d)) + t;
        // A branch, not a multiply by 1: the product would sit on the loop's critical path.
        if (scale != 1) [[unlikely]] {
            out_a = scale * out_a;
            out_b = scale * out_b;
        }
        return out_a - out_b;
    }
};

// The scale for a pair whose first support points are a and b: 1 while their largest coordinate
// is within 2^+-100 of 1, else the power of two that brings it to about 1.
inline double pair_scale(Vec3 a, Vec3 b) {
    // Plain comparisons (maxsd), not std::fmax (a library call here); a NaN coordinate is ignored.
    auto mx = [](double x, double y) { return y > x ? y : x; };
    const double m = mx(mx(mx(std::fabs(a.x), std::fabs(a.y)), mx(std::fabs(a.z), std::fabs(b.x))),
                        mx(std::fabs(b.y), std::fabs(b.z)));
    if (!(m > 0) || !std::isfinite(m) || (m >= 0x1p-100 && m <= 0x1p100)) return 1;
    int e = -std::ilogb(m);
    e = e > 1000 ? 1000 : (e < -1000 ? -1000 : e);
    return std::ldexp(1.0, e);
}

// The scale for a loop whose first support points are a and b, and which also works with the
// point x (the cast's ray start; else 0). A scale that enlarges is checked against the pair's
// extent first: one support point can lie far inside it (a needle 1e15 long with a vertex 1e-300
// from its origin, met first, took its far end to infinity; found by fuzzing). The supports along
// the six axes bound every support point's coordinates, so their largest sets the scale then.
// Only pairs whose first points all lie within 2^-100 of the origin pay the six calls.
template <class Pair>
[[gnu::noinline]] double first_scale_slow(const Pair& pair, double near) {
    auto mx = [](double p, double q) { return q > p ? q : p; };
    const double sc = pair_scale({near, 0, 0}, {});
    if (!(sc > 1)) return sc;
    double big = near;
    for (int i = 0; i < 6; ++i) {
        Vec3 d{}, pa, pb;
        d[i / 2] = i % 2 ? -1.0 : 1.0;
        pair(d, pa, pb);
        big = mx(big, mx(max_abs(pa), max_abs(pb)));
    }
    return pair_scale({big, 0, 0}, {});
}
// Inline: the first points of pairs of ordinary size decide it with two comparisons.
template <class Pair>
[[gnu::always_inline]] inline double first_scale(const Pair& pair, Vec3 a, Vec3 b, Vec3 x = {}) {
    auto mx = [](double p, double q) { return q > p ? q : p; };
    const double near = mx(max_abs(a), mx(max_abs(b), max_abs(x)));
    if (near >= 0x1p-100 && near <= 0x1p100) return 1;  // pair_scale's answer for it
    return first_scale_slow(pair, near);
}

// Brings a loop to the scale `sc` after its first support call: the support functor scales every
// later point itself; the first points and the margin are scaled here (exact: a power of two).
template <class Support>
inline void adopt_scale(Support& sup, double sc, Vec3& a, Vec3& b, double& margin) {
    sup.scale = sc;
    a = sc * a;
    b = sc * b;
    margin *= sc;
}

enum class Core { Point, Segment, Box, SmallHull, Revolution, Generic };

// A shape as a core plus a radius: `shape` is the core's shape (the shape itself, or the operand
// of a Minkowski sum with a sphere), `core` how to take its support.
struct CoreOf {
    Core core;
    double radius;
    const Shape* shape;
};

CoreOf classify(const Shape& s);

// Anything grown by a sphere is its core plus the radius, as spheres and capsules are: GJK then
// converges on the core (a rounded box's corner is a point, not a sphere patch that needs many
// iterations). Nested sums add their radii. Out of line: classify() stays small and inlined.
[[gnu::noinline]] inline CoreOf classify_sum(const MinkowskiSumShape& m) {
    const Shape* other = nullptr;
    double r = 0;
    if (m.b->kind() == ShapeKind::Sphere) {
        other = m.a;
        r = static_cast<const SphereShape*>(m.b)->radius;
    } else if (m.a->kind() == ShapeKind::Sphere) {
        other = m.b;
        r = static_cast<const SphereShape*>(m.a)->radius;
    }
    if (other == nullptr) return {Core::Generic, 0, &m};
    CoreOf c = classify(*other);
    c.radius += r;
    return c;
}

inline CoreOf classify(const Shape& s) {
    switch (s.kind()) {
        case ShapeKind::Point:
            return {Core::Point, 0, &s};
        case ShapeKind::Sphere:
            return {Core::Point, static_cast<const SphereShape&>(s).radius, &s};
        case ShapeKind::Segment:
            return {Core::Segment, 0, &s};
        case ShapeKind::Capsule:
            return {Core::Segment, static_cast<const CapsuleShape&>(s).radius, &s};
        case ShapeKind::Box:
            return {Core::Box, 0, &s};
        case ShapeKind::ConvexHull: {
            const auto& h = static_cast<const ConvexHullShape&>(s);
            if (!h.vertices.empty() && h.vertices.size() <= ConvexHullShape::kHillClimbThreshold &&
                h.soa.size() == 3 * small_hull::padded(h.vertices.size()))
                return {Core::SmallHull, 0, &s};
            return {Core::Generic, 0, &s};
        }
        case ShapeKind::Cylinder:
        case ShapeKind::Cone:
            return {Core::Revolution, 0, &s};
        case ShapeKind::MinkowskiSum:
            return classify_sum(static_cast<const MinkowskiSumShape&>(s));
        default:
            return {Core::Generic, 0, &s};
    }
}

// Half length along local z of a Core::Segment's shape (a capsule or a segment).
inline double segment_half_length(const Shape& s) {
    return s.kind() == ShapeKind::Capsule ? static_cast<const CapsuleShape&>(s).half_height
                                          : static_cast<const SegmentShape&>(s).half_length;
}

template <class Fn>
auto with_support(const CoreOf& c, Fn&& fn) {
    const Shape& s = *c.shape;
    switch (c.core) {
        case Core::Point:
            return fn(PointSupport{});
        case Core::Segment:
            return fn(SegmentSupport{segment_half_length(s)});
        case Core::Box:
            return fn(BoxSupport{static_cast<const BoxShape&>(s).half_extents});
        case Core::SmallHull: {
            const auto& h = static_cast<const ConvexHullShape&>(s);
            return fn(SmallHullSupport{h.vertices.data(), h.soa.data(), h.vertices.size()});
        }
        case Core::Revolution: {
            if (s.kind() == ShapeKind::Cone) {
                const auto& c = static_cast<const ConeShape&>(s);
                return fn(RevolutionSupport{c.radius, c.half_height, true});
            }
            const auto& c = static_cast<const CylinderShape&>(s);
            return fn(RevolutionSupport{c.radius, c.half_height, false});
        }
        case Core::Generic:
            break;
    }
    return fn(GenericSupport{&s});
}

// Calls fn(pair_support, margin) with the pair's support of A - B in A's frame.
template <class Fn>
auto with_pair(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b, Fn&& fn) {
    const RelativeFrame frame = relative_frame(pose_a, pose_b);
    const Mat3& r = frame.r;
    const Vec3 t = frame.t;
    const double margin = ca.radius + cb.radius;
    return with_support(ca, [&](auto sa) {
        return with_support(cb, [&](auto sb) {
            return fn(PairSupport<decltype(sa), decltype(sb)>{sa, sb, r, t}, margin);
        });
    });
}

}  // namespace kairos::kernels
