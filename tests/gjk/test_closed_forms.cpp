// SPDX-License-Identifier: MIT
// The closed forms of src/gjk/closed_forms.hpp (pairs of points, segments, spheres and capsules,
// which gjk_distance and gjk_intersect answer without a GJK loop) against two independent truths:
// the segment-segment distance in long double from the very matrices the library uses, and the
// GJK loop itself on the same cores given as two-vertex hulls (which the closed forms never see).
// Hard inputs on purpose: nearly parallel segments (tilts 0 .. 1e-3 rad) at gaps from 1e-12 to
// 1e-2 of the size, crossing and touching cores, scales 1e-150 to 1e90, both argument orders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "gjk/gjk.hpp"
#include "shapes/shape.hpp"

using namespace kairos;

namespace {

using Real = long double;
struct L3 {
    Real x, y, z;
};
L3 operator+(L3 a, L3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
L3 operator-(L3 a, L3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
L3 operator*(Real s, L3 a) { return {s * a.x, s * a.y, s * a.z}; }
Real dot(L3 a, L3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
L3 cross(L3 a, L3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
L3 lift(Vec3 v) { return {v.x, v.y, v.z}; }

// Nearest point of segment [a, b] to x (long double).
L3 nearest_on(L3 x, L3 a, L3 b) {
    const L3 ab = b - a;
    const Real len2 = dot(ab, ab);
    const Real t = len2 > 0 ? std::clamp(dot(x - a, ab) / len2, Real(0), Real(1)) : 0;
    return a + t * ab;
}
Real dist(L3 a, L3 b) { return std::sqrt(dot(a - b, a - b)); }

// Distance between segments [p1, q1] and [p2, q2] in long double: the smallest over the four
// endpoint-to-segment distances and the lines' common perpendicular when its feet lie on both
// (every candidate is a real pair of points, so the answer is never below the truth).
Real segment_distance(L3 p1, L3 q1, L3 p2, L3 q2) {
    Real best = std::min({dist(p1, nearest_on(p1, p2, q2)), dist(q1, nearest_on(q1, p2, q2)),
                          dist(p2, nearest_on(p2, p1, q1)), dist(q2, nearest_on(q2, p1, q1))});
    // The common perpendicular's foot on the first segment from cross products (no a e - b^2
    // cancellation, which for nearly parallel segments leaves too few digits even in long
    // double); the second foot is then the projection of the first (two feet computed apart
    // would slide along nearly parallel lines independently), and the first is projected back.
    const L3 d1 = q1 - p1, d2 = q2 - p2, r = p2 - p1, n = cross(d1, d2);
    const Real denom = dot(n, n);
    if (denom > 0) {
        const Real s = dot(cross(r, d2), n) / denom;
        if (s >= 0 && s <= 1) {
            const L3 on2 = nearest_on(p1 + s * d1, p2, q2);
            best = std::min(best, dist(nearest_on(on2, p1, q1), on2));
        }
    }
    return best;
}

enum Kind { kPoint, kSegment, kSphere, kCapsule };
const char* const kNames[] = {"point", "segment", "sphere", "capsule"};

// A shape of the kind, its core as a two-vertex hull (GJK's path), and its core's half length.
struct Made {
    std::unique_ptr<Shape> shape;
    ConvexHullShape core_hull;
    double h = 0, r = 0;
};
void make(Kind k, double h, double r, Made& m) {
    m.h = (k == kSegment || k == kCapsule) ? h : 0;
    m.r = (k == kSphere || k == kCapsule) ? r : 0;
    switch (k) {
        case kPoint: m.shape = std::make_unique<PointShape>(); break;
        case kSegment: m.shape = std::make_unique<SegmentShape>(m.h); break;
        case kSphere: m.shape = std::make_unique<SphereShape>(m.r); break;
        case kCapsule: m.shape = std::make_unique<CapsuleShape>(m.r, m.h); break;
    }
    m.core_hull.vertices = m.h > 0 ? std::vector<Vec3>{{0, 0, -m.h}, {0, 0, m.h}} : std::vector<Vec3>{{0, 0, 0}};
    m.core_hull.dimension = m.h > 0 ? 1 : 0;
}

// The core's end points in the world, from the transform's own doubles.
void core_ends(const Made& m, const Transform& x, L3& lo, L3& hi) {
    const L3 c = lift(x.translation);
    const L3 axis{x.rotation.r[0].z, x.rotation.r[1].z, x.rotation.r[2].z};
    lo = c - Real(m.h) * axis;
    hi = c + Real(m.h) * axis;
}

Quat random_rotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    Quat q{g(rng), g(rng), g(rng), g(rng)};
    return normalized(q);
}

struct Tally {
    int cases = 0, intersecting = 0, judged_verdicts = 0, near_parallel = 0, failures = 0;
    double worst = 0, worst_gjk = 0;
};

void check(const Made& a, const Transform& xa, const Made& b, const Transform& xb, double size,
           const std::string& what, Tally& t) {
    const double tol = 1e-12 * size;
    L3 a0, a1, b0, b1;
    core_ends(a, xa, a0, a1);
    core_ends(b, xb, b0, b1);
    const Real core = segment_distance(a0, a1, b0, b1);
    const Real truth = std::max(Real(0), core - Real(a.r) - Real(b.r));
    const DistanceResult r = gjk_distance(*a.shape, xa, *b.shape, xb, 1e-10, 256);
    const DistanceResult s = gjk_distance(*b.shape, xb, *a.shape, xa, 1e-10, 256);
    Vec3 axis{};
    const bool hit = gjk_intersect(*a.shape, xa, *b.shape, xb, axis, nullptr);
    ++t.cases;
    auto fail = [&](const char* rule, double x) {
        if (++t.failures <= 8)
            ADD_FAILURE() << what << ": " << rule << " (" << x << "); truth " << double(truth) << ", got "
                          << r.distance << " / " << s.distance;
    };
    const double err = std::fabs(double(Real(r.distance) - truth));
    t.worst = std::max(t.worst, err / size);
    if (!(err <= tol)) fail("distance off the long-double truth", err / size);
    if (!(std::fabs(r.distance - s.distance) <= tol)) fail("argument orders differ", r.distance - s.distance);
    if (r.iterations != 1) fail("a closed-form pair ran the GJK loop", r.iterations);
    if (truth > tol || truth == 0) ++t.judged_verdicts;
    if (truth > tol && (r.intersecting || hit)) fail("intersecting although apart", double(truth));
    if (core < Real(a.r) + Real(b.r) - Real(tol) && (!r.intersecting || !hit)) fail("apart although overlapping", double(truth));
    if (r.intersecting) ++t.intersecting;
    if (!r.intersecting) {
        // Witness points: the distance apart, each at its radius from its own core, the axis
        // along their difference; the intersect test's separating axis separates the cores.
        const L3 pa = lift(r.point_a), pb = lift(r.point_b);
        if (!(std::fabs(double(dist(pa, pb) - Real(r.distance))) <= tol)) fail("witness points not the distance apart", 0);
        if (!(std::fabs(double(dist(pa, nearest_on(pa, a0, a1)) - Real(a.r))) <= tol)) fail("point_a off A", 0);
        if (!(std::fabs(double(dist(pb, nearest_on(pb, b0, b1)) - Real(b.r))) <= tol)) fail("point_b off B", 0);
        if (r.distance > tol && !(dot(r.axis, r.point_b - r.point_a) > 0)) fail("axis points from B toward A", 0);
        if (!hit) {
            const L3 n = lift(axis);
            const Real ga = std::max(dot(n, a0), dot(n, a1)) + Real(a.r);
            const Real gb = std::min(dot(n, b0), dot(n, b1)) - Real(b.r);
            if (!(gb - ga >= -Real(tol))) fail("intersect's axis does not separate", double(ga - gb));
        }
    }
    // The GJK loop on the bare cores (two-vertex hulls) agrees with the closed form's core distance.
    const DistanceResult g = gjk_distance(a.core_hull, xa, b.core_hull, xb, 1e-12, 256);
    const double core_closed = r.intersecting ? 0.0 : r.distance + a.r + b.r;
    if (!r.intersecting) {
        const double gerr = std::fabs(g.distance - core_closed);
        t.worst_gjk = std::max(t.worst_gjk, gerr / size);
        if (!(gerr <= 1e-9 * size)) fail("GJK on the cores disagrees", gerr / size);
    }
}

// Random pairs of every kind pair; a third of them nearly parallel segments placed a constructed
// gap apart across their common direction, overlapping along it.
TEST(ClosedForms, EveryLineCorePairAgainstLongDoubleAndGjk) {
    const uint64_t seed = 20261126;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double tilts[] = {0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
    const double gaps[] = {0, 1e-12, 1e-9, 1e-6, 1e-2, -1e-9, -1e-2};
    Tally t;
    for (double scale : {1.0, 1e-150, 1e-8, 1e6, 1e90}) {
        for (int ka = 0; ka < 4; ++ka)
            for (int kb = 0; kb < 4; ++kb)
                for (int i = 0; i < 300; ++i) {
                    Made a, b;
                    make(Kind(ka), scale * (0.2 + std::fabs(u(rng))), scale * 0.3 * std::fabs(u(rng)), a);
                    make(Kind(kb), scale * (0.2 + std::fabs(u(rng))), scale * 0.3 * std::fabs(u(rng)), b);
                    const Quat qa = random_rotation(rng);
                    const Transform xa = make_transform(scale * Vec3{u(rng), u(rng), u(rng)}, qa);
                    Transform xb;
                    if (i % 3 == 0) {
                        // B's axis tilted from A's by a tiny angle, B offset across by the radii plus a gap.
                        const double tilt = tilts[i / 3 % 6], gap = gaps[i / 18 % 7];
                        const Vec3 za = xa.rotation.col(2), across = normalized_or(cross(za, Vec3{u(rng), u(rng), u(rng)}), Vec3{1, 0, 0});
                        const Quat qb = axis_angle(across, tilt) * qa;
                        const double along = 0.5 * u(rng) * (a.h + b.h);
                        xb = make_transform(xa.translation + along * za + (a.r + b.r + gap * scale) * cross(across, za), qb);
                        ++t.near_parallel;
                    } else {
                        xb = make_transform(scale * Vec3{u(rng), u(rng), u(rng)}, random_rotation(rng));
                    }
                    const double size = std::max({a.h + a.r, b.h + b.r, max_abs(xa.translation), max_abs(xb.translation)});
                    const std::string what = std::string(kNames[ka]) + "/" + kNames[kb] + " scale " + std::to_string(scale) +
                                             " case " + std::to_string(i) + " seed " + std::to_string(seed);
                    check(a, xa, b, xb, size, what, t);
                }
    }
    std::printf("closed forms: %d cases (%d nearly parallel), %d intersecting; worst error %.3g of the size against "
                "long double, %.3g against GJK on the cores\n",
                t.cases, t.near_parallel, t.intersecting, t.worst, t.worst_gjk);
    EXPECT_EQ(t.failures, 0) << "seed " << seed;
    // Both verdicts are exercised.
    EXPECT_GT(t.intersecting, t.cases / 10) << "seed " << seed;
    EXPECT_LT(t.intersecting, t.cases * 9 / 10) << "seed " << seed;
}

}  // namespace
