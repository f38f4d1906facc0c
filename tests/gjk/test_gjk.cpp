// SPDX-License-Identifier: MIT
// Tests of the GJK core (src/gjk/gjk.hpp): closed forms, random polytopes against the exact oracle,
// hard cases, and the intersection test with a cached axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include "gjk/gjk.hpp"
#include "gjk_test_support.hpp"

using namespace kairos;
using namespace gjk_test;

namespace {

constexpr double kTol = 1e-10;  // the public default
constexpr double kEps = 2.220446049250313e-16;

Transform at(Vec3 p, Quat q = {}) { return make_transform(p, q); }

void expect_finite(const DistanceResult& r) {
    EXPECT_TRUE(std::isfinite(r.distance));
    EXPECT_TRUE(is_finite(r.point_a));
    EXPECT_TRUE(is_finite(r.point_b));
    EXPECT_TRUE(is_finite(r.axis));
    EXPECT_NEAR(length(r.axis), 1.0, 1e-12);
}

// Closed-form check: distance, closest points consistent, axis from A toward B.
void expect_distance(const DistanceResult& r, double expected, double abs_tol) {
    expect_finite(r);
    EXPECT_NEAR(r.distance, expected, abs_tol + kTol * expected);
    if (expected > 0) {
        EXPECT_FALSE(r.intersecting);
        EXPECT_NEAR(length(r.point_b - r.point_a), r.distance, abs_tol + kTol * expected);
        EXPECT_GT(dot(r.axis, r.point_b - r.point_a), 0);
    }
}

}  // namespace

// ---- Closed forms ------------------------------------------------------------------------------

TEST(GjkClosedForm, SphereSphere) {
    ShapePtr a(new SphereShape(1.0)), b(new SphereShape(0.5));
    std::mt19937_64 rng(11);
    for (int i = 0; i < 200; ++i) {
        const Vec3 ca = 3.0 * random_unit(rng), cb = 3.0 * random_unit(rng);
        const double d = length(cb - ca) - 1.5;
        const DistanceResult r = gjk_distance(*a, at(ca, random_quat(rng)), *b, at(cb, random_quat(rng)), kTol, 256);
        if (d > 1e-9) {
            expect_distance(r, d, 1e-14);
            EXPECT_NEAR(length(r.point_a - ca), 1.0, 1e-12);
            EXPECT_NEAR(length(r.point_b - cb), 0.5, 1e-12);
        } else if (d < -1e-9) {
            EXPECT_TRUE(r.intersecting);
            EXPECT_EQ(r.distance, 0);
            EXPECT_LE(length(r.point_a - ca), 1.0 + 1e-12);
            EXPECT_LE(length(r.point_a - cb), 0.5 + 1e-12);
        }
    }
}

TEST(GjkClosedForm, SphereBox) {
    ShapePtr s(new SphereShape(0.3));
    const Vec3 h{1.0, 0.5, 0.25};
    ShapePtr b = box(h);
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(-2.5, 2.5);
    int separated = 0;
    for (int i = 0; i < 500; ++i) {
        const Quat q = random_quat(rng);
        const Transform pb = at({0.1, -0.2, 0.3}, q);
        const Vec3 local{u(rng), u(rng), u(rng)};
        const Vec3 c = pb.apply(local);
        const Vec3 clamp{std::clamp(local.x, -h.x, h.x), std::clamp(local.y, -h.y, h.y),
                         std::clamp(local.z, -h.z, h.z)};
        const double d = length(local - clamp) - 0.3;
        const DistanceResult r = gjk_distance(*s, at(c), *b, pb, kTol, 256);
        if (d > 1e-9) {
            ++separated;
            expect_distance(r, d, 1e-13);
        } else if (d < -1e-9) {
            EXPECT_TRUE(r.intersecting);
        }
    }
    EXPECT_GT(separated, 200);
}

TEST(GjkClosedForm, CapsuleCapsuleAsSegments) {
    ShapePtr a(new CapsuleShape(0.2, 1.0)), b(new CapsuleShape(0.3, 0.5));
    std::mt19937_64 rng(13);
    int separated = 0, overlapping = 0;
    for (int i = 0; i < 500; ++i) {
        const Transform pa = at(random_unit(rng), random_quat(rng));
        const Transform pb = at(1.2 * random_unit(rng), random_quat(rng));
        const Vec3 a0 = pa.apply({0, 0, -1.0}), a1 = pa.apply({0, 0, 1.0});
        const Vec3 b0 = pb.apply({0, 0, -0.5}), b1 = pb.apply({0, 0, 0.5});
        const double seg =
            std::sqrt(static_cast<double>(oracle::segment_segment_sq(to_p3(a0), to_p3(a1), to_p3(b0), to_p3(b1))));
        const double d = seg - 0.5;
        const DistanceResult r = gjk_distance(*a, pa, *b, pb, kTol, 256);
        if (d > 1e-9) {
            ++separated;
            expect_distance(r, d, 1e-13);
        } else if (d < -1e-9) {
            ++overlapping;
            EXPECT_TRUE(r.intersecting);
            EXPECT_EQ(r.distance, 0);
        }
    }
    EXPECT_GT(separated, 100);
    EXPECT_GT(overlapping, 50);
}

TEST(GjkClosedForm, AxisAlignedBoxes) {
    const Vec3 ha{1, 2, 3}, hb{0.5, 0.25, 2};
    ShapePtr a = box(ha), b = box(hb);
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> u(-6, 6);
    for (int i = 0; i < 500; ++i) {
        const Vec3 c{u(rng), u(rng), u(rng)};
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double g = std::fabs(c[k]) - (ha[k] + hb[k]);
            if (g > 0) d2 += g * g;
        }
        const double d = std::sqrt(d2);
        const DistanceResult r = gjk_distance(*a, at({}), *b, at(c), kTol, 256);
        if (d > 1e-9)
            expect_distance(r, d, 1e-13);
        else
            EXPECT_TRUE(r.intersecting);
    }
    // fcl#508: boxes offset along y or z only (FCL GST_LIBCCD reports 3.162 instead of 3).
    ShapePtr u1 = box({1, 1, 1});
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 c{};
        c[axis] = 5;
        const DistanceResult r = gjk_distance(*u1, at({}), *u1, at(c), kTol, 256);
        expect_distance(r, 3.0, 1e-14);
        EXPECT_EQ(r.termination, Termination::RelativeError);
    }
}

TEST(GjkClosedForm, PointSegmentCylinderCone) {
    ShapePtr p(new PointShape()), seg(new SegmentShape(1.0)), cyl(new CylinderShape(0.5, 1.0)),
        cone(new ConeShape(0.5, 1.0));
    // Point above the cylinder's top face, beside its side, at a rim diagonal.
    expect_distance(gjk_distance(*p, at({0.1, 0.2, 3}), *cyl, at({}), kTol, 256), 2.0, 1e-14);
    expect_distance(gjk_distance(*cyl, at({}), *p, at({3, 0, 0.3}), kTol, 256), 2.5, 1e-14);
    expect_distance(gjk_distance(*cyl, at({}), *p, at({0, 1.5, 2}), kTol, 256), std::sqrt(2.0), 1e-13);
    // Point above the cone's apex, and below its base.
    expect_distance(gjk_distance(*p, at({0, 0, 2.5}), *cone, at({}), kTol, 256), 1.5, 1e-14);
    expect_distance(gjk_distance(*p, at({0.1, 0, -3}), *cone, at({}), kTol, 256), 2.0, 1e-14);
    // Point beside the cone's slanted side: distance to the line through apex (0,0,1) and rim (0.5,0,-1).
    {
        const Vec3 x{2, 0, 0};
        const Vec3 apex{0, 0, 1}, rim{0.5, 0, -1};
        const Vec3 e = (rim - apex) / length(rim - apex);
        const Vec3 off = (x - apex) - dot(x - apex, e) * e;
        expect_distance(gjk_distance(*cone, at({}), *p, at(x), kTol, 256), length(off), 1e-13);
    }
    // Parallel segments: distance between their lines.
    expect_distance(gjk_distance(*seg, at({}), *seg, at({0.3, 0.4, 0.5}), kTol, 256), 0.5, 1e-14);
    // Crossed segments (one turned about x by 90 degrees) 2 apart along y... offset along x.
    const Quat qx = normalized(Quat{std::sin(0.785398163397448), 0, 0, std::cos(0.785398163397448)});
    expect_distance(gjk_distance(*seg, at({}), *seg, at({2, 0, 0}, qx), kTol, 256), 2.0, 1e-14);
}

// ---- Random polytopes against the exact oracle -------------------------------------------------

namespace {

struct Body {
    ShapePtr shape;
    Verts verts;  // local vertices for the oracle
};

Body random_body(std::mt19937_64& rng, int kind) {
    std::uniform_real_distribution<double> ext(0.2, 1.5);
    switch (kind) {
        case 0: {  // box
            const Vec3 h{ext(rng), ext(rng), ext(rng)};
            return {box(h), box_vertices(h)};
        }
        case 1: {  // transformed (sheared, scaled) box
            const Vec3 h{ext(rng), ext(rng), ext(rng)};
            std::uniform_real_distribution<double> m(-0.6, 0.6);
            Mat3 lin;
            for (int i = 0; i < 3; ++i) {
                Vec3 row{m(rng), m(rng), m(rng)};
                row[i] += 1.3;
                lin.r[i] = row;
            }
            const Vec3 tr{m(rng), m(rng), m(rng)};
            ShapePtr child = box(h);
            ShapePtr t(new TransformedShape(*child, lin, tr));
            Verts v;
            for (const auto& c : box_vertices(h)) {
                const Vec3 p = lin * Vec3{c[0], c[1], c[2]} + tr;
                v.push_back({p.x, p.y, p.z});
            }
            return {std::move(t), v};
        }
        default: {  // hull of 8..64 points
            std::uniform_int_distribution<int> n(8, 64);
            const Verts v = random_points(rng, n(rng), {ext(rng), ext(rng), ext(rng)});
            return {hull(v), v};
        }
    }
}

struct RandomStats {
    std::vector<double> rel_errors;
    int separated = 0, intersecting = 0, touching = 0;
};

void run_random_pairs(uint64_t seed, int count, double far, double scale, RandomStats& st) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> gap(0.1, 1.8);
    std::uniform_int_distribution<int> kind(0, 2);
    for (int i = 0; i < count; ++i) {
        SCOPED_TRACE(testing::Message() << "seed " << seed << " pair " << i);
        Body a = random_body(rng, kind(rng)), b = random_body(rng, kind(rng));
        for (auto* body : {&a, &b}) {
            if (scale == 1) continue;
            for (auto& p : body->verts)
                for (double& c : p) c *= scale;
            std::vector<std::array<double, 3>> vs = body->verts;
            body->shape = hull(vs);  // scaled copies as hulls of their (scaled) vertices
        }
        const Vec3 base = far * random_unit(rng);
        const Transform pa = at(base + 0.1 * scale * random_unit(rng), random_quat(rng));
        const double reach = (radius_of(a.verts) + radius_of(b.verts)) * gap(rng);
        const Transform pb = at(pa.translation + reach * random_unit(rng), random_quat(rng));

        const oracle::Polytope oa = world_polytope(a.verts, pa), ob = world_polytope(b.verts, pb);
        const oracle::Result o = oracle::distance(oa, ob);
        const DistanceResult r = gjk_distance(*a.shape, pa, *b.shape, pb, kTol, 256);
        expect_finite(r);
        ASSERT_LE(r.iterations, 256u);

        // Size of the relative configuration, and of the world coordinates (outputs are world).
        const double local_scale = radius_of(a.verts) + radius_of(b.verts) + reach;
        const double world_scale = local_scale + length(pa.translation);
        const double slack = 64 * kEps * local_scale;
        const double od = static_cast<double>(o.distance);
        if (!o.intersecting && od > 1e-9 * local_scale) {
            ++st.separated;
            EXPECT_FALSE(r.intersecting) << "oracle distance " << od;
            EXPECT_LE(std::fabs(r.distance - od), kTol * od + slack) << "oracle " << od << " gjk " << r.distance;
            st.rel_errors.push_back(std::fabs(r.distance - od) / od);
            const double pt_tol = 64 * kEps * world_scale;
            EXPECT_NEAR(length(r.point_b - r.point_a), r.distance, pt_tol + kTol * od);
            EXPECT_LE(static_cast<double>(oracle::plane_excess(oa, to_p3(r.point_a))), pt_tol);
            EXPECT_LE(static_cast<double>(oracle::plane_excess(ob, to_p3(r.point_b))), pt_tol);
            EXPECT_GT(dot(r.axis, r.point_b - r.point_a), 0);
        } else if (o.intersecting && static_cast<double>(o.depth) > 1e-9 * local_scale) {
            ++st.intersecting;
            EXPECT_TRUE(r.intersecting) << "oracle depth " << static_cast<double>(o.depth) << " gjk distance "
                                        << r.distance;
            EXPECT_EQ(r.distance, 0);
            const double pt_tol = 64 * kEps * world_scale;
            EXPECT_LE(static_cast<double>(oracle::plane_excess(oa, to_p3(r.point_a))), pt_tol);
            EXPECT_LE(static_cast<double>(oracle::plane_excess(ob, to_p3(r.point_a))), pt_tol);
        } else {
            ++st.touching;
        }
        // The boolean test agrees, from a cold start and from the distance's axis.
        if (!o.intersecting && od > 1e-9 * local_scale) {
            Vec3 axis{};
            EXPECT_FALSE(gjk_intersect(*a.shape, pa, *b.shape, pb, axis, nullptr));
            Vec3 seeded = r.axis;
            uint32_t it = 0;
            EXPECT_FALSE(gjk_intersect(*a.shape, pa, *b.shape, pb, seeded, &it));
            EXPECT_EQ(it, 1u);
        } else if (o.intersecting && static_cast<double>(o.depth) > 1e-9 * local_scale) {
            Vec3 axis{};
            EXPECT_TRUE(gjk_intersect(*a.shape, pa, *b.shape, pb, axis, nullptr));
        }
    }
}

void report(const char* name, RandomStats& st) {
    std::vector<double>& e = st.rel_errors;
    std::sort(e.begin(), e.end());
    const double med = e.empty() ? 0 : e[e.size() / 2];
    const double mx = e.empty() ? 0 : e.back();
    std::printf(
        "[%s] separated %d intersecting %d touching %d; relative distance error vs oracle: median %.3g max %.3g\n",
        name, st.separated, st.intersecting, st.touching, med, mx);
}

}  // namespace

TEST(GjkRandom, PolytopesAgainstOracle) {
    RandomStats st;
    run_random_pairs(20261122, 1500, 0, 1, st);
    report("unit", st);
    const int n = st.separated + st.intersecting + st.touching;
    // The hit rate stays between bounds, so the test keeps exercising both outcomes.
    EXPECT_GT(st.intersecting, n / 5);
    EXPECT_LT(st.intersecting, 3 * n / 5);
}

TEST(GjkRandom, FarFromOrigin) {
    RandomStats st;
    run_random_pairs(777, 300, 1e6, 1, st);
    report("far 1e6", st);
    EXPECT_GT(st.separated, 60);
    EXPECT_GT(st.intersecting, 60);
}

TEST(GjkRandom, TinyAndHugeScales) {
    for (double scale : {1e-4, 1e4}) {
        RandomStats st;
        run_random_pairs(4242, 150, 0, scale, st);
        report(scale < 1 ? "scale 1e-4" : "scale 1e4", st);
        EXPECT_GT(st.separated, 30);
        EXPECT_GT(st.intersecting, 30);
    }
}

// ---- Hard cases --------------------------------------------------------------------------------

TEST(GjkHard, TouchingFacesAndEdges) {
    ShapePtr b = box({1, 1, 1});
    // Face to face, exactly touching; then offset sideways (face-face partially overlapping).
    for (double side : {0.0, 0.5, 1.3, 1.999}) {
        const DistanceResult r = gjk_distance(*b, at({}), *b, at({2, side, 0}), kTol, 256);
        expect_finite(r);
        EXPECT_LE(r.distance, 1e-15);
        EXPECT_TRUE(r.intersecting);
        Vec3 axis{};
        EXPECT_TRUE(gjk_intersect(*b, at({}), *b, at({2, side, 0}), axis, nullptr));
    }
    // Edge to edge, touching: B turned 45 degrees about z and x... about z only gives edge on face.
    const double s = std::sin(M_PI / 8), c = std::cos(M_PI / 8);
    const Quat qz{0, 0, s, c};
    const DistanceResult r = gjk_distance(*b, at({}), *b, at({1 + std::sqrt(2.0), 0, 0}, qz), kTol, 256);
    expect_finite(r);
    EXPECT_LE(r.distance, 1e-14);
}

TEST(GjkHard, GrazingSeparations) {
    ShapePtr b = box({1, 1, 1});
    const double s = std::sin(M_PI / 8), c = std::cos(M_PI / 8);
    const Quat qz{0, 0, s, c};
    for (double gap : {1e-3, 1e-6, 1e-9, 1e-12}) {
        // Vertical edge of B (turned 45 degrees about z) against A's +x face.
        const DistanceResult r = gjk_distance(*b, at({}), *b, at({1 + std::sqrt(2.0) + gap, 0.3, 0}, qz), kTol, 256);
        expect_finite(r);
        EXPECT_NEAR(r.distance, gap, kTol * gap + 64 * kEps * 4) << gap;
        EXPECT_LE(r.iterations, 64u);
        // Parallel faces with a tiny gap.
        const DistanceResult f = gjk_distance(*b, at({}), *b, at({2 + gap, 0.7, -0.4}), kTol, 256);
        EXPECT_NEAR(f.distance, gap, kTol * gap + 64 * kEps * 4) << gap;
        Vec3 axis{};
        EXPECT_FALSE(gjk_intersect(*b, at({}), *b, at({2 + gap, 0.7, -0.4}), axis, nullptr));
    }
}

TEST(GjkHard, NearlyParallelFaces) {
    ShapePtr b = box({1, 1, 1});
    std::mt19937_64 rng(5);
    for (double angle : {1e-3, 1e-6, 1e-9, 1e-12}) {
        const Vec3 axis = random_unit(rng);
        const Quat q = normalized(Quat{axis.x * std::sin(angle / 2), axis.y * std::sin(angle / 2),
                                       axis.z * std::sin(angle / 2), std::cos(angle / 2)});
        const Transform pb = at({2.5, 0.2, 0.1}, q);
        const oracle::Result o = oracle::distance(world_polytope(box_vertices({1, 1, 1}), at({})),
                                                  world_polytope(box_vertices({1, 1, 1}), pb));
        const DistanceResult r = gjk_distance(*b, at({}), *b, pb, kTol, 256);
        expect_finite(r);
        EXPECT_NEAR(r.distance, static_cast<double>(o.distance), kTol * 0.5 + 64 * kEps * 5) << angle;
    }
}

TEST(GjkHard, NeedlesAndFlatHulls) {
    // Long thin needles (hulls of nearly collinear points) crossing at small distances, and flat
    // slabs (nearly coplanar points) stacked closely: simplices become needles and slivers.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> j(-1, 1);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        SCOPED_TRACE(i);
        Verts needle, slab;
        for (int k = 0; k < 12; ++k) needle.push_back({10 * j(rng), 1e-3 * j(rng), 1e-3 * j(rng)});
        for (int k = 0; k < 16; ++k) slab.push_back({j(rng), j(rng), 1e-4 * j(rng)});
        ShapePtr sn = hull(needle), ss = hull(slab);
        const Transform pa = at({j(rng), j(rng), 0.05 * j(rng)}, random_quat(rng));
        const Transform pb = at({}, {});
        const oracle::Polytope on = world_polytope(needle, pa), os = world_polytope(slab, pb);
        const oracle::Result o = oracle::distance(on, os);
        const DistanceResult r = gjk_distance(*sn, pa, *ss, pb, kTol, 256);
        expect_finite(r);
        EXPECT_LT(r.iterations, 256u);
        const double od = static_cast<double>(o.distance);
        if (!o.intersecting && od > 1e-9) {
            ++checked;
            EXPECT_NEAR(r.distance, od, kTol * od + 64 * kEps * 12);
        } else if (o.intersecting && static_cast<double>(o.depth) > 1e-9) {
            EXPECT_TRUE(r.intersecting);
        }
    }
    EXPECT_GT(checked, 20);
}

TEST(GjkHard, DuplicateAndCoplanarSupportPoints) {
    // A hull whose vertices repeat, with many points on its faces: supports return duplicates.
    Verts v = box_vertices({1, 1, 1});
    const Verts copy = v;
    v.insert(v.end(), copy.begin(), copy.end());
    for (int i = -2; i <= 2; ++i)
        for (int k = -2; k <= 2; ++k) v.push_back({i * 0.5, k * 0.5, 1.0});
    ShapePtr h = hull(v);
    ShapePtr b = box({1, 1, 1});
    for (double dz : {2.0, 2.0 + 1e-9, 2.5, 1.5}) {
        const DistanceResult r = gjk_distance(*h, at({}), *b, at({0.2, -0.1, dz}), kTol, 256);
        expect_finite(r);
        EXPECT_NEAR(r.distance, std::max(0.0, dz - 2.0), 1e-14);
    }
    // The same shape on both sides, same pose: every support point of A - B repeats.
    const DistanceResult r = gjk_distance(*h, at({}), *h, at({}), kTol, 256);
    expect_finite(r);
    EXPECT_TRUE(r.intersecting);
}

TEST(GjkHard, DegenerateShapes) {
    ShapePtr p(new PointShape()), seg(new SegmentShape(1.0)), sph(new SphereShape(1.0));
    // Coincident points, a point on a segment, a point at a sphere's centre.
    DistanceResult r = gjk_distance(*p, at({1, 2, 3}), *p, at({1, 2, 3}), kTol, 256);
    expect_finite(r);
    EXPECT_TRUE(r.intersecting);
    r = gjk_distance(*p, at({0, 0, 0.5}), *seg, at({}), kTol, 256);
    expect_finite(r);
    EXPECT_TRUE(r.intersecting);
    r = gjk_distance(*sph, at({}), *sph, at({}), kTol, 256);
    expect_finite(r);
    EXPECT_TRUE(r.intersecting);
    r = gjk_distance(*p, at({3, 0, 0}), *p, at({}), kTol, 256);
    expect_distance(r, 3, 1e-15);
    // A guard of one iteration ends with MaxIterations and a finite answer (boxes as hulls: two
    // boxes apart have a closed form, which needs no iteration).
    ShapePtr b = hull(box_vertices({1, 1, 1}));
    r = gjk_distance(*b, at({}), *b, at({3, 1, 1}, normalized(Quat{0.1, 0.2, 0.3, 1})), kTol, 1);
    expect_finite(r);
    EXPECT_EQ(r.termination, Termination::MaxIterations);
    EXPECT_EQ(r.iterations, 1u);
}

TEST(GjkHard, GenericCompositesWork) {
    // Shapes outside the fast paths: a Minkowski sum (rounded box), a hull of two shapes, a
    // transformed cylinder; checked against cases with a known answer.
    ShapePtr b = box({1, 1, 1}), s(new SphereShape(0.5)), cyl(new CylinderShape(1, 1));
    ShapePtr rounded(new MinkowskiSumShape(*b, *s));
    expect_distance(gjk_distance(*rounded, at({}), *b, at({4, 0.2, 0.1}), kTol, 256), 1.5, 1e-13);
    ShapePtr two(new HullOfTwoShape(*b, *s));
    expect_distance(gjk_distance(*two, at({}), *two, at({0, 0, 3}), kTol, 256), 1.0, 1e-13);
    Mat3 sc;
    sc.r[0] = {2, 0, 0};
    sc.r[1] = {0, 2, 0};
    sc.r[2] = {0, 0, 0.5};
    ShapePtr tc(new TransformedShape(*cyl, sc, {0, 0, 0}));
    expect_distance(gjk_distance(*tc, at({}), *b, at({0, 0, 2}), kTol, 256), 0.5, 1e-13);
    expect_distance(gjk_distance(*tc, at({}), *b, at({4, 0, 0}), kTol, 256), 1.0, 1e-13);
}

// ---- Termination rules are reported -------------------------------------------------------------

TEST(GjkTermination, ReportedRules) {
    ShapePtr b = box({1, 1, 1});
    ShapePtr sph(new SphereShape(1.0)), cyl(new CylinderShape(1, 1));
    EXPECT_EQ(gjk_distance(*b, at({}), *b, at({0.5, 0.2, 0.1}), kTol, 256).termination, Termination::FullSimplex);
    EXPECT_EQ(gjk_distance(*b, at({}), *b, at({3, 0.2, 0.1}), kTol, 256).termination, Termination::RelativeError);
    // A round shape at a loose tolerance ends on the relative error rule with a few iterations.
    const DistanceResult r =
        gjk_distance(*cyl, at({}), *cyl, at({3, 0.2, 0.1}, normalized(Quat{0.3, 0.1, 0, 1})), 1e-3, 256);
    EXPECT_EQ(r.termination, Termination::RelativeError);
    EXPECT_LT(r.iterations, 20u);
    // At the default tolerance every run ends on a documented rule, never on the guard.
    std::mt19937_64 rng(3);
    int counts[10] = {};
    for (int i = 0; i < 500; ++i) {
        const DistanceResult q =
            gjk_distance(*cyl, at({}), *cyl, at(3.0 * random_unit(rng), random_quat(rng)), kTol, 256);
        counts[static_cast<int>(q.termination)]++;
        EXPECT_NE(q.termination, Termination::MaxIterations);
        EXPECT_NE(q.termination, Termination::None);
    }
    std::printf("cylinder/cylinder terminations:");
    for (int i = 0; i < 10; ++i) std::printf(" %d:%d", i, counts[i]);
    std::printf("\n");
}

// ---- Intersection with a cached axis on a smoothly moving pair ---------------------------------

TEST(GjkIntersect, CachedAxisOnSmoothMotion) {
    // A hull turning in place and a box orbiting it at a radius that swings in and out of contact
    // (about 1 frame in 10 overlapping): the cached axis of one frame should separate the next.
    std::mt19937_64 rng(8);
    const Verts hv = random_points(rng, 32, {1.0, 0.7, 0.5});
    ShapePtr h = hull(hv);
    ShapePtr b = box({0.6, 0.4, 0.8});
    Vec3 axis{};
    uint64_t total = 0, total_sep = 0, total_hit = 0;
    int hits = 0, frames = 4000, checked = 0;
    for (int f = 0; f < frames; ++f) {
        const double t = f * 0.004;
        const Transform pa = at({0, 0, 0}, normalized(Quat{std::sin(0.3 * t), 0.2, 0.1, std::cos(0.3 * t)}));
        const double rad = 2.45 + 0.9 * std::sin(1.7 * t);
        const Transform pb = at({rad * std::cos(t), rad * std::sin(t), 0.3 * std::sin(0.5 * t)},
                                normalized(Quat{0.1, std::sin(0.7 * t), 0.3, std::cos(0.7 * t)}));
        uint32_t it = 0;
        const bool hit = gjk_intersect(*h, pa, *b, pb, axis, &it);
        total += it;
        hits += hit;
        (hit ? total_hit : total_sep) += it;
        const DistanceResult r = gjk_distance(*h, pa, *b, pb, kTol, 256);
        // Away from touching, the two queries agree.
        if (r.distance > 1e-9) {
            EXPECT_FALSE(hit) << f;
            ++checked;
        } else if (r.intersecting) {
            Vec3 fresh{};
            EXPECT_EQ(hit, gjk_intersect(*h, pa, *b, pb, fresh, nullptr)) << f;
        }
    }
    const double mean = double(total) / frames;
    std::printf(
        "cached-axis intersect: mean iterations %.3f over %d frames; separated frames %.3f, "
        "intersecting frames %.3f (%d of them)\n",
        mean, frames, double(total_sep) / (frames - hits), hits ? double(total_hit) / hits : 0.0, hits);
    EXPECT_LE(mean, 1.5);
    EXPECT_GT(hits, frames / 20);
    EXPECT_LT(hits, frames / 4);
    EXPECT_GT(checked, frames / 2);
}

TEST(GjkIntersect, BadCachedAxisIsAFreshStart) {
    ShapePtr b = box({1, 1, 1});
    for (Vec3 bad : {Vec3{0, 0, 0}, Vec3{NAN, 0, 0}, Vec3{INFINITY, 1, 0}, Vec3{1e300, 1e300, 1e300}}) {
        Vec3 axis = bad;
        EXPECT_FALSE(gjk_intersect(*b, at({}), *b, at({3, 0, 0}), axis, nullptr));
        EXPECT_TRUE(is_finite(axis));
        EXPECT_NEAR(length(axis), 1, 1e-12);
        EXPECT_GT(axis.x, 0);  // from A toward B
        Vec3 axis2 = bad;
        EXPECT_TRUE(gjk_intersect(*b, at({}), *b, at({1.5, 0, 0}), axis2, nullptr));
    }
}
