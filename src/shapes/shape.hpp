// SPDX-License-Identifier: MIT
// Convex shapes as support mappings: the immutable, reference-counted shape objects of the core.
//
// A shape stores only what its support mapping needs (a box is three half extents). Support
// dispatch is a switch on the kind, inlined into the callers: no virtual call per support point.
#pragma once

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__SSE2__) && defined(__x86_64__)
#include <emmintrin.h>
#endif

#include "math/transform.hpp"

namespace kairos {

enum class ShapeKind : uint8_t {
    Point,
    Segment,       // (0,0,-h) .. (0,0,+h)
    Sphere,        // radius about the origin
    Box,           // [-h, h] per axis
    Capsule,       // segment (0,0,+-h) grown by radius
    Cylinder,      // radius, z in [-h, h]
    Cone,          // apex (0,0,+h), base disk radius r at z = -h
    ConvexHull,    // vertices of a convex polytope
    Transformed,   // x -> linear * x + translation of a child
    MinkowskiSum,  // a + b
    HullOfTwo,     // conv(a u b)
    Disk,          // radius about the origin, perpendicular to a unit normal: internal, the
                   // rotation bound of a turning shape (docs/algorithms.md §4); not in the C API
};

// Base of every shape. Reference counted (atomic), immutable after construction. Composites
// hold a reference to each part. Created with one reference; `release` deletes at zero.
class Shape {
public:
    Shape(const Shape&) = delete;
    Shape& operator=(const Shape&) = delete;
    virtual ~Shape() = default;

    ShapeKind kind() const { return kind_; }
    void retain() const { refs_.fetch_add(1, std::memory_order_relaxed); }
    void release() const {
        if (refs_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete this;
    }
    uint32_t reference_count() const { return refs_.load(std::memory_order_relaxed); }

protected:
    explicit Shape(ShapeKind kind) : kind_(kind) {}

private:
    mutable std::atomic<uint32_t> refs_{1};
    ShapeKind kind_;
};

struct PointShape final : Shape {
    PointShape() : Shape(ShapeKind::Point) {}
};
struct SegmentShape final : Shape {
    explicit SegmentShape(double h) : Shape(ShapeKind::Segment), half_length(h) {}
    double half_length;
};
struct SphereShape final : Shape {
    explicit SphereShape(double r) : Shape(ShapeKind::Sphere), radius(r) {}
    double radius;
};
struct BoxShape final : Shape {
    explicit BoxShape(Vec3 h) : Shape(ShapeKind::Box), half_extents(h) {}
    Vec3 half_extents;
};
struct CapsuleShape final : Shape {
    CapsuleShape(double r, double h) : Shape(ShapeKind::Capsule), radius(r), half_height(h) {}
    double radius, half_height;
};
struct CylinderShape final : Shape {
    CylinderShape(double r, double h) : Shape(ShapeKind::Cylinder), radius(r), half_height(h) {}
    double radius, half_height;
};
struct ConeShape final : Shape {
    ConeShape(double r, double h) : Shape(ShapeKind::Cone), radius(r), half_height(h) {}
    double radius, half_height;
};

// A convex polytope by its vertices only. `neighbors` lists, for vertex i, the indices
// neighbors[neighbor_offsets[i] .. neighbor_offsets[i+1]) joined to it by a hull edge; it is
// filled only when the hull has more than kHillClimbThreshold vertices (support then climbs).
//
// Flat and lower-dimensional sets are hulls too: `dimension` is 3 for a solid, 2 for a flat
// convex polygon (vertices in order around it), 1 for a segment (2 vertices), 0 for a point.
struct ConvexHullShape final : Shape {
    static constexpr size_t kHillClimbThreshold = 32;
    ConvexHullShape() : Shape(ShapeKind::ConvexHull) {}
    std::vector<Vec3> vertices;
    uint8_t dimension = 3;
    std::vector<uint32_t> neighbor_offsets;
    std::vector<uint32_t> neighbors;
    // A hull that does not climb also keeps its vertices structure-of-arrays (small_hull::layout):
    // its brute-force support reads them a vector at a time.
    std::vector<double> soa;
    Vec3 support(Vec3 d) const;  // in hull.cpp
};

struct TransformedShape final : Shape {
    TransformedShape(const Shape& c, const Mat3& l, Vec3 t)
        : Shape(ShapeKind::Transformed), child(&c), linear(l), translation(t), rigid(is_rotation(l)) {
        child->retain();
    }
    ~TransformedShape() override { child->release(); }
    const Shape* child;
    Mat3 linear;
    Vec3 translation;
    // linear is a rotation to rounding: the shape is its child placed rigidly (see unwrap_rigid).
    bool rigid;

private:
    // Orthonormal to 16 units in the last place of 1 (rotation matrices of normalised
    // quaternions reach 11) and not a reflection.
    static bool is_rotation(const Mat3& l) {
        const Mat3 g = transpose_mul(l, l);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (!(std::fabs(g.r[i][j] - (i == j ? 1.0 : 0.0)) <= 0x1p-48)) return false;
        return determinant(l) > 0;
    }
};

// A shape and the pose of its local frame.
struct PlacedShape {
    const Shape* shape;
    Transform pose;
};

// True when s is a rigidly transformed shape (a TransformedShape whose linear part is a rotation).
inline bool rigidly_placed(const Shape& s) {
    return s.kind() == ShapeKind::Transformed && static_cast<const TransformedShape&>(s).rigid;
}

// A rigidly transformed shape at pose is its child at the composed pose (nested ones in turn).
// The queries take the child from here, so its closed forms and support kernel apply: two
// translated balls once went to the expansion through the generic support, 135 us and 1 % short
// of the depth, instead of the ball/ball closed form. The shape is the same to rounding (the
// rotation's 16 units in the last place); the composed pose is exact for an identity linear part.
inline PlacedShape unwrap_rigid(const Shape& s, const Transform& pose) {
    PlacedShape p{&s, pose};
    while (rigidly_placed(*p.shape)) {
        const auto& t = static_cast<const TransformedShape&>(*p.shape);
        p.pose = {p.pose.rotation * t.linear, p.pose.apply(t.translation)};
        p.shape = t.child;
    }
    return p;
}
// A shape made of two others, each kept alive by a reference it holds.
struct BinaryShape : Shape {
    BinaryShape(ShapeKind k, const Shape& a_, const Shape& b_) : Shape(k), a(&a_), b(&b_) {
        a->retain();
        b->retain();
    }
    ~BinaryShape() override {
        a->release();
        b->release();
    }
    const Shape* a;
    const Shape* b;
};
struct MinkowskiSumShape final : BinaryShape {
    MinkowskiSumShape(const Shape& a_, const Shape& b_) : BinaryShape(ShapeKind::MinkowskiSum, a_, b_) {}
};
struct HullOfTwoShape final : BinaryShape {
    HullOfTwoShape(const Shape& a_, const Shape& b_) : BinaryShape(ShapeKind::HullOfTwo, a_, b_) {}
};

// A flat disk of `radius` centred at the origin, perpendicular to unit `normal`.
struct DiskShape final : Shape {
    DiskShape(Vec3 n, double r) : Shape(ShapeKind::Disk), normal(n), radius(r) {}
    Vec3 normal;
    double radius;
};

// Sign used by supports: +1 for zero, so a zero direction still yields a point of the shape.
inline double support_sign(double v) { return v < 0 ? -1.0 : 1.0; }
// support_sign(d) * h, bit for bit for any h but a NaN (NaN and zero d keep h), without a
// branch: the signs of a support direction's coordinates change unpredictably from one GJK
// iteration to the next, and the compiler turns the select into a branch, mispredicted about as
// often. On x86-64 the comparison's mask flips h's sign bit.
inline double toward(double d, double h) {
#if defined(__SSE2__) && defined(__x86_64__)
    const __m128d negative = _mm_cmplt_sd(_mm_set_sd(d), _mm_setzero_pd());
    return _mm_cvtsd_f64(_mm_xor_pd(_mm_set_sd(h), _mm_and_pd(negative, _mm_set_sd(-0.0))));
#else
    return support_sign(d) * h;
#endif
}

// Supports of the two solids of revolution about z (local frame, any finite d): a cylinder of
// radius r over z in [-h, h], and a cone with its apex at (0, 0, h) and its base disk of radius r
// at z = -h. support() and the GJK kernels (RevolutionSupport) share them.
inline Vec3 cylinder_support(double r, double h, Vec3 d) {
    const Planar radial = radial_unit(d.x, d.y);
    return {r * radial.x, r * radial.y, toward(d.z, h)};
}
inline Vec3 cone_support(double r, double h, Vec3 d) {
    const Planar radial = radial_unit(d.x, d.y);
    // Apex when d.z*h >= d.(base rim point) = r*|d_xy| - d.z*h.
    const double apex_score = d.z * h;
    const double rim_score = r * (d.x * radial.x + d.y * radial.y) - d.z * h;
    if (apex_score >= rim_score) return {0, 0, h};
    return {r * radial.x, r * radial.y, -h};
}

// A point of `s` (local frame) maximising d . x. Any finite d, zero included.
inline Vec3 support(const Shape& s, Vec3 d) {
    switch (s.kind()) {
        case ShapeKind::Point:
            return {};
        case ShapeKind::Segment:
            return {0, 0, toward(d.z, static_cast<const SegmentShape&>(s).half_length)};
        case ShapeKind::Sphere:
            return static_cast<const SphereShape&>(s).radius * normalized_or(d, {0, 0, 1});
        case ShapeKind::Box: {
            const Vec3 h = static_cast<const BoxShape&>(s).half_extents;
            return {toward(d.x, h.x), toward(d.y, h.y), toward(d.z, h.z)};
        }
        case ShapeKind::Capsule: {
            const auto& c = static_cast<const CapsuleShape&>(s);
            return Vec3{0, 0, toward(d.z, c.half_height)} + c.radius * normalized_or(d, {0, 0, 1});
        }
        case ShapeKind::Cylinder: {
            const auto& c = static_cast<const CylinderShape&>(s);
            return cylinder_support(c.radius, c.half_height, d);
        }
        case ShapeKind::Cone: {
            const auto& c = static_cast<const ConeShape&>(s);
            return cone_support(c.radius, c.half_height, d);
        }
        case ShapeKind::ConvexHull:
            return static_cast<const ConvexHullShape&>(s).support(d);
        case ShapeKind::Transformed: {
            const auto& t = static_cast<const TransformedShape&>(s);
            // A huge d through a large linear part would overflow to inf (a NaN point), a tiny
            // one through a small part underflow to zero: rescale such d by a power of two
            // (exact, and a support depends only on the direction).
            const double m = max_abs(d);
            if (m > 0x1p+500 || (m < 0x1p-500 && m > 0)) {
                const int e = std::ilogb(m);
                d = {std::ldexp(d.x, -e), std::ldexp(d.y, -e), std::ldexp(d.z, -e)};
            }
            return t.linear * support(*t.child, mul_transpose(t.linear, d)) + t.translation;
        }
        case ShapeKind::MinkowskiSum: {
            const auto& m = static_cast<const MinkowskiSumShape&>(s);
            return support(*m.a, d) + support(*m.b, d);
        }
        case ShapeKind::HullOfTwo: {
            const auto& h = static_cast<const HullOfTwoShape&>(s);
            const Vec3 pa = support(*h.a, d), pb = support(*h.b, d);
            return dot(d, pb) > dot(d, pa) ? pb : pa;
        }
        case ShapeKind::Disk: {
            // A direction (nearly) along the normal has every disk point as a maximiser: return
            // the centre there; normalising the tiny in-plane rest would make the bound unsafe.
            const auto& k = static_cast<const DiskShape&>(s);
            const Vec3 in_plane = d - dot(d, k.normal) * k.normal;
            const double m = max_abs(in_plane);
            if (!(m > 1e-300) || !(m > 1e-15 * max_abs(d))) return {};
            return k.radius * normalized_or(in_plane, {});
        }
    }
    return {};
}

// True when every support point of `s` is a vertex of finitely many (a polytope: points,
// segments, boxes, hulls, and transforms, sums and hulls of them), so a support carries only the
// rounding of its arithmetic; false when some part is curved (its points are rounded).
inline bool polytope(const Shape& s) {
    switch (s.kind()) {
        case ShapeKind::Point:
        case ShapeKind::Segment:
        case ShapeKind::Box:
        case ShapeKind::ConvexHull:
            return true;
        case ShapeKind::Transformed:
            return polytope(*static_cast<const TransformedShape&>(s).child);
        case ShapeKind::MinkowskiSum: {
            const auto& m = static_cast<const MinkowskiSumShape&>(s);
            return polytope(*m.a) && polytope(*m.b);
        }
        case ShapeKind::HullOfTwo: {
            const auto& h = static_cast<const HullOfTwoShape&>(s);
            return polytope(*h.a) && polytope(*h.b);
        }
        default:
            return false;
    }
}

// Support of the shape placed at `pose`, in world frame.
inline Vec3 support(const Shape& s, const Transform& pose, Vec3 world_direction) {
    return pose.apply(support(s, pose.to_local_direction(world_direction)));
}

// Tight axis-aligned box of the shape at `pose` (world frame), from six support queries.
void bounds(const Shape& s, const Transform& pose, Vec3& out_min, Vec3& out_max);

// Convex hull construction (hull.cpp).
enum class HullStatus { Ok, Empty, NonFinite, Collinear };
// Builds the hull of `count` points: Ok for every non-empty set of finite points, whatever its
// dimension (see ConvexHullShape::dimension; "flat" is relative to the set's extent, as the
// file comment of hull.cpp says). Empty for count 0, NonFinite for a NaN or infinite coordinate.
// On Ok, *out_shape holds a new shape (one reference). Throws std::bad_alloc on allocation failure.
HullStatus make_convex_hull(const Vec3* points, size_t count, ConvexHullShape** out_shape);
// The triangle a, b, c (a flat hull of three vertices). Collinear when c lies within 1e-10 of
// the longest side's length from the line of that side (or two points coincide); NonFinite as above.
HullStatus make_triangle(Vec3 a, Vec3 b, Vec3 c, ConvexHullShape** out_shape);

}  // namespace kairos
