// SPDX-License-Identifier: MIT
// Cylinders, cones and capsules with parallel axes overlapping, plain or rounded by balls:
// coaxial (coincident or shifted along the common axis) or with the axes from 1e-12 of the size to
// most of the radii apart, the second turned about its axis or reversed. The signed distance
// against the depth of their axial sections: A - B is then a body of revolution whose section is
// the sum of theirs, so the depth is that of a polygon, computed here from the Minkowski difference
// of their sections' vertices, hulled by brute force, in long double. The expansion approached the
// circle where coaxial sides meet to 6e-4 of the depth in 254 support calls (coaxial_depth,
// penetration.cpp). Sizes 1e-3 to 1e3, up to 1e4 sizes from the origin, both argument orders.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "../support/gjk_test_support.hpp"
#include "gjk/penetration.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using gjk_test::random_quat;
using gjk_test::random_unit;

namespace {

using Real = long double;
struct P2 {
    Real x, z;
};

// A core's axial section (x across the axis, z along it; symmetric in x).
std::vector<P2> section(int kind, double r, double h) {
    switch (kind) {
        case 0:  // cylinder
            return {{-r, -h}, {r, -h}, {r, h}, {-r, h}};
        case 1:  // cone, apex at +h
            return {{-r, -h}, {r, -h}, {0, h}};
        default:  // segment (a capsule's core)
            return {{0, -h}, {0, h}};
    }
}

// The depth of the origin inside the convex hull of pts (> 0 inside), and the hull's support
// function: the least over the hull's edges of the origin's distance to the edge's line.
struct Hull2 {
    std::vector<P2> pts;
    Real support(Real ux, Real uz) const {
        Real best = -INFINITY;
        for (const P2& p : pts) best = std::max(best, ux * p.x + uz * p.z);
        return best;
    }
    Real depth() const {
        Real best = INFINITY;
        const size_t n = pts.size();
        for (size_t i = 0; i < n; ++i)
            for (size_t j = 0; j < n; ++j) {
                if (i == j) continue;
                const Real ex = pts[j].x - pts[i].x, ez = pts[j].z - pts[i].z;
                const Real len = std::sqrt(ex * ex + ez * ez);
                if (!(len > 0)) continue;
                const Real nx = ez / len, nz = -ex / len;  // one side's normal
                const Real c = nx * pts[i].x + nz * pts[i].z;
                bool edge = true;
                for (const P2& p : pts) edge = edge && nx * p.x + nz * p.z <= c + 1e-15L * (std::fabs(c) + len);
                if (edge) best = std::min(best, c);  // the origin's distance to the supporting line
            }
        return best;
    }
};

// A core (kind 0 cylinder, 1 cone, 2 segment: a capsule's core) of radius r and half height h,
// rounded by a ball of radius pad when pad > 0.
struct Axial {
    Axial(int kind, double r, double h, double pad)
        : core(kind == 0   ? gjk_test::ShapePtr(new CylinderShape(r, h))
               : kind == 1 ? gjk_test::ShapePtr(new ConeShape(r, h))
                           : gjk_test::ShapePtr(new SegmentShape(h))),
          ball(pad),
          rounded(*core, ball) {}
    const Shape& shape() const { return ball.radius > 0 ? static_cast<const Shape&>(rounded) : *core; }
    gjk_test::ShapePtr core;
    SphereShape ball;
    MinkowskiSumShape rounded;
};

// How far a world point lies from the surface of a core (kind, r, h) at `pose` grown by `pad`:
// its distance, in the axial half-plane through it, to the section's boundary, less pad.
double off_surface(Vec3 world, const Transform& pose, int kind, double r, double h, double pad) {
    const Vec3 q = pose.apply_inverse(world);
    const Real px = std::hypot(Real(q.x), Real(q.y)), pz = q.z;
    const std::vector<P2> v = section(kind, r, h);
    Real best = INFINITY;
    for (size_t i = 0; i < v.size(); ++i) {
        const P2 a = v[i], b = v[(i + 1) % v.size()];
        const Real ex = b.x - a.x, ez = b.z - a.z, len_sq = ex * ex + ez * ez;
        Real s = len_sq > 0 ? ((px - a.x) * ex + (pz - a.z) * ez) / len_sq : 0;
        s = std::clamp(s, Real(0), Real(1));
        best = std::min(best, std::hypot(px - (a.x + s * ex), pz - (a.z + s * ez)));
    }
    return double(std::fabs(best - Real(pad)));
}

}  // namespace

TEST(CoaxialDepth, CylindersConesAndCapsulesAboutOneAxis) {
    const uint64_t seed = 5001;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const char* names[] = {"cylinder", "cone", "capsule"};
    int cases = 0, failures = 0, coincident = 0, apart = 0, offset = 0;
    double worst = 0;
    for (const double size : {1e-3, 1.0, 1e3})
        for (const double far : {0.0, 1e4})
            for (int i = 0; i < 600; ++i) {
                // Kinds of A and B (not two capsules: their cores have a closed form of their own).
                const bool same = i % 3 == 0;  // copies of one shape
                int ka = static_cast<int>(3 * u(rng)), kb = same ? ka : static_cast<int>(3 * u(rng));
                if (ka == 2 && kb == 2) kb = i % 2;
                const double ra = size * (0.2 + u(rng)), ha = size * (0.2 + u(rng));
                const double rb = same ? ra : size * (0.2 + u(rng)), hb = same ? ha : size * (0.2 + u(rng));
                // Rounding radii: capsules always, the others in half of the cases.
                const double pad_a = ka == 2 ? 0.5 * ra : (i % 2 ? 0.1 * size * u(rng) : 0.0);
                const double pad_b = kb == 2 ? 0.5 * rb : (i % 4 < 2 ? 0.1 * size * u(rng) : 0.0);
                const bool flip = i % 5 == 1;
                // Centred together (copies or not), shifted, or ends overlapping by 1e-6 of the length.
                const double side = u(rng) < 0.5 ? -1.0 : 1.0;
                const double dz = i % 7 == 3                           ? side * (ha + hb) * (1 - 1e-6)
                                  : (same && i % 2 == 0) || i % 7 == 5 ? 0.0
                                                                       : 0.95 * (ha + hb) * (2 * u(rng) - 1);
                // B's axis across A's by `off` in a third of the cases (parallel axes): from a rounding
                // of the size to most of the radii.
                const double off_scale = i % 3 == 2 ? std::array{1e-12, 1e-6, 1e-3, 0.3, 0.9}[i % 5] : 0.0;
                const double off = off_scale * std::min(ra + rb, 2 * size) * (0.5 + 0.5 * u(rng));
                const double phi = 6.283185307179586 * u(rng);
                const Vec3 across{off * std::cos(phi), off * std::sin(phi), 0};
                if (same && ka == kb && dz == 0 && !flip && off == 0) ++coincident;

                const Axial shape_a(ka, ra, ha, pad_a), shape_b(kb, rb, hb, pad_b);
                const Shape &a = shape_a.shape(), &b = shape_b.shape();

                // A's frame at random; B's: A's, reversed or not, turned about the axis, dz along it.
                const Quat qa = random_quat(rng);
                const Transform pa = make_transform(far * size * random_unit(rng), qa);
                const Quat qb = qa * axis_angle({1, 0, 0}, flip ? 3.141592653589793 : 0.0) *
                                axis_angle({0, 0, 1}, 6.283185307179586 * u(rng));
                const Transform pb = make_transform(pa.apply(across + Vec3{0, 0, dz}), qb);

                // Truth: A - B is a body of revolution about the axis through the offset, whose
                // section is the sections' Minkowski difference (B's reversed with it and at dz): m
                // about its own axis, and `placed` in the plane through both axes, where the origin
                // lies `off` from it (x toward B's axis).
                Hull2 m, placed;
                for (const P2& p : section(ka, ra, ha))
                    for (const P2& q : section(kb, rb, hb))
                        for (const double mirror : {1.0, -1.0}) {
                            const P2 d{p.x - mirror * q.x, p.z - ((flip ? -q.z : q.z) + Real(dz))};
                            m.pts.push_back(d);
                            placed.pts.push_back({d.x - Real(off), d.z});
                        }
                const Real core_depth = placed.depth();
                if (!(core_depth > 0)) {  // offset clear of a cone's slant or a segment's end
                    ASSERT_GT(off, 0) << "coaxial drawings overlap along the axis; case " << i << " seed " << seed;
                    ++apart;
                    continue;
                }
                const double truth = -double(core_depth + Real(pad_a) + Real(pad_b));
                const double coords = max_abs(pa.translation) + max_abs(pb.translation);
                const double tol = 1e-12 * size + 1e-14 * coords;
                ++cases;
                if (off > 0) ++offset;
                auto fail = [&](const char* rule, double got, double want) {
                    if (++failures <= 10)
                        ADD_FAILURE() << names[ka] << "/" << names[kb] << " " << rule << ": got " << got << ", want "
                                      << want << " (dz " << dz << ", off " << off << ", flip " << flip << ", pads "
                                      << pad_a << " " << pad_b << "); size " << size << " far " << far << " case " << i
                                      << " seed " << seed;
                };
                for (int order = 0; order < 2; ++order) {
                    const Shape& x = order == 0 ? a : b;
                    const Shape& y = order == 0 ? b : a;
                    const Transform& px = order == 0 ? pa : pb;
                    const Transform& py = order == 0 ? pb : pa;
                    const DistanceResult s = signed_distance(x, px, y, py, 1e-10, 256);
                    const double err = std::fabs(s.distance - truth);
                    worst = std::max(worst, err / size);
                    if (!(err <= tol)) fail("signed distance", s.distance, truth);
                    if (!(std::fabs(length(s.axis) - 1) <= 1e-12)) fail("axis length", length(s.axis), 1);
                    // The axis achieves the depth: the sections' translation along it (in A's frame,
                    // its part across the axis turned into the half-plane, the sign toward B) is it.
                    const Vec3 n = pa.to_local_direction(order == 0 ? s.axis : -1.0 * s.axis);
                    const Real along = m.support(std::hypot(Real(n.x), Real(n.y)), n.z) -
                                       (Real(n.x) * across.x + Real(n.y) * across.y);
                    if (!(along - core_depth <= tol)) fail("depth along the axis", double(along), double(core_depth));
                    if (s.iterations > 64) fail("support calls", s.iterations, 64);
                    // The deepest points: point_b - point_a = distance * axis, each on its shape's
                    // surface (its section's boundary, at its radius).
                    const Vec3 gap = (s.point_b - s.point_a) - s.distance * s.axis;
                    if (!(length(gap) <= tol)) fail("point_b - point_a - distance * axis", length(gap), 0);
                    const double on_a = order == 0 ? off_surface(s.point_a, px, ka, ra, ha, pad_a)
                                                   : off_surface(s.point_b, py, ka, ra, ha, pad_a);
                    const double on_b = order == 0 ? off_surface(s.point_b, py, kb, rb, hb, pad_b)
                                                   : off_surface(s.point_a, px, kb, rb, hb, pad_b);
                    if (!(on_a <= tol)) fail("A's deepest point off its surface by", on_a, 0);
                    if (!(on_b <= tol)) fail("B's deepest point off its surface by", on_b, 0);
                }
            }
    std::printf(
        "shapes with parallel axes: %d cases (%d coincident copies, %d with the axes apart; %d overlap-free "
        "drawings skipped), worst signed distance error %.3g of the size\n",
        cases, coincident, offset, apart, worst);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(coincident, cases / 20) << "seed " << seed;
    EXPECT_GT(offset, cases / 5) << "seed " << seed;
    EXPECT_LT(apart, cases / 10) << "seed " << seed;
}

namespace {

// A core's support value along the shape-local direction d: its section's, turned about the axis.
Real core_support(int kind, double r, double h, Vec3 d) {
    const Real across = std::hypot(Real(d.x), Real(d.y));
    Real best = -INFINITY;
    for (const P2& p : section(kind, r, h)) best = std::max(best, std::fabs(p.x) * across + p.z * Real(d.z));
    return best;
}

// The distance between two convex polygons: 0 when no edge's normal separates them (they
// overlap), else the least over corner-edge pairs, both ways.
Real polygon_distance(const std::vector<P2>& a, const std::vector<P2>& b) {
    bool separated = false;
    for (int pass = 0; pass < 2 && !separated; ++pass) {
        const std::vector<P2>& p = pass ? b : a;
        for (size_t j = 0; j < p.size() && !separated; ++j) {
            const P2 s = p[j], t = p[(j + 1) % p.size()];
            const Real nx = t.z - s.z, nz = s.x - t.x;
            Real a_lo = INFINITY, a_hi = -INFINITY, b_lo = INFINITY, b_hi = -INFINITY;
            for (const P2& q : a)
                a_lo = std::min(a_lo, nx * q.x + nz * q.z), a_hi = std::max(a_hi, nx * q.x + nz * q.z);
            for (const P2& q : b)
                b_lo = std::min(b_lo, nx * q.x + nz * q.z), b_hi = std::max(b_hi, nx * q.x + nz * q.z);
            separated = (nx != 0 || nz != 0) && (a_hi < b_lo || b_hi < a_lo);
        }
    }
    if (!separated) return 0;
    Real best = INFINITY;
    for (int pass = 0; pass < 2; ++pass) {
        const std::vector<P2>& corners = pass ? b : a;
        const std::vector<P2>& edges = pass ? a : b;
        for (const P2& c : corners)
            for (size_t j = 0; j < edges.size(); ++j) {
                const P2 s = edges[j], t = edges[(j + 1) % edges.size()];
                const Real ex = t.x - s.x, ez = t.z - s.z, ee = ex * ex + ez * ez;
                Real k = ee > 0 ? ((c.x - s.x) * ex + (c.z - s.z) * ez) / ee : 0;
                k = std::clamp(k, Real(0), Real(1));
                best = std::min(best, std::hypot(c.x - (s.x + k * ex), c.z - (s.z + k * ez)));
            }
    }
    return best;
}

}  // namespace

// Cylinders, cones and capsules with parallel axes apart (plain or rounded by balls, the second
// reversed or not, turned about its axis), side by side, stacked or diagonal, gaps 1e-12 to 1 of
// the size: the distance against that of their sections in the plane through both axes (A - B is
// a body of revolution whose nearest point to the origin lies there), in long double. The pairs
// take the closed form (gjk/parallel_axes.hpp) unless the axes are turned by more than their poses'
// rounding: here by 1e-13 rad in a third of the cases, which the closed form must decline near the
// origin and may take 1e4 sizes from it (within twice the angle times B's reach of the parallel
// pair's distance). Checked: the distance, its points on the surfaces and the distance
// apart along the axis, and the axis by the shapes' supports (written here, not the library's).
// Sizes 1e-3 to 1e3, 1e-120 and 1e120 (the closed form works at a power of two that brings the
// pair to about 1), up to 1e4 sizes from the origin, both argument orders.
TEST(CoaxialDepth, ParallelAxesApartTakeTheSectionsDistance) {
    const uint64_t seed = 5101;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const char* names[] = {"cylinder", "cone", "capsule"};
    int cases = 0, failures = 0, closed = 0, tilted_closed = 0, tilted = 0, clear = 0;
    double worst = 0;
    for (const double size : {1e-3, 1.0, 1e3, 1e-120, 1e120})
        for (const double far : {0.0, 1e4})
            for (int i = 0; i < (size < 1e-100 || size > 1e100 ? 100 : 400); ++i) {
                int ka = static_cast<int>(3 * u(rng)), kb = static_cast<int>(3 * u(rng));
                if (ka == 2 && kb == 2) kb = i % 2;
                const double ra = size * (0.2 + u(rng)), ha = size * (0.2 + u(rng));
                const double rb = size * (0.2 + u(rng)), hb = size * (0.2 + u(rng));
                const double pad_a = ka == 2 ? 0.5 * ra : (i % 2 ? 0.1 * size * u(rng) : 0.0);
                const double pad_b = kb == 2 ? 0.5 * rb : (i % 4 < 2 ? 0.1 * size * u(rng) : 0.0);
                const bool flip = i % 5 == 1;
                const double tilt = i % 3 == 1 ? 1e-13 : 0.0;
                // Where B's axis lies: side by side, stacked along A's, or diagonal; the gap then
                // set by moving B along the direction that separates the sections.
                const double gap = size * std::pow(10.0, -12 + 12 * u(rng));
                const double phi = 6.283185307179586 * u(rng);
                const int where = i % 3;
                const double off0 = where == 1 ? 0.3 * size * u(rng) : 3 * size;
                const double dz0 = where == 0 ? 0.5 * size * (2 * u(rng) - 1) : (u(rng) < 0.5 ? -1 : 1) * 3 * size;
                std::vector<P2> sa, sb0;
                for (const P2& p : section(ka, ra, ha)) sa.push_back({p.x, p.z});
                for (const P2& p : section(kb, rb, hb)) sb0.push_back({p.x, flip ? -p.z : p.z});
                const auto placed = [&](Real off, Real dz) {
                    std::vector<P2> s;
                    for (const P2& p : sb0) s.push_back({p.x + off, p.z + dz});
                    return s;
                };
                // Scale B's offset from A's axis so that the cores' sections are gap + pads apart.
                const Real want = Real(gap) + pad_a + pad_b;
                Real lo = 0, hi = 1;
                for (int k = 0; k < 200; ++k) {
                    const Real mid = 0.5L * (lo + hi);
                    const bool apart = polygon_distance(sa, placed(mid * off0, mid * dz0)) > want;
                    (apart ? hi : lo) = mid;
                }
                const double off = double(hi * off0), dz = double(hi * dz0);
                const Real core_gap = polygon_distance(sa, placed(off, dz));
                if (!(core_gap > Real(pad_a + pad_b))) continue;  // rounded to touching
                const double truth = double(core_gap - pad_a - pad_b);

                const Axial shape_a(ka, ra, ha, pad_a), shape_b(kb, rb, hb, pad_b);
                const Shape &a = shape_a.shape(), &b = shape_b.shape();
                const Quat qa = random_quat(rng);
                const Transform pa = make_transform(far * size * random_unit(rng), qa);
                const Quat qb = qa * axis_angle({std::cos(phi + 1), std::sin(phi + 1), 0}, tilt) *
                                axis_angle({1, 0, 0}, flip ? 3.141592653589793 : 0.0) *
                                axis_angle({0, 0, 1}, 6.283185307179586 * u(rng));
                const Transform pb = make_transform(pa.apply({off * std::cos(phi), off * std::sin(phi), dz}), qb);
                const double coords = max_abs(pa.translation) + max_abs(pb.translation);
                // A turn moves B's support values by at most the angle times its reach: twice that.
                const double tol = 1e-10 * truth + 2 * tilt * std::hypot(rb, hb) + 1e-14 * size + 1e-15 * coords;
                ++cases;
                tilted += tilt > 0;
                // Untilted cores clear of their poses' rounding: the closed form's (at most 64 ulps
                // of the coordinates and the reaches are left to the loop's contact rules).
                clear += tilt == 0 && core_gap > 1e-12L * (size + coords) ? 2 : 0;
                auto fail = [&](const char* rule, double got, double want_) {
                    if (++failures <= 10)
                        ADD_FAILURE() << names[ka] << "/" << names[kb] << " " << rule << ": got " << got << ", want "
                                      << want_ << " (gap " << gap << ", where " << where << ", tilt " << tilt
                                      << ", flip " << flip << ", pads " << pad_a << " " << pad_b << "); size " << size
                                      << " far " << far << " case " << i << " seed " << seed;
                };
                for (int order = 0; order < 2; ++order) {
                    const Shape& x = order == 0 ? a : b;
                    const Shape& y = order == 0 ? b : a;
                    const Transform& px = order == 0 ? pa : pb;
                    const Transform& py = order == 0 ? pb : pa;
                    const DistanceResult r = gjk_distance(x, px, y, py, 1e-10, 256);
                    const bool closed_form = r.iterations == 1;  // the loop takes at least two calls
                    if (closed_form) (tilt > 0 ? tilted_closed : closed) += 1;
                    const double err = std::fabs(r.distance - truth);
                    worst = std::max(worst, err / size);
                    if (r.intersecting) fail("intersecting", 1, 0);
                    if (!(err <= tol)) fail("distance", r.distance, truth);
                    const Vec3 gap_v = (r.point_b - r.point_a) - r.distance * r.axis;
                    if (!(length(gap_v) <= tol)) fail("point_b - point_a - distance * axis", length(gap_v), 0);
                    const double on_a = order == 0 ? off_surface(r.point_a, px, ka, ra, ha, pad_a)
                                                   : off_surface(r.point_b, py, ka, ra, ha, pad_a);
                    const double on_b = order == 0 ? off_surface(r.point_b, py, kb, rb, hb, pad_b)
                                                   : off_surface(r.point_a, px, kb, rb, hb, pad_b);
                    if (!(on_a <= tol)) fail("A's point off its surface by", on_a, 0);
                    if (!(on_b <= tol)) fail("B's point off its surface by", on_b, 0);
                    // The axis: the shapes' supports along it are the distance apart.
                    const Vec3 n = order == 0 ? r.axis : -1.0 * r.axis;  // from A toward B
                    const Real sep = Real(dot(n, pb.translation - pa.translation)) -
                                     core_support(ka, ra, ha, pa.to_local_direction(n)) -
                                     core_support(kb, rb, hb, pb.to_local_direction(-1.0 * n)) - pad_a - pad_b;
                    // The loop's axis on a line contact tilts by up to sqrt(2 tol) rad, plus rounding
                    // (ParallelCylindersNearALineContact); the closed form's is exact to rounding.
                    const double axis_slack =
                        closed_form ? 0.0 : (2 * std::sqrt(2e-10) + 1e-15 * (size + coords) / truth) * size;
                    if (!(std::fabs(double(sep) - truth) <= tol + axis_slack))
                        fail("separation along the axis", double(sep), truth);
                }
            }
    std::printf(
        "parallel axes apart: %d pairs (%d turned by 1e-13 rad), closed form %d of %d answers untilted (%d "
        "clear of rounding), %d of %d turned; worst distance error %.3g of the size\n",
        cases, tilted, closed, 2 * (cases - tilted), clear, tilted_closed, 2 * tilted, worst);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    // Every parallel pair clear of rounding takes the closed form. Of the turned ones, those whose
    // turn is within their poses' rounding (1e4 sizes from the origin); the loop takes the rest.
    EXPECT_GE(closed, clear) << "seed " << seed;
    EXPECT_GT(clear, (cases - tilted) * 3 / 2) << "seed " << seed;
    EXPECT_GT(tilted_closed, tilted / 2) << "seed " << seed;
    EXPECT_LT(tilted_closed, 2 * tilted - tilted / 2) << "seed " << seed;
}

// A short capsule near a cone a thousand times wider, its axis turned from the cone's by 1e-6 to
// 0.5 rad, at loose tolerances: the distance is never below the shapes' true distance (the loop's
// answers are points of the shapes; GJK at 1e-12 here). A turn within the tolerance of the
// distance times the reaches once took the parallel closed form, whose point on the turned capsule
// lay off it: 3 % below a gap the shapes' supports proved (fuzz_queries, tolerance 0.25).
TEST(CoaxialDepth, TurnedPairsAtLooseTolerancesStayAboveTheDistance) {
    const uint64_t seed = 5102;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0, failures = 0, truths = 0;
    double worst_truth = 0, worst_above = 0;
    for (int i = 0; i < 400; ++i) {
        const double radius = 1e3 * (1 + 9 * u(rng)), half_height = 0.1 + 0.9 * u(rng),
                     half_length = 0.1 + 0.2 * u(rng);
        const ConeShape cone(radius, half_height);
        const SegmentShape segment(half_length);
        const SphereShape ball(1.0);
        const MinkowskiSumShape capsule(segment, ball);
        const double tilt = std::array{1e-6, 1e-3, 0.1, 0.5}[i % 4];
        const Quat qa = random_quat(rng);
        const Transform pa = make_transform(10 * random_unit(rng), qa);
        // Above the cone's base or its slant, 2 to 8 away along its axis, turned about a
        // direction across it.
        const double phi = 6.283185307179586 * u(rng);
        const Quat qb = qa * axis_angle({std::cos(phi), std::sin(phi), 0}, tilt);
        const Transform pb =
            make_transform(pa.apply({0.5 * u(rng), 0.5 * u(rng), (i % 2 ? 1 : -1) * (3 + 6 * u(rng))}), qb);
        // Truth: the least over the capsule's segment of its points' distance to the cone (convex
        // along the segment, so a golden-section search finds it), less the ball's radius.
        const Vec3 s0 = pb.apply({0, 0, -half_length}), s1 = pb.apply({0, 0, half_length});
        const auto to_cone = [&](double t) { return off_surface(s0 + t * (s1 - s0), pa, 1, radius, half_height, 0); };
        double lo = 0, hi = 1;
        for (int k = 0; k < 120; ++k) {
            const double m1 = lo + 0.381966 * (hi - lo), m2 = hi - 0.381966 * (hi - lo);
            (to_cone(m1) < to_cone(m2) ? hi : lo) = to_cone(m1) < to_cone(m2) ? m2 : m1;
        }
        const double truth = std::min({to_cone(0), to_cone(1), to_cone(0.5 * (lo + hi))}) - 1.0;
        ASSERT_GT(truth, 1.0) << "the capsule is placed apart from the cone; case " << i << " seed " << seed;
        ++truths;
        worst_truth =
            std::max(worst_truth, std::fabs(gjk_distance(cone, pa, capsule, pb, 1e-12, 256).distance - truth) / truth);
        for (const double tolerance : {0.25, 1e-2, 1e-6}) {
            for (int order = 0; order < 2; ++order) {
                const DistanceResult r = order ? gjk_distance(capsule, pb, cone, pa, tolerance, 256)
                                               : gjk_distance(cone, pa, capsule, pb, tolerance, 256);
                ++cases;
                // Never below the distance (beyond rounding), and above it by at most GJK's stop allows:
                // the cores' distance (the ball's radius 1 added) within its lower bound / (1 - tolerance).
                const double allowed = (truth + 1) / (1 - tolerance) - 1;
                worst_above = std::max(worst_above, (r.distance - truth) / (allowed - truth));
                if ((!(r.distance >= truth * (1 - 1e-9)) || !(r.distance <= allowed * (1 + 1e-9))) && ++failures <= 10)
                    ADD_FAILURE() << "tilt " << tilt << " tolerance " << tolerance << " order " << order
                                  << ": distance " << r.distance << ", truth " << truth << "; case " << i << " seed "
                                  << seed;
            }
        }
    }
    std::printf(
        "turned capsules by wide cones: %d distances at loose tolerances, at most %.2g of the allowed excess above; "
        "GJK at "
        "1e-12 within %.2g of the truth\n",
        cases, worst_above, worst_truth);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_EQ(truths, 400) << "seed " << seed;
    EXPECT_LT(worst_truth, 1e-9) << "seed " << seed;
}

// Overlapping cylinders and cones about nearly one axis: B turned by 1e-9 to 1e-6 rad about a
// direction across it, coaxial or with the axes apart by up to 0.3 of the radii, centred together
// or shifted along the axis, copies in a third of the cases, at the default tolerance. The
// expansion approaches the circle where the turned sides meet as slowly as the untilted one: a
// quarter of such pairs used up its 252 support calls (0.1 to 0.4 ms) and stopped up to 4e-4 of
// the size short. Truth: the untilted pair's depth D0 (its sections' Minkowski difference, long
// double); turning B about its centre by theta moves each of its points by at most theta times
// its reach, so the depth lies within that of D0. The answer is the expansion's converged depth
// or, unconverged, the larger of its lower bound and the closed form's (at most pi theta reach_b
// short; src/gjk/penetration.cpp): within (pi + 1) theta reach_b of D0 either way, and never above
// D0 by more than the turn (reach_b: the larger reach of the two).
TEST(CoaxialDepth, NearlyParallelOverlapsStayNearTheUntiltedDepth) {
    const uint64_t seed = 5201;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0, failures = 0, unconverged = 0;
    double worst = 0;
    for (const double theta : {1e-9, 1e-8, 1e-7, 1e-6})
        for (int i = 0; i < 120; ++i) {
            const int ka = i % 2, kb = (i / 2) % 2;  // cylinders and cones
            const bool same = i % 3 == 0;
            const double ra = 0.2 + u(rng), ha = 0.2 + u(rng);
            const double rb = same ? ra : 0.2 + u(rng), hb = same ? ha : 0.2 + u(rng);
            const double dz = std::array{0.0, 0.3, 0.7}[i % 3] * (ha + hb) * (2 * u(rng) - 1);
            const double off = (i % 4 == 1 ? 0.3 * u(rng) : 0.0) * std::min(ra, rb);
            const double phi = 6.283185307179586 * u(rng), psi = 6.283185307179586 * u(rng);
            const Vec3 across{off * std::cos(phi), off * std::sin(phi), 0};
            const Axial shape_a(same ? kb : ka, ra, ha, 0), shape_b(kb, rb, hb, 0);
            const Quat qa = random_quat(rng);
            const Transform pa = make_transform(random_unit(rng), qa);
            const Quat qb = qa * axis_angle({std::cos(psi), std::sin(psi), 0}, theta);
            const Transform pb = make_transform(pa.apply(across + Vec3{0, 0, dz}), qb);
            Hull2 placed;
            for (const P2& p : section(same ? kb : ka, ra, ha))
                for (const P2& q : section(kb, rb, hb))
                    for (const double mirror : {1.0, -1.0})
                        placed.pts.push_back({p.x - mirror * q.x - Real(off), p.z - (q.z + Real(dz))});
            const Real d0 = placed.depth();
            if (!(d0 > 0.01L)) continue;  // clear overlaps only
            // Either may be the one turned, by argument order: the larger reach bounds both.
            const double reach_b = std::max(std::hypot(ra, ha), std::hypot(rb, hb));
            const double allowed = 5 * theta * reach_b + 1e-12;
            for (int order = 0; order < 2; ++order) {
                const Shape& x = order ? shape_b.shape() : shape_a.shape();
                const Shape& y = order ? shape_a.shape() : shape_b.shape();
                const DistanceResult s = signed_distance(x, order ? pb : pa, y, order ? pa : pb, 1e-10, 256);
                ++cases;
                if (s.termination != Termination::RelativeError) ++unconverged;
                const double err = std::fabs(double(-s.distance - d0)), above = double(-s.distance - d0);
                worst = std::max(worst, err / (theta * reach_b));
                const Vec3 gap = (s.point_b - s.point_a) - s.distance * s.axis;
                if ((!(err <= allowed) || !(above <= theta * reach_b + 1e-10) || !(length(gap) <= 1e-12) ||
                     !(std::fabs(length(s.axis) - 1) <= 1e-12) || s.iterations > 160) &&
                    ++failures <= 10)
                    ADD_FAILURE() << "theta " << theta << " order " << order << ": depth " << -s.distance
                                  << ", untilted " << double(d0) << " (allowed " << allowed << "), points' gap "
                                  << length(gap) << ", calls " << s.iterations << ", termination " << int(s.termination)
                                  << "; case " << i << " seed " << seed;
            }
        }
    std::printf("nearly parallel overlaps: %d answers (%d unconverged), worst |depth - untilted| %.2g theta reach_b\n",
                cases, unconverged, worst);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(cases, 600) << "seed " << seed;
    EXPECT_GT(unconverged, cases / 50) << "seed " << seed;  // the branch under test
}

// B's axis across A's by an offset whose squares underflow (5e-324 to 1e-160 on x and y, A at the
// origin unturned, so the offset reaches the closed forms exact), overlapping and stacked apart:
// a fuzz_queries finding, a cylinder 4.3e12 wide about a small one 5e-324 off its axis on x and
// y, whose depth came out along (1 1 0), not unit, and 1.41 times too deep (the plane through both
// axes was the offset over its length, which had one bit). Sizes 1 to 1e12, both orders. Truth:
// the sections' depth and distance in long double, whose range holds the squares.
TEST(CoaxialDepth, OffsetsWhoseSquaresUnderflowKeepAUnitAxis) {
    const char* names[] = {"cylinder", "cone", "capsule"};
    int cases = 0, failures = 0, overlapping = 0, stacked = 0;
    for (const double size : {1.0, 1e3, 1e12})
        for (const double tiny : {4.9406564584124654e-324, 1e-310, 1e-170, 1e-160})
            for (int ka = 0; ka < 3; ++ka)
                for (int kb = 0; kb < 3; ++kb) {
                    if (ka == 2 && kb == 2) continue;  // two segments: a closed form of their own
                    for (const bool apart : {false, true}) {
                        const double ra = size, ha = 1e6 * size, rb = 0.4 * size, hb = 0.3 * size;
                        const double pad_a = ka == 2 ? 0.5 * ra : 0.0, pad_b = kb == 2 ? 0.5 * rb : 0.0;
                        const double dz = apart ? ha + hb + pad_a + pad_b + 0.01 * size : 0.25 * size;
                        const Axial shape_a(ka, ra, ha, pad_a), shape_b(kb, rb, hb, pad_b);
                        const Transform pa = make_transform({0, 0, 0}, Quat{});
                        const Transform pb = make_transform({tiny, tiny, dz}, Quat{});
                        const Real off = std::hypot(Real(tiny), Real(tiny));
                        std::vector<P2> a_pts = section(ka, ra, ha), b_pts;
                        Hull2 placed;
                        for (const P2& p : section(kb, rb, hb)) b_pts.push_back({p.x + off, p.z + Real(dz)});
                        for (const P2& p : a_pts)
                            for (const P2& q : section(kb, rb, hb))
                                for (const double mirror : {1.0, -1.0})
                                    placed.pts.push_back({p.x - mirror * q.x - off, p.z - q.z - Real(dz)});
                        const Real pads = Real(pad_a) + Real(pad_b);
                        const double truth =
                            apart ? double(polygon_distance(a_pts, b_pts) - pads) : -double(placed.depth() + pads);
                        ++cases;
                        (apart ? stacked : overlapping) += 1;
                        for (int order = 0; order < 2; ++order) {
                            const Shape& x = order == 0 ? shape_a.shape() : shape_b.shape();
                            const Shape& y = order == 0 ? shape_b.shape() : shape_a.shape();
                            const Transform& px = order == 0 ? pa : pb;
                            const Transform& py = order == 0 ? pb : pa;
                            const DistanceResult s = signed_distance(x, px, y, py, 1e-10, 256);
                            const double tol = 1e-12 * (ha + ra);  // the coordinates reach ha
                            if (!(std::fabs(s.distance - truth) <= tol) || !(std::fabs(length(s.axis) - 1) <= 1e-12)) {
                                if (++failures <= 10)
                                    ADD_FAILURE()
                                        << names[ka] << "/" << names[kb] << " size " << size << " offset " << tiny
                                        << (apart ? " apart" : " overlapping") << " order " << order
                                        << ": signed distance " << s.distance << " (want " << truth << "), axis ("
                                        << s.axis.x << " " << s.axis.y << " " << s.axis.z << ")";
                            }
                        }
                    }
                }
    std::printf("offsets whose squares underflow: %d cases (%d overlapping, %d stacked apart)\n", cases, overlapping,
                stacked);
    EXPECT_EQ(failures, 0);
}
