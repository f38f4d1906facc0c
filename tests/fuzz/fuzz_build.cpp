// SPDX-License-Identifier: MIT
// Shape construction for the fuzz targets: point sets, every constructor and combinator, each call
// checked against the status contract and each shape against its model (see fuzz_support.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "fuzz_support.hpp"

namespace kfuzz {

// ---- Point sets --------------------------------------------------------------------------------

std::vector<kairos_vec3> hull_points(Input& in) {
    const size_t count = in.u8() % 65;
    const unsigned mode = in.pick(12);
    Rng rng(in.u64());
    std::vector<kairos_vec3> base(count);
    const double eps = std::pow(10.0, -9 - static_cast<int>(in.pick(7)));  // 1e-9 .. 1e-15
    switch (mode) {
        case 0:  // random in a cube
            for (auto& p : base) p = {rng.symmetric(), rng.symmetric(), rng.symmetric()};
            break;
        case 1:  // small lattice from the bytes: many duplicates, collinear and coplanar runs
            for (auto& p : base)
                p = {double(int(in.u8() % 5) - 2), double(int(in.u8() % 5) - 2), double(int(in.u8() % 5) - 2)};
            break;
        case 2: {  // few distinct points, repeated
            kairos_vec3 distinct[4];
            for (auto& d : distinct) d = {rng.symmetric(), rng.symmetric(), rng.symmetric()};
            const unsigned k = 1 + in.pick(4);
            for (auto& p : base) p = distinct[rng.next() % k];
            break;
        }
        case 3:  // coplanar
            for (auto& p : base) p = {rng.symmetric(), rng.symmetric(), 0};
            break;
        case 4:  // collinear
            for (auto& p : base) p = {rng.symmetric(), 0, 0};
            break;
        case 5:  // nearly collinear: a line plus 1e-9 .. 1e-15
            for (auto& p : base) p = {rng.symmetric(), eps * rng.symmetric(), eps * rng.symmetric()};
            break;
        case 6:  // nearly coplanar
            for (auto& p : base) p = {rng.symmetric(), rng.symmetric(), eps * rng.symmetric()};
            break;
        case 7:  // on a sphere: every point a vertex, many nearly coplanar neighbours
            for (auto& p : base) {
                const real x = rng.symmetric(), y = rng.symmetric(), z = rng.symmetric();
                const real n = std::sqrt(x * x + y * y + z * z);
                p = n > 0 ? kairos_vec3{double(x / n), double(y / n), double(z / n)} : kairos_vec3{1, 0, 0};
            }
            break;
        case 8:  // a box's corners, then points on its faces
            for (size_t i = 0; i < count; ++i) {
                if (i < 8) {
                    base[i] = {i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0};
                } else {
                    kairos_vec3 p{rng.symmetric(), rng.symmetric(), rng.symmetric()};
                    const double side = rng.next() & 1 ? 1.0 : -1.0;
                    switch (rng.next() % 3) {
                        case 0:
                            p.x = side;
                            break;
                        case 1:
                            p.y = side;
                            break;
                        default:
                            p.z = side;
                            break;
                    }
                    base[i] = p;
                }
            }
            break;
        case 9:  // raw bits: anything, non-finite included (no placement)
            for (auto& p : base) p = {in.bits(), in.bits(), in.bits()};
            return base;
        case 10: {  // tight clusters around 2..4 centres
            kairos_vec3 centres[4];
            for (auto& c : centres) c = {rng.symmetric(), rng.symmetric(), rng.symmetric()};
            const unsigned k = 2 + in.pick(3);
            for (auto& p : base) {
                const kairos_vec3 c = centres[rng.next() % k];
                p = {c.x + eps * rng.symmetric(), c.y + eps * rng.symmetric(), c.z + eps * rng.symmetric()};
            }
            break;
        }
        default:  // one point, repeated
            for (auto& p : base) p = {0.25, -0.5, 0.75};
            break;
    }
    // Placement: scale (tiny to huge), rotation, offset (possibly far from the origin).
    const double scale = power_of_ten(in) * (in.rare(8) ? -1.0 : 1.0);
    const kairos_quat q = [&] {
        const kairos_quat r = orientation(in);
        return unit_quat(r.x, r.y, r.z, r.w);
    }();
    kairos_vec3 offset{0, 0, 0};
    switch (in.pick(4)) {
        case 0:
            break;
        case 1:
            offset = small_vec(in, 4);
            break;
        case 2: {
            const double far = std::pow(10.0, 3 + static_cast<int>(in.pick(13)));  // 1e3 .. 1e15
            offset = {far, -0.5 * far, 0.25 * far};
            break;
        }
        default:
            offset = small_vec(in, power_of_ten(in));
            break;
    }
    Model frame;
    const Placed rot = place(frame, q, {});
    const real* r = rot.rotation;
    for (auto& p : base) {
        const real x = scale * real(p.x), y = scale * real(p.y), z = scale * real(p.z);
        p = {static_cast<double>(offset.x + r[0] * x + r[1] * y + r[2] * z),
             static_cast<double>(offset.y + r[3] * x + r[4] * y + r[5] * z),
             static_cast<double>(offset.z + r[6] * x + r[7] * y + r[8] * z)};
    }
    if (count > 0 && in.rare(16)) {
        kairos_vec3& p = base[in.pick(static_cast<unsigned>(count))];
        const double v = edge_value(in);
        switch (in.pick(3)) {
            case 0:
                p.x = v;
                break;
            case 1:
                p.y = v;
                break;
            default:
                p.z = v;
                break;
        }
    }
    return base;
}

// ---- Shape construction ------------------------------------------------------------------------

namespace {

// A size argument: finite and > 0 (>= 0 when allow_zero), else INVALID_ARGUMENT.
void expect_size(double v, bool allow_zero, Verdict& verdict, Model& m) {
    if (!std::isfinite(v) || (allow_zero ? !(v >= 0) : !(v > 0))) {
        verdict.require(KAIROS_ERROR_INVALID_ARGUMENT);
    } else if (!moderate(v)) {
        verdict.unsure();
        m.moderate = false;
    }
}

void finish_primitive_tolerance(Model& m) {
    m.tolerance = kRelative * m.magnitude + kFloor;
    if (m.magnitude > kModerateMax) m.moderate = false;
}

}  // namespace

std::optional<Built> ShapeBuilder::finish(const char* function, int32_t status, kairos_shape* out,
                                          const Verdict& verdict, std::shared_ptr<Model> model) {
    verdict.check(status, function);
    if (status != KAIROS_OK) {
        if (!poisoned(out)) violation("%s failed with %s but wrote *out", function, kairos_status_name(status));
        return std::nullopt;
    }
    if (out == nullptr) violation("%s returned KAIROS_OK with *out NULL", function);
    Built b{ShapeRef(out), std::move(model)};
    check_shape(out, *b.model, in_, thorough_);
    pool_.push_back(b);
    return b;
}

std::optional<Built> ShapeBuilder::primitive(unsigned kind) {
    auto m = std::make_shared<Model>();
    Verdict v;
    kairos_shape* out;
    poison(out);
    const bool null_out = in_.rare(32);
    if (null_out) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    kairos_shape** const dst = null_out ? nullptr : &out;
    int32_t status = KAIROS_OK;
    const char* fn = "";
    switch (kind) {
        case 0: {
            fn = "kairos_shape_sphere";
            const double r = length(in_);
            m->kind = Kind::Sphere;
            m->a = r;
            expect_size(r, false, v, *m);
            m->magnitude = std::fabs(real(r));
            status = observe(fn, [&] { return kairos_shape_sphere(r, dst); });
            break;
        }
        case 1: {
            fn = "kairos_shape_box";
            const unsigned shape = in_.pick(3);
            const double x = length(in_);
            // Cubes and thin plates as well as three independent sides.
            const double y = shape == 1 ? x : length(in_);
            const double z = shape == 1 ? x : shape == 2 ? x * 1e-9 : length(in_);
            m->kind = Kind::Box;
            m->a = x;
            m->b = y;
            m->c = z;
            expect_size(x, false, v, *m);
            expect_size(y, false, v, *m);
            expect_size(z, false, v, *m);
            m->magnitude = std::sqrt(real(x) * x + real(y) * y + real(z) * z);
            status = observe(fn, [&] { return kairos_shape_box({x, y, z}, dst); });
            break;
        }
        case 2:
        case 3:
        case 4: {
            const double r = length(in_);
            const double h = in_.rare(8) ? 0.0 : length(in_);
            m->a = r;
            m->b = h;
            expect_size(r, false, v, *m);
            expect_size(h, kind == 2, v, *m);
            m->magnitude = kind == 2 ? std::fabs(real(r)) + std::fabs(real(h)) : std::sqrt(real(r) * r + real(h) * h);
            if (kind == 2) {
                fn = "kairos_shape_capsule";
                m->kind = Kind::Capsule;
                status = observe(fn, [&] { return kairos_shape_capsule(r, h, dst); });
            } else if (kind == 3) {
                fn = "kairos_shape_cylinder";
                m->kind = Kind::Cylinder;
                status = observe(fn, [&] { return kairos_shape_cylinder(r, h, dst); });
            } else {
                fn = "kairos_shape_cone";
                m->kind = Kind::Cone;
                status = observe(fn, [&] { return kairos_shape_cone(r, h, dst); });
            }
            break;
        }
        case 5:
            fn = "kairos_shape_point";
            m->kind = Kind::Point;
            status = observe(fn, [&] { return kairos_shape_point(dst); });
            break;
        default: {
            fn = "kairos_shape_segment";
            const double h = length(in_);
            m->kind = Kind::Segment;
            m->a = h;
            expect_size(h, false, v, *m);
            m->magnitude = std::fabs(real(h));
            status = observe(fn, [&] { return kairos_shape_segment(h, dst); });
            break;
        }
    }
    finish_primitive_tolerance(*m);
    if (!m->moderate) v.unsure();
    return finish(fn, status, out, v, m);
}

namespace {

// The model of a point set (hull or triangle): support max d.p; tolerance 1e-9 of the set's
// extent plus 512 ulps of its largest coordinate (the hull may drop points within about 1e-12
// of the extent, plus 64 ulps, of the hull of the others).
void points_model(Model& m, const kairos_vec3* points, size_t count) {
    m.kind = Kind::Points;
    Vr lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    real largest = 0, magnitude = 0;
    for (size_t i = 0; i < count; ++i) {
        const Vr p = to_real(points[i]);
        m.points.push_back(p);
        lo = {std::fmin(lo.x, p.x), std::fmin(lo.y, p.y), std::fmin(lo.z, p.z)};
        hi = {std::fmax(hi.x, p.x), std::fmax(hi.y, p.y), std::fmax(hi.z, p.z)};
        largest = std::fmax(largest, max3(std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)));
        magnitude = std::fmax(magnitude, norm(p));
    }
    const real extent = count > 0 ? max3(hi.x - lo.x, hi.y - lo.y, hi.z - lo.z) : 0;
    m.magnitude = magnitude;
    m.tolerance = kRelative * extent + 512 * ulp(largest) + kFloor;
}

}  // namespace

std::optional<Built> ShapeBuilder::convex_hull() {
    static const char* const fn = "kairos_shape_convex_hull";
    std::vector<kairos_vec3> points = hull_points(in_);
    const size_t count = points.size();
    auto m = std::make_shared<Model>();
    Verdict v;
    kairos_shape* out;
    poison(out);
    const bool null_points = count > 0 && in_.rare(32);
    const bool null_out = in_.rare(32);
    if (null_points || null_out) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    bool all_finite = true;
    for (const kairos_vec3& p : points) {
        all_finite = all_finite && finite(p);
        m->moderate = m->moderate && moderate(p);
    }
    if (count == 0) {
        v.require(KAIROS_ERROR_DEGENERATE);
    } else if (!all_finite) {
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
        if (KAIROS_FUZZ_ALLOW_DEGENERATE_HULL) v.require(KAIROS_ERROR_DEGENERATE);
    } else {
        if (KAIROS_FUZZ_ALLOW_DEGENERATE_HULL) v.allow(KAIROS_ERROR_DEGENERATE);
        if (!m->moderate) v.unsure();
    }
    const kairos_vec3* data = null_points || count == 0 ? nullptr : points.data();
    if (count == 0 && in_.pick(2) == 1) data = points.data();  // an empty vector's pointer: maybe not NULL
    const int32_t status =
        observe(fn, [&] { return kairos_shape_convex_hull(data, count, null_out ? nullptr : &out); });
    if (status == KAIROS_OK) points_model(*m, points.data(), count);
    if (m->magnitude > kModerateMax) m->moderate = false;
    return finish(fn, status, out, v, m);
}

std::optional<Built> ShapeBuilder::triangle() {
    kairos_vec3 p[3];
    std::vector<kairos_vec3> points = hull_points(in_);
    for (int i = 0; i < 3; ++i) p[i] = i < static_cast<int>(points.size()) ? points[i] : position(in_);
#if KAIROS_FUZZ_HAVE_TRIANGLE
    static const char* const fn = "kairos_shape_triangle";
    auto m = std::make_shared<Model>();
    Verdict v;
    kairos_shape* out;
    poison(out);
    const bool null_out = in_.rare(32);
    if (null_out) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    if (!finite(p[0]) || !finite(p[1]) || !finite(p[2])) {
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
        m->moderate = false;
    } else {
        const Vr e1 = to_real(p[1]) - to_real(p[0]), e2 = to_real(p[2]) - to_real(p[0]);
        const Vr c{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
        // Clearly a triangle: its height over the longest side above 1e-6 of that side (the
        // library calls it degenerate below 1e-10), and every side longer than the rounding of
        // the coordinates (the library: 64 ulps of the largest; here 4 times that).
        const real longest = std::fmax(norm(e1), std::fmax(norm(e2), norm(e2 - e1)));
        const real shortest = std::fmin(norm(e1), std::fmin(norm(e2), norm(e2 - e1)));
        const real largest = max3(biggest(p[0]), biggest(p[1]), biggest(p[2]));
        const bool solid = norm(c) > 1e-6L * longest * longest && shortest > 256 * ulp(largest);
        m->moderate = moderate(p[0]) && moderate(p[1]) && moderate(p[2]);
        if (!solid || !m->moderate) v.unsure();
    }
    const int32_t status =
        observe(fn, [&] { return kairos_shape_triangle(p[0], p[1], p[2], null_out ? nullptr : &out); });
    char what[400];
    std::snprintf(what, sizeof what, "kairos_shape_triangle(%s, %s, %s)", show(p[0]), show(p[1]), show(p[2]));
    v.check(status, what);
    if (status == KAIROS_OK) points_model(*m, p, 3);
    if (m->magnitude > kModerateMax) m->moderate = false;
    return finish(fn, status, out, v, m);
#else
    // Without kairos_shape_triangle: the hull of the three points (degenerate before 0.2).
    static const char* const fn = "kairos_shape_convex_hull";
    auto m = std::make_shared<Model>();
    Verdict v;
    kairos_shape* out;
    poison(out);
    const bool all_finite = finite(p[0]) && finite(p[1]) && finite(p[2]);
    m->moderate = all_finite && moderate(p[0]) && moderate(p[1]) && moderate(p[2]);
    if (!all_finite) v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    if (KAIROS_FUZZ_ALLOW_DEGENERATE_HULL) {
        if (all_finite)
            v.allow(KAIROS_ERROR_DEGENERATE);
        else
            v.require(KAIROS_ERROR_DEGENERATE);
    }
    if (all_finite && !m->moderate) v.unsure();
    const int32_t status = observe(fn, [&] { return kairos_shape_convex_hull(p, 3, &out); });
    if (status == KAIROS_OK) points_model(*m, p, 3);
    if (m->magnitude > kModerateMax) m->moderate = false;
    return finish(fn, status, out, v, m);
#endif
}

std::optional<Built> ShapeBuilder::part(int depth) {
    if (!pool_.empty() && in_.pick(2) == 1)
        return pool_[in_.pick(static_cast<unsigned>(std::min<size_t>(pool_.size(), 256)))];
    return build(depth + 1);
}

std::optional<Built> ShapeBuilder::composite(unsigned kind, int depth) {
    std::optional<Built> first = part(depth);
    if (!first) return std::nullopt;
    auto m = std::make_shared<Model>();
    m->left = first->model;
    Verdict v;
    kairos_shape* out;
    poison(out);
    const unsigned null_probe = in_.rare(24) ? 1 + in_.pick(3) : 0;  // 1: first part, 2: second, 3: out
    if (null_probe != 0) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    kairos_shape** const dst = null_probe == 3 ? nullptr : &out;
    const kairos_shape* a = null_probe == 1 ? nullptr : first->shape.get();
    int32_t status;
    const char* fn;
    if (kind == 0 || kind == 1) {
        std::optional<Built> second = part(depth);
        if (!second) return std::nullopt;
        m->right = second->model;
        const kairos_shape* b = null_probe == 2 ? nullptr : second->shape.get();
        const Model &l = *m->left, &r = *m->right;
        m->moderate = l.moderate && r.moderate;
        if (kind == 0) {
            fn = "kairos_shape_minkowski_sum";
            m->kind = Kind::MinkowskiSum;
            m->magnitude = l.magnitude + r.magnitude;
            m->tolerance = l.tolerance + r.tolerance + 4 * ulp(m->magnitude);
            status = observe(fn, [&] { return kairos_shape_minkowski_sum(a, b, dst); });
        } else {
            fn = "kairos_shape_hull";
            m->kind = Kind::HullOfTwo;
            m->magnitude = std::fmax(l.magnitude, r.magnitude);
            m->tolerance = std::fmax(l.tolerance, r.tolerance) + 4 * ulp(m->magnitude);
            status = observe(fn, [&] { return kairos_shape_hull(a, b, dst); });
        }
    } else {
        fn = "kairos_shape_transformed";
        m->kind = Kind::Transformed;
        double linear[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        switch (in_.pick(8)) {
            case 0:
                break;
            case 1: {  // rotation times a diagonal scale (negative entries mirror)
                const Placed rot = place(*m, orientation(in_), {});
                double s[3];
                for (double& si : s) si = (1.0 + in_.fraction()) * power_of_ten(in_) * (in_.rare(4) ? -1.0 : 1.0);
                for (int i = 0; i < 9; ++i) linear[i] = static_cast<double>(rot.rotation[i] * s[i % 3]);
                break;
            }
            case 2: {
                const double scale = power_of_ten(in_);
                for (double& e : linear) e = scale * in_.symmetric();
                break;
            }
            case 3:
            case 4: {  // singular (row 2 = a row 0 + b row 1), or nearly: plus 1e-8 .. 1e-16 of it
                for (int i = 0; i < 6; ++i) linear[i] = in_.symmetric();
                const double ca = in_.symmetric(), cb = in_.symmetric();
                const double e = in_.pick(2) == 0 ? 0.0 : std::pow(10.0, -8 - static_cast<int>(in_.pick(9)));
                for (int j = 0; j < 3; ++j) linear[6 + j] = ca * linear[j] + cb * linear[3 + j] + e * in_.symmetric();
                break;
            }
            case 5:
                for (double& e : linear) e = in_.bits();
                break;
            case 6:  // shear
                linear[in_.pick(2) == 0 ? 1 : 5] = in_.symmetric() * power_of_ten(in_);
                linear[in_.pick(2) == 0 ? 3 : 6] = in_.symmetric() * power_of_ten(in_);
                break;
            default:
                for (double& e : linear) e = in_.pick(4) == 0 ? edge_value(in_) : in_.symmetric();
                break;
        }
        const kairos_vec3 t = in_.pick(2) == 0 ? kairos_vec3{0, 0, 0} : position(in_);
        const bool null_linear = null_probe == 2;
        bool all_finite = finite(t);
        bool all_moderate = moderate(t);
        real frob = 0;
        for (int i = 0; i < 9; ++i) {
            m->linear[i] = linear[i];
            all_finite = all_finite && std::isfinite(linear[i]);
            all_moderate = all_moderate && moderate(linear[i]);
            frob += real(linear[i]) * linear[i];
        }
        frob = std::sqrt(frob);
        m->translation = to_real(t);
        const Model& c = *m->left;
        m->magnitude = frob * c.magnitude + norm(m->translation);
        m->tolerance = frob * (c.tolerance + kRelative * c.magnitude) + 16 * ulp(m->magnitude) + kFloor;
        m->moderate = c.moderate && all_moderate && all_finite;
        if (!null_linear) {
            if (!all_finite) {
                v.require(KAIROS_ERROR_INVALID_ARGUMENT);
            } else {
                const real* l = m->linear;
                const real det = l[0] * (l[4] * l[8] - l[5] * l[7]) - l[1] * (l[3] * l[8] - l[5] * l[6]) +
                                 l[2] * (l[3] * l[7] - l[4] * l[6]);
                const real rows = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]) *
                                  std::sqrt(l[3] * l[3] + l[4] * l[4] + l[5] * l[5]) *
                                  std::sqrt(l[6] * l[6] + l[7] * l[7] + l[8] * l[8]);
                // The library rejects |det| <= 1e-12 of the rows' product; near that line either.
                if (!(rows > 0) || std::fabs(det) < 1e-13L * rows) {
                    if (all_moderate)
                        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
                    else
                        v.unsure();
                } else if (std::fabs(det) <= 1e-11L * rows || !all_moderate) {
                    v.unsure();
                }
            }
        }
        status = observe(fn, [&] { return kairos_shape_transformed(a, null_linear ? nullptr : linear, t, dst); });
    }
    if (m->magnitude > kModerateMax) m->moderate = false;
    if (!m->moderate && !v.expects_error()) v.unsure();
    return finish(fn, status, out, v, m);
}

std::optional<Built> ShapeBuilder::build(int depth) {
    unsigned kind = in_.pick(12);
    if (kind >= 9 && depth >= max_depth_) kind %= 9;
    if (kind <= 6) return primitive(kind);
    if (kind == 7) return convex_hull();
    if (kind == 8) return triangle();
    return composite(kind - 9, depth);
}

Built ShapeBuilder::build_or_sphere() {
    if (std::optional<Built> b = build()) return *b;
    kairos_shape* s = nullptr;
    if (kairos_shape_sphere(1.0, &s) != KAIROS_OK) violation("kairos_shape_sphere(1) failed: %s", kairos_last_error());
    auto m = std::make_shared<Model>();
    m->kind = Kind::Sphere;
    m->a = 1;
    m->magnitude = 1;
    m->tolerance = kRelative;
    return Built{ShapeRef(s), m};
}

}  // namespace kfuzz
