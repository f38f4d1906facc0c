// SPDX-License-Identifier: MIT
// Casts through degenerate shapes, whatever ends their loops: boxes, cylinders, cones and capsules
// flat or needle-thin (thickness 1e-9 to 1e-1 of the size), needle and flat hulls, turned, scaled
// from 1e-3 to 1e3 and placed up to 1e4 sizes from the origin. The truth comes by construction and
// from supports written apart from the library (peer::world_support):
// - a ray (and a point or a small box moving the same way, both orders) that passes an interior
//   point at time t must hit no later than t;
// - at toi the plane of the reported normal still holds the ray point (or B) on its side;
// - the ray cast's point is the ray point, a shape cast's point lies in both shapes;
// - a ray gliding parallel to a support plane of the shape, g above it (g from 1e-8 of the size
//   on polytopes, 1e-6 on curved shapes, up to 1e-3), must miss.
// Slack: (2 tolerance + 1e-6) of the size (the fuzz target's, within the points' accuracy range,
// aspect up to 1e5) plus the positions' rounding far from the origin. A stress run of this kind
// found the two ray-cast faults that RayCastGraze's needle tests keep; this test is the net.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "cast_test_support.hpp"
#include "casts/cast.hpp"
#include "gjk_peer_shapes.hpp"
#include "shapes/shape.hpp"

using namespace kairos;

namespace {

constexpr uint32_t kMaxIt = 256;

struct Degenerate {
    peer::Spec spec;
    gjk_test::ShapePtr shape;
    Vec3 inside_local;    // an interior point, local frame
    double size = 0;      // bounding radius
    double thinnest = 0;  // the smallest dimension
    bool curved = false;
};

// Thin: the smallest dimension over the largest, 1e-9 .. 1e-1 (hulls no thinner: within 1e-10 of
// a plane the builder makes them flat, with no interior to pass).
Degenerate make_degenerate(std::mt19937_64& rng, int trial) {
    std::uniform_real_distribution<double> u(0, 1);
    const double thin = std::pow(10.0, -9 + 8 * u(rng)), scale = std::pow(10.0, -3 + 6 * u(rng));
    const bool flat = (trial / 18) % 2 == 0;  // independent of the kind and the tolerance
    auto around = [&](double r) { return r * (2 * u(rng) - 1); };
    Degenerate d;
    peer::Spec& s = d.spec;
    switch (trial % 6) {
        case 0: {
            s.kind = peer::Kind::Box;
            s.a = scale * (0.3 + u(rng));
            s.b = flat ? scale * (0.3 + u(rng)) : thin * scale;
            s.c = thin * scale;
            d.inside_local = {around(0.9 * s.a), around(0.9 * s.b), around(0.9 * s.c)};
            d.thinnest = std::fmin(s.a, std::fmin(s.b, s.c));
            break;
        }
        case 1:
        case 2: {
            s.kind = trial % 6 == 1 ? peer::Kind::Cylinder : peer::Kind::Cone;
            s.a = flat ? scale : thin * scale;
            s.b = flat ? thin * scale : scale;
            const double z = around(0.9 * s.b);
            const double radius = s.kind == peer::Kind::Cylinder ? s.a : s.a * (s.b - z) / (2 * s.b);
            const double f = 0.8 * u(rng), phi = 6.283185307179586 * u(rng);
            d.inside_local = {f * radius * std::cos(phi), f * radius * std::sin(phi), z};
            d.thinnest = std::fmin(s.a, s.b);
            d.curved = true;
            break;
        }
        case 3: {
            s.kind = peer::Kind::Capsule;
            s.a = thin * scale;
            s.b = scale;
            const double f = 0.8 * u(rng), phi = 6.283185307179586 * u(rng);
            d.inside_local = {f * s.a * std::cos(phi), f * s.a * std::sin(phi), around(s.b)};
            d.thinnest = s.a;
            d.curved = true;
            break;
        }
        default: {
            s.kind = peer::Kind::Hull;
            const double t = std::fmax(thin, 1e-9);
            const Vec3 e1 = gjk_test::random_unit(rng);
            const Vec3 e2 = normalized_or(cross(e1, gjk_test::random_unit(rng)), Vec3{0, 0, 1});
            const Vec3 e3 = cross(e1, e2);
            const int count = 5 + trial % 9;
            Vec3 sum{};
            double total = 0;
            for (int k = 0; k < count; ++k) {
                const Vec3 p =
                    around(scale) * e1 + (flat ? around(scale) : around(t * scale)) * e2 + around(t * scale) * e3;
                s.verts.push_back({p.x, p.y, p.z});
                const double w = 0.2 + u(rng);
                sum = sum + w * p;
                total += w;
            }
            d.inside_local = (1 / total) * sum;
            d.thinnest = t * scale;
            break;
        }
    }
    d.shape = peer::make_kairos(s);
    d.size = peer::extent(s);
    return d;
}

// The 26 unit directions toward a cube's faces, edges and corners.
const std::vector<Vec3>& cube_directions() {
    static const std::vector<Vec3> dirs = [] {
        std::vector<Vec3> v;
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z)
                    if (x != 0 || y != 0 || z != 0)
                        v.push_back(normalized_or(Vec3{double(x), double(y), double(z)}, {}));
        return v;
    }();
    return dirs;
}

// The support value of the placed shape along world direction n.
double h(const peer::Spec& s, Vec3 n) { return dot(n, peer::world_support(s, n)); }

struct Tally {
    int casts = 0, bad = 0;
    double worst_plane = 0, worst_point = 0;
    void fail(uint64_t seed, int trial, const char* what, const char* how, double value, const CastResult& r) {
        if (++bad <= 12)
            ADD_FAILURE() << "seed " << seed << " trial " << trial << " " << what << ": " << how << " " << value
                          << " (hit " << r.hit << " toi " << r.toi << " termination " << int(r.termination) << ")";
    }
};

}  // namespace

TEST(CastDegenerate, ThroughAndBesideThinShapesTheContractHolds) {
    const uint64_t seed = 7401;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double tolerances[3] = {1e-10, 1e-6, 1e-3};
    Tally t;
    int grazes = 0, rounding_stops = 0;
    const PointShape point;
    for (int trial = 0; trial < 3000; ++trial) {
        Degenerate d = make_degenerate(rng, trial);
        const double far = trial % 4 == 1 ? d.size * std::pow(10.0, 1 + 3 * u(rng)) : 0;
        const Vec3 offset = far * gjk_test::random_unit(rng);
        const Quat turn = gjk_test::random_quat(rng);
        d.spec.pose = make_transform(offset, turn);
        const peer::Spec& s = d.spec;
        const double tol = tolerances[(trial / 6) % 3];  // every kind at every tolerance
        // The positions' rounding far from the origin, relative to the size below.
        const double placement = 64 * 2.2e-16 * (far + 4 * d.size);

        // Through an interior point, reached at toi_through.
        const Vec3 through = s.pose.apply(d.inside_local);
        const Vec3 dir = gjk_test::random_unit(rng);
        const double reach = d.size * (0.5 + 2 * u(rng)), toi_through = 0.3 + 0.7 * u(rng);
        const Vec3 from = through + reach * dir, motion = (-reach / toi_through) * dir;
        const double size = 2 * d.size + reach, slack = (2 * tol + 1e-6) * size + placement;
        // B: a point, or a box 1e-2 .. 1 of the shape's size centred on the ray point.
        peer::Spec box;
        box.kind = peer::Kind::Box;
        const double bs = d.size * std::pow(10.0, -2 + 2 * u(rng));
        box.a = bs * (0.1 + u(rng)), box.b = bs * (0.1 + u(rng)), box.c = bs * (0.1 + u(rng));
        const gjk_test::ShapePtr box_shape = peer::make_kairos(box);
        const Quat box_turn = gjk_test::random_quat(rng);
        // The interior point is inside by more than the positions' rounding; the points' accuracy
        // holds up to an aspect of 1e5 (the header), the planes' at any.
        const bool deep = far == 0 || d.thinnest > 1e3 * placement;
        const bool points_checked = d.thinnest >= 1e-5 * d.size;
        for (int which = 0; which < 5; ++which) {
            const char* what[] = {"ray", "shape, point", "point, shape", "shape, box", "box, shape"};
            const Transform at_from = make_transform(from, which >= 3 ? box_turn : Quat{});
            const Shape& mover = which >= 3 ? static_cast<const Shape&>(*box_shape) : static_cast<const Shape&>(point);
            CastResult r;
            double sign = 1;
            if (which == 0) {
                r = ray_cast(*d.shape, s.pose, from, motion, tol, kMaxIt);
            } else if (which % 2 == 1) {
                r = shape_cast(*d.shape, s.pose, {}, mover, at_from, motion, tol, kMaxIt);
            } else {
                r = shape_cast(mover, at_from, motion, *d.shape, s.pose, {}, tol, kMaxIt);
                sign = -1;
            }
            ++t.casts;
            if (cast_test::rounding_stop(r.termination)) ++rounding_stops;
            if (!deep) continue;
            if (!r.hit) {
                t.fail(seed, trial, what[which], "missed, passing the inside at", toi_through, r);
                continue;
            }
            if (r.toi > toi_through + 1e-9 + tol) t.fail(seed, trial, what[which], "late, inside at", toi_through, r);
            if (!(r.toi > 0)) continue;
            const Vec3 x = from + r.toi * motion;
            const Vec3 n = sign * r.normal;
            box.pose = make_transform(x, box_turn);
            // The mover's side of the plane: the ray point, or B's lowest point along n.
            const double low = which >= 3 ? -h(box, -1 * n) : dot(n, x);
            const double behind = h(s, n) - low;
            t.worst_plane = std::fmax(t.worst_plane, behind / size);
            if (!(behind <= slack))
                t.fail(seed, trial, what[which], "behind the normal's plane by", behind / size, r);
            double off = 0;
            if (which == 0) {
                off = length(r.point - x);
            } else {
                for (const Vec3& e : cube_directions()) {
                    off = std::fmax(off, dot(e, r.point) - h(s, e));
                    off = std::fmax(off, dot(e, r.point) - (which >= 3 ? h(box, e) : dot(e, x)));
                }
            }
            if (!points_checked) continue;
            t.worst_point = std::fmax(t.worst_point, off / size);
            if (!(off <= slack)) t.fail(seed, trial, what[which], "point off by", off / size, r);
        }

        // Gliding over a support plane of direction m, g above it: separated all along.
        const Vec3 m = gjk_test::random_unit(rng);
        Vec3 along = gjk_test::random_unit(rng);
        along = along - dot(along, m) * m;
        if (!(length(along) > 0.1)) continue;
        along = normalized_or(along, Vec3{});
        const double g = d.size * std::pow(10.0, (d.curved ? -6 : -8) + (d.curved ? 3 : 5) * u(rng));
        if (!(g > 4 * tol * 4 * d.size + placement)) continue;  // within the tolerance a hit is allowed
        const Vec3 start = peer::world_support(s, m) + g * m - 2 * d.size * along;
        const Vec3 glide = 4 * d.size * along;
        if (!(dot(m, start) - h(s, m) > 0.5 * g && dot(m, start + glide) - h(s, m) > 0.5 * g)) continue;
        const Transform at_start = make_transform(start, Quat{});
        const CastResult g0 = ray_cast(*d.shape, s.pose, start, glide, tol, kMaxIt);
        const CastResult g1 = shape_cast(*d.shape, s.pose, {}, point, at_start, glide, tol, kMaxIt);
        const CastResult g2 = shape_cast(point, at_start, glide, *d.shape, s.pose, {}, tol, kMaxIt);
        grazes += 3;
        if (g0.hit) t.fail(seed, trial, "ray graze", "false hit at gap", g / d.size, g0);
        if (g1.hit) t.fail(seed, trial, "shape, point graze", "false hit at gap", g / d.size, g1);
        if (g2.hit) t.fail(seed, trial, "point, shape graze", "false hit at gap", g / d.size, g2);
    }
    std::printf(
        "degenerate shapes: %d casts (%d ended on a rounding rule), %d grazes; worst plane %.3g, point %.3g of "
        "the size\n",
        t.casts, rounding_stops, grazes, t.worst_plane, t.worst_point);
    EXPECT_EQ(t.bad, 0);
    EXPECT_EQ(t.casts, 15000);
    // The cases reach the loops' rounding stops, and most grazes are run.
    EXPECT_GT(rounding_stops, 50);
    EXPECT_LT(rounding_stops, 5000);
    EXPECT_GT(grazes, 3000);
}
