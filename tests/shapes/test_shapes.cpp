// SPDX-License-Identifier: MIT
// Support mappings of every shape kind checked against closed-form support functions and
// sampled points of the shapes; bounds at random poses; sharing shapes between threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "shapes/shape.hpp"

namespace kairos {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr uint64_t kSeed = 20261122;

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

Vec3 random_unit(Rng& rng) {
    for (;;) {
        const Vec3 v{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
        const double n = length(v);
        if (n > 0.1 && n <= 1) return v / n;
    }
}

Mat3 random_rotation(Rng& rng) {
    Quat q{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    return to_matrix(normalized(q));
}

// Input points of the hulls made in these tests: the closed form of a hull's support function
// is the maximum over the points it was built from, not over the vertices it kept.
std::map<const Shape*, std::vector<Vec3>>& hull_inputs() {
    static std::map<const Shape*, std::vector<Vec3>> inputs;
    return inputs;
}

double norm_xy(Vec3 d) { return std::hypot(d.x, d.y); }
double norm3(Vec3 d) { return std::hypot(d.x, d.y, d.z); }

// Closed-form support function h(d) = max over the shape of d.x (docs/algorithms.md section 1).
double h_closed(const Shape& s, Vec3 d) {
    switch (s.kind()) {
        case ShapeKind::Point:
            return 0;
        case ShapeKind::Segment:
            return static_cast<const SegmentShape&>(s).half_length * std::fabs(d.z);
        case ShapeKind::Sphere:
            return static_cast<const SphereShape&>(s).radius * norm3(d);
        case ShapeKind::Box: {
            const Vec3 h = static_cast<const BoxShape&>(s).half_extents;
            return h.x * std::fabs(d.x) + h.y * std::fabs(d.y) + h.z * std::fabs(d.z);
        }
        case ShapeKind::Capsule: {
            const auto& c = static_cast<const CapsuleShape&>(s);
            return c.radius * norm3(d) + c.half_height * std::fabs(d.z);
        }
        case ShapeKind::Cylinder: {
            const auto& c = static_cast<const CylinderShape&>(s);
            return c.radius * norm_xy(d) + c.half_height * std::fabs(d.z);
        }
        case ShapeKind::Cone: {
            const auto& c = static_cast<const ConeShape&>(s);
            return std::max(c.half_height * d.z, c.radius * norm_xy(d) - c.half_height * d.z);
        }
        case ShapeKind::ConvexHull: {
            double best = -std::numeric_limits<double>::infinity();
            for (const Vec3& p : hull_inputs().at(&s)) best = std::max(best, dot(d, p));
            return best;
        }
        case ShapeKind::Transformed: {
            const auto& t = static_cast<const TransformedShape&>(s);
            return h_closed(*t.child, transpose(t.linear) * d) + dot(d, t.translation);
        }
        case ShapeKind::MinkowskiSum: {
            const auto& m = static_cast<const MinkowskiSumShape&>(s);
            return h_closed(*m.a, d) + h_closed(*m.b, d);
        }
        case ShapeKind::HullOfTwo: {
            const auto& m = static_cast<const HullOfTwoShape&>(s);
            return std::max(h_closed(*m.a, d), h_closed(*m.b, d));
        }
        default:  // a kind these tests do not model yet
            break;
    }
    ADD_FAILURE() << "no closed form for shape kind " << int(s.kind());
    return 0;
}

// An upper bound of |x| over the shape, the length scale of its rounding errors.
double radius_bound(const Shape& s) {
    switch (s.kind()) {
        case ShapeKind::Point:
            return 0;
        case ShapeKind::Segment:
            return static_cast<const SegmentShape&>(s).half_length;
        case ShapeKind::Sphere:
            return static_cast<const SphereShape&>(s).radius;
        case ShapeKind::Box:
            return length(static_cast<const BoxShape&>(s).half_extents);
        case ShapeKind::Capsule: {
            const auto& c = static_cast<const CapsuleShape&>(s);
            return c.radius + c.half_height;
        }
        case ShapeKind::Cylinder: {
            const auto& c = static_cast<const CylinderShape&>(s);
            return std::hypot(c.radius, c.half_height);
        }
        case ShapeKind::Cone: {
            const auto& c = static_cast<const ConeShape&>(s);
            return std::hypot(c.radius, c.half_height);
        }
        case ShapeKind::ConvexHull: {
            double r = 0;
            for (const Vec3& p : hull_inputs().at(&s)) r = std::max(r, length(p));
            return r;
        }
        case ShapeKind::Transformed: {
            const auto& t = static_cast<const TransformedShape&>(s);
            const double frobenius =
                std::sqrt(length_sq(t.linear.r[0]) + length_sq(t.linear.r[1]) + length_sq(t.linear.r[2]));
            return frobenius * radius_bound(*t.child) + length(t.translation);
        }
        case ShapeKind::MinkowskiSum: {
            const auto& m = static_cast<const MinkowskiSumShape&>(s);
            return radius_bound(*m.a) + radius_bound(*m.b);
        }
        case ShapeKind::HullOfTwo: {
            const auto& m = static_cast<const HullOfTwoShape&>(s);
            return std::max(radius_bound(*m.a), radius_bound(*m.b));
        }
        default:  // a kind these tests do not model yet
            break;
    }
    ADD_FAILURE() << "no closed form for shape kind " << int(s.kind());
    return 0;
}

// A random point of the shape from its closed-form parametrisation: half the time on the
// boundary (surface, rim, corner), otherwise inside.
Vec3 sample(const Shape& s, Rng& rng) {
    const bool boundary = uniform(rng, 0, 1) < 0.5;
    switch (s.kind()) {
        case ShapeKind::Point:
            return {};
        case ShapeKind::Segment: {
            const double h = static_cast<const SegmentShape&>(s).half_length;
            return {0, 0, boundary ? (uniform(rng, 0, 1) < 0.5 ? -h : h) : uniform(rng, -h, h)};
        }
        case ShapeKind::Sphere: {
            const double r = static_cast<const SphereShape&>(s).radius;
            return r * (boundary ? 1.0 : std::cbrt(uniform(rng, 0, 1))) * random_unit(rng);
        }
        case ShapeKind::Box: {
            const Vec3 h = static_cast<const BoxShape&>(s).half_extents;
            Vec3 x{uniform(rng, -h.x, h.x), uniform(rng, -h.y, h.y), uniform(rng, -h.z, h.z)};
            if (boundary) {
                // A face, an edge or a corner: pin one to three coordinates.
                const int pinned = 1 + static_cast<int>(uniform(rng, 0, 3));
                for (int i = 0; i < pinned; ++i) {
                    const int axis = static_cast<int>(uniform(rng, 0, 3));
                    x[axis] = uniform(rng, 0, 1) < 0.5 ? -h[axis] : h[axis];
                }
            }
            return x;
        }
        case ShapeKind::Capsule: {
            const auto& c = static_cast<const CapsuleShape&>(s);
            const double z = boundary && uniform(rng, 0, 1) < 0.5
                                 ? (uniform(rng, 0, 1) < 0.5 ? -c.half_height : c.half_height)
                                 : uniform(rng, -c.half_height, c.half_height);
            const double radial = boundary ? c.radius : c.radius * std::cbrt(uniform(rng, 0, 1));
            return Vec3{0, 0, z} + radial * random_unit(rng);
        }
        case ShapeKind::Cylinder: {
            const auto& c = static_cast<const CylinderShape&>(s);
            const double angle = uniform(rng, 0, 2 * M_PI);
            const double radial = boundary ? c.radius : c.radius * std::sqrt(uniform(rng, 0, 1));
            const double z = boundary && uniform(rng, 0, 1) < 0.5
                                 ? (uniform(rng, 0, 1) < 0.5 ? -c.half_height : c.half_height)
                                 : uniform(rng, -c.half_height, c.half_height);
            return {radial * std::cos(angle), radial * std::sin(angle), z};
        }
        case ShapeKind::Cone: {
            const auto& c = static_cast<const ConeShape&>(s);
            // At height z the cross-section is a disk of radius r (h - z) / (2 h).
            const double z =
                boundary && uniform(rng, 0, 1) < 0.3 ? -c.half_height : uniform(rng, -c.half_height, c.half_height);
            const double rz = c.radius * (c.half_height - z) / (2 * c.half_height);
            const double angle = uniform(rng, 0, 2 * M_PI);
            const double radial = boundary ? rz : rz * std::sqrt(uniform(rng, 0, 1));
            if (boundary && uniform(rng, 0, 1) < 0.1) return {0, 0, c.half_height};
            return {radial * std::cos(angle), radial * std::sin(angle), z};
        }
        case ShapeKind::ConvexHull: {
            const auto& pts = hull_inputs().at(&s);
            if (boundary) return pts[static_cast<size_t>(uniform(rng, 0, static_cast<double>(pts.size())))];
            // A random convex combination of four input points.
            Vec3 x{};
            double total = 0;
            for (int k = 0; k < 4; ++k) {
                const double w = uniform(rng, 0, 1);
                x += w * pts[static_cast<size_t>(uniform(rng, 0, static_cast<double>(pts.size())))];
                total += w;
            }
            return x / total;
        }
        case ShapeKind::Transformed: {
            const auto& t = static_cast<const TransformedShape&>(s);
            return t.linear * sample(*t.child, rng) + t.translation;
        }
        case ShapeKind::MinkowskiSum: {
            const auto& m = static_cast<const MinkowskiSumShape&>(s);
            return sample(*m.a, rng) + sample(*m.b, rng);
        }
        case ShapeKind::HullOfTwo: {
            const auto& m = static_cast<const HullOfTwoShape&>(s);
            const double u = uniform(rng, 0, 1);
            const double lambda = u < 0.25 ? 0.0 : (u < 0.5 ? 1.0 : uniform(rng, 0, 1));
            return lambda * sample(*m.a, rng) + (1 - lambda) * sample(*m.b, rng);
        }
        default:  // a kind these tests do not model yet
            break;
    }
    ADD_FAILURE() << "no closed form for shape kind " << int(s.kind());
    return {};
}

// Surface checks of primitives: where the support point of a primitive must lie.
void expect_on_primitive(const Shape& s, Vec3 d, Vec3 p, double tol) {
    switch (s.kind()) {
        case ShapeKind::Point:
            EXPECT_EQ(p, Vec3{});
            break;
        case ShapeKind::Segment: {
            const double h = static_cast<const SegmentShape&>(s).half_length;
            EXPECT_EQ(p.x, 0);
            EXPECT_EQ(p.y, 0);
            EXPECT_EQ(std::fabs(p.z), h);
            if (d.z != 0) {
                EXPECT_EQ(p.z, std::copysign(h, d.z));
            }
            break;
        }
        case ShapeKind::Sphere:
            EXPECT_NEAR(length(p), static_cast<const SphereShape&>(s).radius, tol);
            break;
        case ShapeKind::Box: {
            const Vec3 h = static_cast<const BoxShape&>(s).half_extents;
            for (int i = 0; i < 3; ++i) {
                EXPECT_EQ(std::fabs(p[i]), h[i]) << "axis " << i;
                if (d[i] != 0) {
                    EXPECT_EQ(p[i], std::copysign(h[i], d[i])) << "axis " << i;
                }
            }
            break;
        }
        case ShapeKind::Capsule: {
            const auto& c = static_cast<const CapsuleShape&>(s);
            // On the sphere around one end of the core segment, on the side d points to.
            const double end = d.z < 0 ? -c.half_height : c.half_height;
            EXPECT_NEAR(length(p - Vec3{0, 0, end}), c.radius, tol);
            break;
        }
        case ShapeKind::Cylinder: {
            const auto& c = static_cast<const CylinderShape&>(s);
            EXPECT_EQ(std::fabs(p.z), c.half_height);
            if (d.z != 0) {
                EXPECT_EQ(p.z, std::copysign(c.half_height, d.z));
            }
            if (d.x != 0 || d.y != 0) {
                EXPECT_NEAR(norm_xy(p), c.radius, tol);  // on the rim
            } else {
                EXPECT_LE(norm_xy(p), c.radius + tol);  // anywhere on the cap
            }
            break;
        }
        case ShapeKind::Cone: {
            const auto& c = static_cast<const ConeShape&>(s);
            const bool apex = p == Vec3{0, 0, c.half_height};
            const bool rim = p.z == -c.half_height && std::fabs(norm_xy(p) - c.radius) <= tol;
            // Straight down the whole base maximises: any point of the base disk will do.
            const bool base = d.x == 0 && d.y == 0 && d.z < 0 && p.z == -c.half_height && norm_xy(p) <= c.radius + tol;
            EXPECT_TRUE(apex || rim || base) << "p = " << p.x << ", " << p.y << ", " << p.z;
            break;
        }
        case ShapeKind::ConvexHull: {
            const auto& pts = hull_inputs().at(&s);
            EXPECT_NE(std::find(pts.begin(), pts.end(), p), pts.end()) << "not an input point";
            break;
        }
        default:
            break;
    }
}

// p belongs to the convex shape iff e.p <= h(e) for every direction e; checked on many.
void expect_inside(const Shape& s, Vec3 p, double tol, Rng& rng) {
    ASSERT_TRUE(is_finite(p));
    for (int k = 0; k < 64; ++k) {
        Vec3 e = k < 6 ? Vec3{} : random_unit(rng);
        if (k < 6) e[k % 3] = k < 3 ? 1 : -1;
        ASSERT_LE(dot(e, p), h_closed(s, e) + tol) << "outside along " << e.x << ", " << e.y << ", " << e.z;
    }
}

// ---- The shapes under test ------------------------------------------------------------------------

struct Case {
    std::string name;
    const Shape* shape;
};

// Owns the shapes; every composite retains its parts, so dropping our references at the end
// frees everything (LeakSanitizer checks that in the sanitizer build).
class Zoo {
public:
    Zoo() {
        Rng rng(kSeed);
        const Shape* point = keep(new PointShape());
        const Shape* segment = keep(new SegmentShape(1.5));
        const Shape* sphere = keep(new SphereShape(0.7));
        const Shape* box = keep(new BoxShape({0.5, 1.25, 2.0}));
        const Shape* capsule = keep(new CapsuleShape(0.4, 1.1));
        const Shape* capsule0 = keep(new CapsuleShape(0.6, 0.0));
        const Shape* cylinder = keep(new CylinderShape(0.8, 0.6));
        const Shape* cone = keep(new ConeShape(0.9, 1.3));
        std::vector<Vec3> cloud;
        for (int i = 0; i < 60; ++i)
            cloud.push_back(Vec3{uniform(rng, -1, 1), uniform(rng, -2, 2), uniform(rng, -0.5, 0.5)});
        const Shape* hull = keep_hull(cloud);
        std::vector<Vec3> ball;  // > 32 vertices: the hill-climbing support
        for (int i = 0; i < 400; ++i) ball.push_back(1.5 * random_unit(rng));
        const Shape* big_hull = keep_hull(ball);

        const Mat3 rot = random_rotation(rng);
        Mat3 scale;
        scale.r[0] = {2.0, 0, 0};
        scale.r[1] = {0, 0.5, 0};
        scale.r[2] = {0, 0, 1.3};
        Mat3 shear;
        shear.r[0] = {1, 0.7, 0};
        shear.r[2] = {0.3, 0, 1};
        Mat3 mirror;
        mirror.r[2] = {0, 0, -1};
        const Mat3 general = rot * scale * shear * mirror;
        const Vec3 offset{0.3, -1.2, 2.5};

        const Shape* rotated_box = keep(new TransformedShape(*box, rot, offset));
        const Shape* general_cone = keep(new TransformedShape(*cone, general, offset));
        const Shape* general_hull = keep(new TransformedShape(*hull, general, {-1, 0.5, 0}));
        const Shape* mirrored_cylinder = keep(new TransformedShape(*cylinder, mirror * shear, {}));
        const Shape* box_plus_sphere = keep(new MinkowskiSumShape(*box, *sphere));
        const Shape* cone_plus_segment = keep(new MinkowskiSumShape(*cone, *segment));
        const Shape* sphere_or_box = keep(new HullOfTwoShape(*sphere, *rotated_box));
        const Shape* nested_hull = keep(new HullOfTwoShape(*cylinder, *general_cone));
        const Shape* nested_transformed = keep(new TransformedShape(*nested_hull, rot * scale, {1, 2, 3}));
        const Shape* nested = keep(new MinkowskiSumShape(*nested_transformed, *capsule));
        const Shape* nested_outer = keep(new TransformedShape(*nested, shear * mirror, {-2, 0, 1}));
        const Shape* hull_of_hulls = keep(new HullOfTwoShape(*big_hull, *general_hull));

        cases = {{"point", point},
                 {"segment", segment},
                 {"sphere", sphere},
                 {"box", box},
                 {"capsule", capsule},
                 {"capsule_zero_height", capsule0},
                 {"cylinder", cylinder},
                 {"cone", cone},
                 {"convex_hull", hull},
                 {"convex_hull_hill_climb", big_hull},
                 {"transformed_rotation", rotated_box},
                 {"transformed_scale_shear_mirror_cone", general_cone},
                 {"transformed_scale_shear_mirror_hull", general_hull},
                 {"transformed_mirror_shear_cylinder", mirrored_cylinder},
                 {"minkowski_box_sphere", box_plus_sphere},
                 {"minkowski_cone_segment", cone_plus_segment},
                 {"hull_of_two_sphere_box", sphere_or_box},
                 {"hull_of_two_nested", nested_hull},
                 {"transformed_of_hull_of_two", nested_transformed},
                 {"minkowski_nested", nested},
                 {"transformed_of_minkowski_nested", nested_outer},
                 {"hull_of_two_hulls", hull_of_hulls}};
    }
    ~Zoo() {
        for (const Shape* s : owned_) {
            hull_inputs().erase(s);
            s->release();
        }
    }
    std::vector<Case> cases;

private:
    const Shape* keep(const Shape* s) {
        owned_.push_back(s);
        return s;
    }
    const Shape* keep_hull(const std::vector<Vec3>& pts) {
        ConvexHullShape* h = nullptr;
        EXPECT_EQ(make_convex_hull(pts.data(), pts.size(), &h), HullStatus::Ok);
        hull_inputs()[h] = pts;
        return keep(h);
    }
    std::vector<const Shape*> owned_;
};

// Directions: random unit vectors at log-uniform magnitudes, plus axes and directions with zero
// components, where the supports have ties.
std::vector<Vec3> test_directions(Rng& rng, int n) {
    std::vector<Vec3> dirs;
    for (int i = 0; i < 3; ++i) {
        Vec3 e{};
        e[i] = 1;
        dirs.push_back(e);
        dirs.push_back(-e);
        dirs.push_back(3 * e);
    }
    dirs.push_back({1, 1, 0});
    dirs.push_back({0, -1, 1});
    dirs.push_back({-1, 0, -1});
    for (int i = 0; i < n; ++i) dirs.push_back(std::pow(10.0, uniform(rng, -3, 3)) * random_unit(rng));
    return dirs;
}

TEST(ShapeSupport, MatchesClosedFormAndBeatsSampledPoints) {
    Zoo zoo;
    for (const Case& c : zoo.cases) {
        Rng rng(kSeed);
        SCOPED_TRACE("seed " + std::to_string(kSeed) + ", shape " + c.name);
        const double radius = radius_bound(*c.shape);
        std::vector<Vec3> samples;
        for (int i = 0; i < 300; ++i) samples.push_back(sample(*c.shape, rng));
        const std::vector<Vec3> dirs = test_directions(rng, 300);
        for (size_t k = 0; k < dirs.size(); ++k) {
            const Vec3 d = dirs[k];
            SCOPED_TRACE("direction #" + std::to_string(k) + " = (" + std::to_string(d.x) + ", " + std::to_string(d.y) +
                         ", " + std::to_string(d.z) + ")");
            const Vec3 s = support(*c.shape, d);
            const double tol = 16 * kEps * length(d) * (radius + 1);
            ASSERT_TRUE(is_finite(s));
            ASSERT_NEAR(dot(d, s), h_closed(*c.shape, d), tol);
            for (const Vec3& x : samples) ASSERT_GE(dot(d, s), dot(d, x) - tol);
            expect_on_primitive(*c.shape, d, s, 64 * kEps * (radius + 1));
            expect_inside(*c.shape, s, 64 * kEps * (radius + 1), rng);
            if (HasFatalFailure()) return;
        }
    }
}

TEST(ShapeSupport, ZeroTinyAndHugeDirectionsGiveAPointOfTheShape) {
    Zoo zoo;
    for (const Case& c : zoo.cases) {
        Rng rng(kSeed + 1);
        SCOPED_TRACE("seed " + std::to_string(kSeed + 1) + ", shape " + c.name);
        const double tol = 64 * kEps * (radius_bound(*c.shape) + 1);
        {
            SCOPED_TRACE("zero direction");
            const Vec3 s = support(*c.shape, Vec3{});
            expect_inside(*c.shape, s, tol, rng);
        }
        for (int k = 0; k < 50; ++k) {
            const Vec3 u = random_unit(rng);
            for (double magnitude : {1e-300, 1e300}) {
                SCOPED_TRACE("direction " + std::to_string(k) + " scaled by " + std::to_string(std::log10(magnitude)));
                const Vec3 s = support(*c.shape, magnitude * u);
                expect_inside(*c.shape, s, tol, rng);
                // Still a maximiser: scaling the direction does not change the answer.
                EXPECT_GE(dot(u, s), h_closed(*c.shape, u) - 1e-9 * (radius_bound(*c.shape) + 1));
            }
            if (HasFatalFailure()) return;
        }
    }
}

// A huge direction through a large linear part must not overflow to inf (and a NaN point), nor
// a tiny one through a small linear part underflow to the zero direction.
TEST(ShapeSupport, ExtremeDirectionsThroughLargeAndSmallTransforms) {
    const Shape* sphere = new SphereShape(1.0);
    const Shape* box = new BoxShape({1, 2, 3});
    Rng rng(kSeed + 5);
    for (double scale : {1e12, 1e-12}) {
        Mat3 linear = random_rotation(rng);
        for (auto& row : linear.r) row = scale * row;
        for (const Shape* child : {sphere, box}) {
            const Shape* t = new TransformedShape(*child, linear, {1, 2, 3});
            for (int k = 0; k < 50; ++k) {
                const Vec3 u = random_unit(rng);
                for (double magnitude : {1e-300, 1.0, 1e300}) {
                    SCOPED_TRACE("seed " + std::to_string(kSeed + 5) + ", linear scale " +
                                 std::to_string(std::log10(scale)) + ", direction " + std::to_string(k) + " times 1e" +
                                 std::to_string(std::log10(magnitude)));
                    const Vec3 s = support(*t, magnitude * u);
                    ASSERT_TRUE(is_finite(s));
                    const double tol = 64 * kEps * (radius_bound(*t) + 1);
                    ASSERT_NEAR(dot(u, s), h_closed(*t, u), tol);
                }
            }
            t->release();
        }
    }
    sphere->release();
    box->release();
}

TEST(ShapeSupport, WorldSupportAppliesThePose) {
    Zoo zoo;
    Rng rng(kSeed + 2);
    for (const Case& c : zoo.cases) {
        SCOPED_TRACE("seed " + std::to_string(kSeed + 2) + ", shape " + c.name);
        for (int k = 0; k < 20; ++k) {
            const Transform pose{random_rotation(rng), {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)}};
            const Vec3 d = random_unit(rng);
            const Vec3 s = support(*c.shape, pose, d);
            const double expected = h_closed(*c.shape, transpose(pose.rotation) * d) + dot(d, pose.translation);
            ASSERT_NEAR(dot(d, s), expected, 64 * kEps * (radius_bound(*c.shape) + 10));
        }
    }
}

// ---- Bounds -----------------------------------------------------------------------------------------

TEST(ShapeBounds, ClosedFormContainsSamplesAndTight) {
    Zoo zoo;
    for (const Case& c : zoo.cases) {
        Rng rng(kSeed + 3);
        SCOPED_TRACE("seed " + std::to_string(kSeed + 3) + ", shape " + c.name);
        const double tol = 64 * kEps * (radius_bound(*c.shape) + 10);
        for (int k = 0; k < 30; ++k) {
            SCOPED_TRACE("pose " + std::to_string(k));
            const Transform pose{random_rotation(rng), {uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)}};
            Vec3 lo, hi;
            bounds(*c.shape, pose, lo, hi);
            for (int i = 0; i < 3; ++i) {
                // The extent along world axis e_i is h(R^T e_i) + t_i; R^T e_i is row i of R.
                const Vec3 local = pose.rotation.r[i];
                EXPECT_NEAR(hi[i], h_closed(*c.shape, local) + pose.translation[i], tol) << "axis " << i;
                EXPECT_NEAR(lo[i], -h_closed(*c.shape, -local) + pose.translation[i], tol) << "axis " << i;
                // Tight: the support point along each face normal touches that face.
                Vec3 e{};
                e[i] = 1;
                const Vec3 top = support(*c.shape, pose, e), bottom = support(*c.shape, pose, -e);
                EXPECT_EQ(top[i], hi[i]);
                EXPECT_EQ(bottom[i], lo[i]);
                for (int j = 0; j < 3; ++j) {
                    EXPECT_GE(top[j], lo[j] - tol);
                    EXPECT_LE(top[j], hi[j] + tol);
                }
            }
            if (c.shape->kind() == ShapeKind::Sphere) {
                const double r = static_cast<const SphereShape*>(c.shape)->radius;
                for (int i = 0; i < 3; ++i) {
                    EXPECT_NEAR(hi[i], pose.translation[i] + r, tol);
                    EXPECT_NEAR(lo[i], pose.translation[i] - r, tol);
                }
            }
            if (c.shape->kind() == ShapeKind::Box) {
                const Vec3 h = static_cast<const BoxShape*>(c.shape)->half_extents;
                for (int i = 0; i < 3; ++i) {
                    double half = 0;
                    for (int j = 0; j < 3; ++j) half += std::fabs(pose.rotation.r[i][j]) * h[j];
                    EXPECT_NEAR(hi[i], pose.translation[i] + half, tol);
                    EXPECT_NEAR(lo[i], pose.translation[i] - half, tol);
                }
            }
            for (int n = 0; n < 100; ++n) {
                const Vec3 x = pose.apply(sample(*c.shape, rng));
                for (int i = 0; i < 3; ++i) {
                    ASSERT_GE(x[i], lo[i] - tol);
                    ASSERT_LE(x[i], hi[i] + tol);
                }
            }
        }
    }
}

// ---- Threads ----------------------------------------------------------------------------------------

TEST(ShapeThreads, ConcurrentSupportQueriesAgree) {
    Zoo zoo;
    Rng rng(kSeed + 4);
    const std::vector<Vec3> dirs = test_directions(rng, 2000);
    for (const Case& c : zoo.cases) {
        SCOPED_TRACE(c.name);
        std::vector<Vec3> expected;
        for (const Vec3& d : dirs) expected.push_back(support(*c.shape, d));
        std::vector<std::vector<Vec3>> got(4);
        std::vector<std::thread> threads;
        for (auto& out : got)
            threads.emplace_back([&, shape = c.shape, out_ptr = &out] {
                for (int rep = 0; rep < 3; ++rep) {
                    out_ptr->clear();
                    for (const Vec3& d : dirs) out_ptr->push_back(support(*shape, d));
                }
            });
        for (auto& t : threads) t.join();
        for (const auto& out : got) ASSERT_TRUE(out == expected);
    }
}

TEST(ShapeThreads, RetainReleaseFromManyThreads) {
    const Shape* sphere = new SphereShape(1.0);
    const Shape* box = new BoxShape({1, 2, 3});
    const Shape* sum = new MinkowskiSumShape(*sphere, *box);
    EXPECT_EQ(sphere->reference_count(), 2u);
    EXPECT_EQ(box->reference_count(), 2u);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&] {
            std::vector<const Shape*> made;
            for (int i = 0; i < 2000; ++i) {
                sphere->retain();
                made.push_back(new TransformedShape(*sum, Mat3::identity(), {1, 0, 0}));
                made.push_back(new HullOfTwoShape(*sphere, *box));
            }
            for (const Shape* s : made) s->release();
            for (int i = 0; i < 2000; ++i) sphere->release();
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(sphere->reference_count(), 2u);
    EXPECT_EQ(box->reference_count(), 2u);
    EXPECT_EQ(sum->reference_count(), 1u);
    sum->release();  // frees the sum and drops its references to the parts
    EXPECT_EQ(sphere->reference_count(), 1u);
    EXPECT_EQ(box->reference_count(), 1u);
    sphere->release();
    box->release();
}

}  // namespace
}  // namespace kairos
