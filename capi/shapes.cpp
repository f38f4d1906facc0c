// SPDX-License-Identifier: MIT
// C API shape constructors and queries: validate, then build or query the core's shapes.
#include <cmath>
#include <cstdint>

#include "boundary.hpp"

using namespace kairos;
using namespace kairos::capi;

namespace {

// Hands a new core shape to the caller: the only place a shape handle is written.
void publish(const Shape* s, kairos_shape** out) { *out = handle_of(s); }

}  // namespace

extern "C" {

KAIROS_API int32_t kairos_shape_sphere(double radius, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_size(radius, fn, "radius");
        require_pointer(out, fn, "out");
        publish(new SphereShape(radius), out);
    });
}

KAIROS_API int32_t kairos_shape_box(kairos_vec3 half_extents, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_size(half_extents.x, fn, "half_extents.x");
        require_size(half_extents.y, fn, "half_extents.y");
        require_size(half_extents.z, fn, "half_extents.z");
        require_pointer(out, fn, "out");
        publish(new BoxShape({half_extents.x, half_extents.y, half_extents.z}), out);
    });
}

KAIROS_API int32_t kairos_shape_capsule(double radius, double half_height, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_size(radius, fn, "radius");
        require_size(half_height, fn, "half_height", /*allow_zero=*/true);
        require_pointer(out, fn, "out");
        publish(new CapsuleShape(radius, half_height), out);
    });
}

KAIROS_API int32_t kairos_shape_cylinder(double radius, double half_height, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_size(radius, fn, "radius");
        require_size(half_height, fn, "half_height");
        require_pointer(out, fn, "out");
        publish(new CylinderShape(radius, half_height), out);
    });
}

KAIROS_API int32_t kairos_shape_cone(double radius, double half_height, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_size(radius, fn, "radius");
        require_size(half_height, fn, "half_height");
        require_pointer(out, fn, "out");
        publish(new ConeShape(radius, half_height), out);
    });
}

KAIROS_API int32_t kairos_shape_point(kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(out, fn, "out");
        publish(new PointShape(), out);
    });
}

KAIROS_API int32_t kairos_shape_segment(double half_length, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_size(half_length, fn, "half_length");
        require_pointer(out, fn, "out");
        publish(new SegmentShape(half_length), out);
    });
}

KAIROS_API int32_t kairos_shape_convex_hull(const kairos_vec3* points, size_t count, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        if (count > 0) require_pointer(points, fn, "points");
        require_pointer(out, fn, "out");
        if (count > UINT32_MAX)
            fail(KAIROS_ERROR_LIMIT, fn, "count %zu exceeds the limit of %u points", count, UINT32_MAX);
        if (count == 0) fail(KAIROS_ERROR_DEGENERATE, fn, "count is 0: the hull of no points is no shape");
        char name[64];
        std::vector<Vec3> local(count);
        for (size_t i = 0; i < count; ++i) {
            std::snprintf(name, sizeof name, "points[%zu]", i);
            local[i] = read_point(points[i], fn, name);  // names a bad coordinate and throws
        }
        ConvexHullShape* hull = nullptr;
        if (make_convex_hull(local.data(), count, &hull) != HullStatus::Ok)
            fail(KAIROS_ERROR_INTERNAL, fn, "points: the checked set was refused by the hull builder");
        publish(hull, out);
    });
}

KAIROS_API int32_t kairos_shape_triangle(kairos_vec3 a, kairos_vec3 b, kairos_vec3 c, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        const Vec3 pa = read_point(a, fn, "a"), pb = read_point(b, fn, "b"), pc = read_point(c, fn, "c");
        require_pointer(out, fn, "out");
        ConvexHullShape* tri = nullptr;
        if (make_triangle(pa, pb, pc, &tri) != HullStatus::Ok)
            fail(KAIROS_ERROR_DEGENERATE, fn,
                 "a, b, c are collinear or coincide (relative to the longest side): a triangle needs three corners");
        publish(tri, out);
    });
}

KAIROS_API int32_t kairos_shape_minkowski_sum(const kairos_shape* a, const kairos_shape* b, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(a, fn, "a");
        require_pointer(b, fn, "b");
        require_pointer(out, fn, "out");
        const Shape* sum = new MinkowskiSumShape(shape_of(a), shape_of(b));
        require_extent(sum, fn, "a + b");
        publish(sum, out);
    });
}

KAIROS_API int32_t kairos_shape_hull(const kairos_shape* a, const kairos_shape* b, kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(a, fn, "a");
        require_pointer(b, fn, "b");
        require_pointer(out, fn, "out");
        const Shape* both = new HullOfTwoShape(shape_of(a), shape_of(b));
        require_extent(both, fn, "the hull of a and b");
        publish(both, out);
    });
}

KAIROS_API int32_t kairos_shape_transformed(const kairos_shape* s, const double linear[9], kairos_vec3 translation,
                                            kairos_shape** out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(s, fn, "s");
        require_pointer(linear, fn, "linear");
        char name[32];
        for (int i = 0; i < 9; ++i) {
            std::snprintf(name, sizeof name, "linear[%d]", i);
            require_finite(linear[i], fn, name);
        }
        const Vec3 t = read_point(translation, fn, "translation");
        require_pointer(out, fn, "out");
        Mat3 m;
        for (std::size_t i = 0; i < 3; ++i) m.r[i] = {linear[3 * i], linear[3 * i + 1], linear[3 * i + 2]};
        // Invertible relative to its own scale: |det| against the product of the row lengths
        // (Hadamard's bound), so a uniformly tiny or huge matrix is judged like a unit one.
        const double bound = length(m.r[0]) * length(m.r[1]) * length(m.r[2]);
        const double det = determinant(m);
        if (!(std::fabs(det) > 1e-12 * bound))
            fail(KAIROS_ERROR_INVALID_ARGUMENT, fn,
                 "linear is singular or nearly so (det %g, product of row lengths %g)", det, bound);
        const Shape* mapped = new TransformedShape(shape_of(s), m, t);
        require_extent(mapped, fn, "the transformed shape");
        publish(mapped, out);
    });
}

KAIROS_API void kairos_shape_retain(kairos_shape* s) {
    if (s != nullptr) shape_of(s).retain();
}

KAIROS_API void kairos_shape_release(kairos_shape* s) {
    if (s != nullptr) shape_of(s).release();
}

KAIROS_API int32_t kairos_shape_support(const kairos_shape* s, kairos_vec3 direction, kairos_vec3* out) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(s, fn, "s");
        Vec3 d = read_vec3(direction, fn, "direction");
        require_pointer(out, fn, "out");
        // A support depends only on the direction: scaled by a power of two (exact) to a largest
        // component in [1, 2), a subnormal or huge direction compares like a unit one (a cone's
        // apex and rim scores both underflowed to 0 for d = (4e-322, 0, 0), and the apex won).
        if (const double m = max_abs(d); m > 0) {
            const int e = std::ilogb(m);
            d = {std::ldexp(d.x, -e), std::ldexp(d.y, -e), std::ldexp(d.z, -e)};
        }
        const Vec3 p = support(shape_of(s), d);
        require_finite_result(is_finite(p), fn);
        *out = to_c(p);
    });
}

KAIROS_API int32_t kairos_shape_bounds(const kairos_shape* s, const kairos_pose* pose, kairos_vec3* min,
                                       kairos_vec3* max) {
    const char* const fn = __func__;
    return guarded(fn, [&] {
        require_pointer(s, fn, "s");
        const Transform p = read_transform(pose, fn, "pose");
        require_pointer(min, fn, "min");
        require_pointer(max, fn, "max");
        Vec3 lo, hi;
        bounds(shape_of(s), p, lo, hi);
        *min = to_c(lo);
        *max = to_c(hi);
    });
}

}  // extern "C"
