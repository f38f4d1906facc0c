// SPDX-License-Identifier: MIT
// The closed forms of src/gjk/closed_forms.hpp (pairs of points, segments, spheres and capsules,
// and a sphere or point against a box, which gjk_distance and gjk_intersect answer without a GJK
// loop) against two independent truths:
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
#include <utility>
#include <vector>

#include "casts/cast.hpp"
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

// gjk_distance and gjk_intersect of a solid (s at xs) and a ball or point (b at xb), the solid
// first when order is 0, else second; axis: intersect's, from the first shape toward the second.
struct InOrder {
    DistanceResult r;
    bool hit;
    Vec3 axis;
};
InOrder query_in_order(const Shape& s, const Transform& xs, const Shape& b, const Transform& xb, int order) {
    InOrder q{};
    q.r = order == 0 ? gjk_distance(s, xs, b, xb, 1e-10, 256) : gjk_distance(b, xb, s, xs, 1e-10, 256);
    q.hit = order == 0 ? gjk_intersect(s, xs, b, xb, q.axis, nullptr) : gjk_intersect(b, xb, s, xs, q.axis, nullptr);
    return q;
}

// The checks such a query shares: the distance against the long-double truth within tol (its
// error over size returned), one iteration, the verdicts against the truth and the cores'
// distance d_core (the ball's radius r), the witness points (compared in long double: squares
// of 1e-162 underflow in double) and the distance's axis.
template <class Fail>
double judge(const InOrder& q, Real truth, Real d_core, double r, double tol, double size, Fail&& fail) {
    const DistanceResult& res = q.r;
    const double err = std::fabs(double(Real(res.distance) - truth));
    if (!(err <= tol)) fail("distance off the long-double truth", err / size);
    if (res.iterations != 1) fail("a closed-form pair ran the GJK loop", res.iterations);
    if (truth > tol && (res.intersecting || q.hit)) fail("intersecting although apart", double(truth));
    if (d_core < Real(r) - Real(tol) && (!res.intersecting || !q.hit)) fail("apart although overlapping", double(d_core));
    if (!res.intersecting) {
        if (!(std::fabs(double(dist(lift(res.point_b), lift(res.point_a)) - Real(res.distance))) <= tol))
            fail("witness points", 0);
        if (res.distance > tol && !(dot(res.axis, res.point_b - res.point_a) > 0)) fail("axis from A toward B", 0);
    }
    return err / size;
}

// A sphere (or a point, or a rounded box's corner) against a box, in both orders: the box placed at
// random, the ball's centre put at a face, an edge or a corner region at gaps from 1e-12 to 1e-2
// of the size on either side, or at random. Truth: the centre clamped to the box in long double
// (from the very matrix the library uses); and GJK on the cores given as hulls.
TEST(ClosedForms, BallAgainstBoxAgainstLongDoubleAndGjk) {
    const uint64_t seed = 611;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double gaps[] = {0, 1e-12, 1e-9, 1e-6, 1e-2, -1e-12, -1e-9, -1e-2, 0.3};
    int cases = 0, intersecting = 0, failures = 0;
    double worst = 0, worst_gjk = 0;
    for (double scale : {1.0, 1e-150, 1e-6, 1e4, 1e90}) {
        for (int i = 0; i < 1500; ++i) {
            const Vec3 h = scale * Vec3{0.1 + std::fabs(u(rng)), 0.1 + std::fabs(u(rng)), 0.1 + std::fabs(u(rng))};
            const double radius = i % 4 == 0 ? 0.0 : scale * 0.5 * std::fabs(u(rng));
            BoxShape box(h);
            SphereShape ball(radius);
            PointShape point;
            const Shape& b = radius > 0 ? static_cast<const Shape&>(ball) : static_cast<const Shape&>(point);
            ConvexHullShape box_hull, point_hull;
            for (int k = 0; k < 8; ++k)
                box_hull.vertices.push_back({k & 1 ? h.x : -h.x, k & 2 ? h.y : -h.y, k & 4 ? h.z : -h.z});
            point_hull.vertices = {{0, 0, 0}};
            point_hull.dimension = 0;
            const Transform xbox = make_transform(scale * Vec3{u(rng), u(rng), u(rng)}, random_rotation(rng));
            // The centre: in a face, edge or corner region (1, 2 or 3 coordinates beyond the box)
            // at the chosen gap from the ball's surface, or anywhere near.
            Vec3 local{u(rng) * h.x, u(rng) * h.y, u(rng) * h.z};
            const double gap = gaps[i % 9] * scale;
            const int beyond = 1 + i / 9 % 3;
            Vec3 out_dir{};
            for (int k = 0; k < beyond; ++k) {
                const int axis = (i / 27 + k) % 3;
                const double sgn = u(rng) < 0 ? -1 : 1;
                (axis == 0 ? out_dir.x : axis == 1 ? out_dir.y : out_dir.z) = sgn;
                (axis == 0 ? local.x : axis == 1 ? local.y : local.z) = sgn * (axis == 0 ? h.x : axis == 1 ? h.y : h.z);
            }
            out_dir = normalized_or(out_dir, Vec3{1, 0, 0});
            local = local + (radius + gap) * out_dir;
            const Transform xb = make_transform(xbox.apply(local), random_rotation(rng));
            // Truth in long double: the centre in the box's frame, clamped.
            const L3 rel = lift(xb.translation) - lift(xbox.translation);
            Real sq = 0;
            for (int k = 0; k < 3; ++k) {
                const L3 col{xbox.rotation.r[0][k], xbox.rotation.r[1][k], xbox.rotation.r[2][k]};
                const Real c = dot(col, rel), hk = k == 0 ? h.x : k == 1 ? h.y : h.z;
                const Real o = std::fabs(c) - hk;
                if (o > 0) sq += o * o;
            }
            const Real truth = std::max(Real(0), std::sqrt(sq) - Real(radius));
            const double size = std::max({max_abs(h), max_abs(xbox.translation), max_abs(xb.translation), radius});
            const double tol = 1e-12 * size;
            for (int order = 0; order < 2; ++order) {
                const InOrder q = query_in_order(box, xbox, b, xb, order);
                const DistanceResult& r = q.r;
                const bool hit = q.hit;
                const Vec3 axis = q.axis;
                ++cases;
                auto fail = [&](const char* rule, double x) {
                    if (++failures <= 8)
                        ADD_FAILURE() << rule << " (" << x << "); truth " << double(truth) << ", got " << r.distance
                                      << "; scale " << scale << " case " << i << " order " << order << " seed " << seed;
                };
                worst = std::max(worst, judge(q, truth, std::sqrt(sq), radius, tol, size, fail));
                if (r.intersecting) ++intersecting;
                if (!hit) {
                    // The axis (from A toward B) separates: the box's shadow from its own frame.
                    const Vec3 n = order == 0 ? axis : -axis;  // from the box toward the ball
                    const Vec3 nl = xbox.to_local_direction(n);
                    const double box_top = dot(n, xbox.translation) + std::fabs(nl.x) * h.x + std::fabs(nl.y) * h.y +
                                           std::fabs(nl.z) * h.z;
                    const double ball_bottom = dot(n, xb.translation) - radius;
                    if (!(ball_bottom - box_top >= -tol)) fail("intersect's axis does not separate", box_top - ball_bottom);
                }
                // GJK on the cores as hulls.
                if (!r.intersecting) {
                    const DistanceResult g = order == 0 ? gjk_distance(box_hull, xbox, point_hull, xb, 1e-12, 256)
                                                        : gjk_distance(point_hull, xb, box_hull, xbox, 1e-12, 256);
                    const double gerr = std::fabs(g.distance - (r.distance + radius));
                    worst_gjk = std::max(worst_gjk, gerr / size);
                    if (!(gerr <= 1e-9 * size)) fail("GJK on the cores disagrees", gerr / size);
                }
            }
        }
    }
    std::printf("ball/box closed form: %d queries, %d intersecting; worst error %.3g of the size against long "
                "double, %.3g against GJK on the cores\n",
                cases, intersecting, worst, worst_gjk);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(intersecting, cases / 10) << "seed " << seed;
    EXPECT_LT(intersecting, cases * 9 / 10) << "seed " << seed;
}

// A point's distance in the plane (long double) to a convex polygon given counter-clockwise:
// 0 inside, else the least distance to its edges. Generic, unlike the library's case analysis.
Real polygon_distance(Real px, Real pz, const std::vector<std::pair<Real, Real>>& poly) {
    bool inside = true;
    Real best = INFINITY;
    for (size_t k = 0; k < poly.size(); ++k) {
        const auto [ax, az] = poly[k];
        const auto [bx, bz] = poly[(k + 1) % poly.size()];
        const Real ex = bx - ax, ez = bz - az;
        if (ex * (pz - az) - ez * (px - ax) < 0) inside = false;  // right of the edge: outside
        const Real t = std::clamp(((px - ax) * ex + (pz - az) * ez) / (ex * ex + ez * ez), Real(0), Real(1));
        const Real dx = px - (ax + t * ex), dz = pz - (az + t * ez);
        best = std::min(best, std::sqrt(dx * dx + dz * dz));
    }
    return inside ? 0 : best;
}

// A ball or a point against a cylinder or a cone (a point core and a solid of revolution), which
// gjk_distance and gjk_intersect answer in closed form. The centre is placed off each feature
// (side, flat end or base, rim, slant, apex) along a normal there, at gaps from -1e-2 to 0.3 of
// the size (1e-12 .. 1e-2 either side of the surface), or inside anywhere; solids plain, needles
// (1e3 times longer than wide) and flat; scales 1e-150 to 1e90; both orders. Truth: the distance
// in long double from the centre's (radius, height) in the axial half-plane to the axial section
// (a rectangle or a triangle) by a generic polygon distance. Also the GJK loop on the same solid
// as a general shape (the hull of it with itself), which the closed form never sees. A fuzz-found
// case first: a point 1.3e-5 of the size inside a needle cone that the GJK loop, from the point's
// side, called apart by 5.8e-14 (Johnson's determinants failed on the sliver).
TEST(ClosedForms, BallAgainstCylinderAndConeAgainstLongDoubleAndGjk) {
    {
        const double k = std::ldexp(1.0, -299);  // the finding's 1e90 scale, brought near 1 exactly
        ConeShape cone(k * 4.6677315591541371e+86, k * 1.1795153501611867e+90);
        PointShape point;
        const Vec3 local{k * 7.2083936956637913e+85, k * 1.0215793390773524e+86, k * 4.7961304912696624e+89};
        const Transform xc = make_transform({0.25, -0.5, 1}, Quat{0.3, -0.2, 0.5, 0.7874007874011811});
        const Transform xp = make_transform(xc.apply(local), Quat{});
        Vec3 axis{};
        EXPECT_TRUE(gjk_distance(point, xp, cone, xc, 1e-10, 256).intersecting);
        EXPECT_TRUE(gjk_intersect(point, xp, cone, xc, axis, nullptr));
        EXPECT_TRUE(gjk_distance(cone, xc, point, xp, 1e-10, 256).intersecting);
    }
    const uint64_t seed = 25021;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double gaps[] = {0, 1e-12, 1e-9, 1e-6, 1e-2, -1e-12, -1e-9, -1e-2, 0.3};
    int cases = 0, intersecting = 0, failures = 0, gjk_checked = 0;
    int feature_count[5] = {};
    double worst = 0, worst_gjk = 0;
    for (double scale : {1.0, 1e-150, 1e-6, 1e4, 1e90}) {
        for (int i = 0; i < 1200; ++i) {
            const bool is_cone = i % 2 == 1;
            const double aspect = i % 7 == 0 ? 1e-3 : i % 7 == 1 ? 1e3 : 1.0;  // radius over height
            const double r = scale * (0.2 + u(rng)) * std::min(1.0, aspect),
                         hh = scale * (0.2 + u(rng)) / std::max(1.0, aspect);
            const double radius = (i / 2) % 4 == 0 ? 0.0 : scale * 0.3 * u(rng);  // cones and cylinders alike
            CylinderShape cyl(r, hh);
            ConeShape cone(r, hh);
            const Shape& solid = is_cone ? static_cast<const Shape&>(cone) : cyl;
            const HullOfTwoShape general(solid, solid);
            SphereShape ball(radius > 0 ? radius : 1);
            PointShape point;
            const Shape& b = radius > 0 ? static_cast<const Shape&>(ball) : static_cast<const Shape&>(point);
            // A feature, its point X and an outward normal n there, in the section (rho, z).
            const int feature =
                static_cast<int>(rng() % 5);  // 0 side/slant, 1 end/base, 2 rim, 3 apex or other rim, 4 inside
            ++feature_count[feature];
            const double l = std::hypot(2 * hh, r);
            double xr, xz, nr, nz;
            const double w = u(rng);
            if (feature == 0) {
                if (is_cone)
                    xr = w * r, xz = hh - 2 * hh * w, nr = 2 * hh / l, nz = r / l;
                else
                    xr = r, xz = hh * (2 * w - 1), nr = 1, nz = 0;
            } else if (feature == 1) {
                xr = w * r, xz = is_cone || i % 3 ? -hh : hh, nr = 0, nz = xz < 0 ? -1 : 1;
            } else if (feature == 2 || (feature == 3 && !is_cone)) {
                // The rim at the bottom (a cone's) or either end: n between the end's and the side's.
                xr = r, xz = is_cone || feature == 2 ? -hh : hh;
                const double sr = is_cone ? 2 * hh / l : 1, sz = is_cone ? r / l : 0;
                const double er = 0, ez = xz < 0 ? -1 : 1;
                nr = w * sr + (1 - w) * er, nz = w * sz + (1 - w) * ez;
                const double m = std::hypot(nr, nz);
                nr /= m, nz /= m;
            } else if (feature == 3) {  // the apex: n between the slant's normal and the axis
                xr = 0, xz = hh;
                nr = w * 2 * hh / l, nz = w * r / l + (1 - w);
                const double m = std::hypot(nr, nz);
                nr /= m, nz /= m;
            } else {  // inside, anywhere
                xz = hh * (2 * u(rng) - 1);
                xr = (is_cone ? r * (hh - xz) / (2 * hh) : r) * w;
                nr = 0, nz = 0;
            }
            const double gap = feature == 4 ? 0 : gaps[i % 9] * scale * (aspect == 1 ? 1 : 1e-3);
            const double a = 2 * std::acos(-1.0) * u(rng);
            const Vec3 ud{std::cos(a), std::sin(a), 0};
            const Vec3 local = (xr + (radius + gap) * nr) * ud + Vec3{0, 0, xz + (radius + gap) * nz};
            const Transform xs = make_transform(scale * Vec3{u(rng), u(rng), u(rng)}, random_rotation(rng));
            const Transform xb = make_transform(xs.apply(local), random_rotation(rng));
            // Truth in long double: the centre in the solid's frame, its (radius, height), the section.
            const L3 rel = lift(xb.translation) - lift(xs.translation);
            Real c[3];
            for (int k = 0; k < 3; ++k)
                c[k] = dot(L3{xs.rotation.r[0][k], xs.rotation.r[1][k], xs.rotation.r[2][k]}, rel);
            const Real rho = std::sqrt(c[0] * c[0] + c[1] * c[1]);
            std::vector<std::pair<Real, Real>> section = {{0, -hh}, {r, -hh}};
            if (!is_cone) section.push_back({r, hh});
            section.push_back({0, hh});
            const Real d_core = polygon_distance(rho, c[2], section);
            const Real truth = std::max(Real(0), d_core - Real(radius));
            const double size = std::max({r, hh, max_abs(xs.translation), max_abs(xb.translation), radius});
            const double tol = 1e-12 * size;
            for (int order = 0; order < 2; ++order) {
                const InOrder q = query_in_order(solid, xs, b, xb, order);
                const DistanceResult& res = q.r;
                const bool hit = q.hit;
                const Vec3 axis = q.axis;
                ++cases;
                auto fail = [&](const char* rule, double x) {
                    if (++failures <= 8)
                        ADD_FAILURE() << rule << " (" << x << "); truth " << double(truth) << ", got " << res.distance
                                      << "; " << (is_cone ? "cone" : "cylinder") << " feature " << feature << " scale "
                                      << scale << " case " << i << " order " << order << " seed " << seed;
                };
                worst = std::max(worst, judge(q, truth, d_core, radius, tol, size, fail));
                if (res.intersecting) ++intersecting;
                if (!hit) {
                    // The axis (from A toward B) separates: the solid's support along it.
                    const Vec3 n = order == 0 ? axis : -axis;  // from the solid toward the ball
                    const double top = dot(n, xs.apply(support(solid, xs.to_local_direction(n))));
                    const double bottom = dot(n, xb.translation) - radius;
                    if (!(bottom - top >= -tol)) fail("intersect's axis does not separate", top - bottom);
                }
                // The GJK loop on the solid as a general shape, where it converges.
                if (!res.intersecting && aspect == 1) {
                    const DistanceResult g = order == 0 ? gjk_distance(general, xs, b, xb, 1e-12, 256)
                                                        : gjk_distance(b, xb, general, xs, 1e-12, 256);
                    if (g.termination == Termination::RelativeError || g.termination == Termination::RepeatedSupport) {
                        ++gjk_checked;
                        const double gerr = std::fabs(g.distance - res.distance);
                        worst_gjk = std::max(worst_gjk, gerr / size);
                        if (!(gerr <= 1e-8 * size)) fail("the GJK loop disagrees", gerr / size);
                    }
                }
            }
        }
    }
    std::printf(
        "ball/cylinder and ball/cone closed form: %d queries, %d intersecting (features %d %d %d %d %d); worst "
        "error %.3g of the size against long double, %.3g against the GJK loop on %d\n",
        cases, intersecting, feature_count[0], feature_count[1], feature_count[2], feature_count[3], feature_count[4],
        worst, worst_gjk, gjk_checked);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(intersecting, cases / 5) << "seed " << seed;
    EXPECT_LT(intersecting, cases * 4 / 5) << "seed " << seed;
    EXPECT_GT(gjk_checked, cases / 10) << "seed " << seed;
}

// Rays and shape casts between balls (point cores: spheres and points), which ray_cast and
// shape_cast answer by the closed form. Truth: the entry of the ray into the ball in long double
// (the smaller root of the quadratic, from the closest approach). Rays aimed at the ball with
// offsets from the centre line of 0 .. 1 - 1e-12 .. 1 + 1e-2 of the radius (grazing included),
// starting inside, reaching it just before or just after the step's end; scales 1e-150 to 1e90;
// both shapes of a shape cast moving. Each answer is also held against the GJK cast loop on the
// same balls given as one-vertex hulls grown by a sphere (a Minkowski sum), which it never sees.
TEST(ClosedForms, BallCastsAgainstLongDoubleAndGjk) {
    const uint64_t seed = 97;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double offsets[] = {0, 0.5, 0.9, 1 - 1e-6, 1 - 1e-12, 1 + 1e-12, 1 + 1e-6, 1.01};
    const double reaches[] = {2, 1.0000001, 0.9999999, 0.5};  // the step's length over the entry distance
    int cases = 0, hits = 0, failures = 0;
    double worst = 0, worst_gjk = 0;
    for (double scale : {1.0, 1e-150, 1e-6, 1e4, 1e90}) {
        for (int i = 0; i < 640; ++i) {
            const double ra = scale * (0.1 + std::fabs(u(rng))), rb = i % 5 == 0 ? 0.0 : scale * std::fabs(u(rng));
            const double radius = ra + rb;
            // B's centre relative to A's at the start: `back` before the ball along -dir, offset
            // across by offsets[] of the radius; the relative motion along dir covers reaches[].
            const Vec3 dir = normalized_or(Vec3{u(rng), u(rng), u(rng)}, Vec3{1, 0, 0});
            const Vec3 side = normalized_or(cross(dir, Vec3{u(rng), u(rng), u(rng)}), Vec3{0, 1, 0});
            const double off = offsets[i % 8] * radius;
            const bool inside = i % 16 == 15;
            const double back = inside ? 0.5 * radius : radius * (1 + 3 * std::fabs(u(rng)));
            const Vec3 rel0 = (inside ? 0.0 : off) * side - back * dir;
            const double entry = back - std::sqrt(std::max(0.0, radius * radius - off * off));
            const Vec3 rel_motion = (entry > 0 ? entry * reaches[i / 8 % 4] : radius) * dir;
            const Transform xa = make_transform(scale * Vec3{u(rng), u(rng), u(rng)}, random_rotation(rng));
            const Transform xb = make_transform(xa.translation + rel0, random_rotation(rng));
            const Vec3 ta = scale * Vec3{u(rng), u(rng), u(rng)};
            const Vec3 tb = ta + rel_motion;
            // Truth in long double from the doubles the casts see.
            const L3 p0 = lift(xb.translation) - lift(xa.translation), v = lift(tb) - lift(ta);
            const Real vv = dot(v, v), m = -dot(p0, v) / vv;
            const L3 w = p0 + m * v;
            const Real R = Real(ra) + Real(rb), ww = dot(w, w), pp = dot(p0, p0);
            Real truth = -1;
            if (pp <= R * R) truth = 0;
            else if (m > 0 && ww <= R * R) {
                const Real h = std::sqrt(R * R - ww) / std::sqrt(vv);
                truth = (pp - R * R) / vv / (m + h);
                if (truth > 1) truth = -1;
            }
            SphereShape a(ra), b(rb);
            PointShape pt;
            const Shape& bs = rb > 0 ? static_cast<const Shape&>(b) : static_cast<const Shape&>(pt);
            ConvexHullShape ha, hb;
            ha.vertices = {{0, 0, 0}}, ha.dimension = 0;
            hb.vertices = {{0, 0, 0}}, hb.dimension = 0;
            MinkowskiSumShape ga(ha, a);
            MinkowskiSumShape gb(hb, b);
            const CastResult c = shape_cast(a, xa, ta, bs, xb, tb, 1e-12, 256);
            const CastResult g = shape_cast(ga, xa, ta, rb > 0 ? static_cast<const Shape&>(gb) : hb, xb, tb, 1e-12, 256);
            // The ray cast: the ray of B's centre against A grown by B's radius is the same
            // question when B is a point.
            ++cases;
            auto fail = [&](const char* rule, double x) {
                if (++failures <= 8)
                    ADD_FAILURE() << rule << " (" << x << "); truth " << double(truth) << ", got hit " << c.hit
                                  << " toi " << c.toi << "; scale " << scale << " case " << i << " seed " << seed;
            };
            // Verdicts beyond grazing: a miss by more than 1e-9 of the radius, a hit inside by more.
            const Real closest = std::sqrt(m > 1 ? dot(p0 + v, p0 + v) : (m < 0 ? pp : ww));
            const bool clear_miss = closest > R * (1 + 1e-9L), clear_hit = closest < R * (1 - 1e-9L);
            if (clear_miss && c.hit) fail("a hit where the balls stay apart", double(closest / R - 1));
            if (clear_hit && truth >= 0 && !c.hit) fail("a miss where the balls meet", double(truth));
            if (c.iterations != 1) fail("a closed-form pair ran the cast loop", c.iterations);
            if (c.hit) {
                ++hits;
                if (truth >= 0) {
                    const double err = std::fabs(double(Real(c.toi) - truth));
                    // Grazing entries are ill-conditioned in toi (not in distance): judged on clear hits.
                    if (clear_hit) {
                        worst = std::max(worst, err);
                        if (!(err <= 1e-12)) fail("toi off the long-double truth", err);
                    }
                }
                if (!(std::fabs(length(c.normal) - 1) <= 1e-12)) fail("normal not unit", length(c.normal));
                // The normal is from A toward B: the line between the centres at toi.
                if (c.toi > 0) {
                    const L3 between = p0 + Real(c.toi) * v;
                    const Real along = dot(lift(c.normal), between) / std::sqrt(dot(between, between));
                    if (!(along > 1 - 1e-9L)) fail("normal not along the centres", double(along));
                }
            }
            if (g.hit == c.hit && c.hit && clear_hit) worst_gjk = std::max(worst_gjk, std::fabs(g.toi - c.toi));
            if (clear_hit != clear_miss && g.hit != c.hit) fail("the GJK cast loop disagrees", g.toi - c.toi);
            if (clear_hit && c.hit && g.hit && !(std::fabs(g.toi - c.toi) <= 1e-9)) fail("GJK's toi differs", g.toi - c.toi);
            // Ray casts: B's centre as a ray against A grown by rb.
            if (rb == 0) {
                const CastResult rc = ray_cast(a, xa, xb.translation, tb - ta, 1e-12, 256);
                if (rc.hit != c.hit || std::fabs(rc.toi - c.toi) > 1e-12) fail("ray and shape cast differ", rc.toi - c.toi);
                if (rc.hit && rc.toi > 0) {
                    // The ray's hit point on the sphere's surface, at the ray point.
                    const Vec3 at = xb.translation + rc.toi * (tb - ta);
                    const double off_surface = std::fabs(length(rc.point - xa.translation) - ra);
                    if (!(off_surface <= 1e-12 * scale * 4)) fail("ray hit point off the surface", off_surface / scale);
                    if (!(length(at - rc.point) <= 1e-9 * scale * 4 + 1e-6 * ra * double(!clear_hit)))
                        fail("ray hit point away from the ray point", length(at - rc.point) / scale);
                }
            }
        }
    }
    std::printf("ball casts: %d casts, %d hits; worst toi error %.3g against long double, %.3g against the GJK loop\n",
                cases, hits, worst, worst_gjk);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(hits, cases / 5) << "seed " << seed;
    EXPECT_LT(hits, cases * 4 / 5) << "seed " << seed;
}

// A fuzz_world finding: a tiny ball ended 8e-321 from another (subnormal coordinates), and the
// contact's normal was gap / |gap| with |gap| itself subnormal, rounded to a few bits: 1.8e-4 off
// unit. Distances, intersect axes and casts between cores that far apart or closer, both orders.
TEST(ClosedForms, SubnormalGapsGiveUnitAxes) {
    const Vec3 offsets[] = {{2.4209216646221081e-321, -7.4900351909532976e-321, 3.0582663477573161e-321},
                            {5e-324, 0, 0}, {1e-320, 3e-322, -7e-323}, {1e-310, -1e-311, 4e-312}};
    SphereShape tiny(4.41007095445182e-260 * 1e-70);  // a radius far below the gap: 0 after rounding
    PointShape point;
    SegmentShape seg(1e-322);
    BoxShape box({1e-322, 2e-322, 1e-322});
    const Shape* shapes[] = {&tiny, &point, &seg};
    for (const Vec3& o : offsets)
        for (const Shape* a : shapes)
            for (const Shape* b : {static_cast<const Shape*>(&point), static_cast<const Shape*>(&box)}) {
                const Transform xa = make_transform(o, Quat{}), xb = make_transform({0, 0, 0}, Quat{});
                for (int order = 0; order < 2; ++order) {
                    const DistanceResult r = order == 0 ? gjk_distance(*a, xa, *b, xb, 1e-10, 256)
                                                        : gjk_distance(*b, xb, *a, xa, 1e-10, 256);
                    EXPECT_NEAR(length(r.axis), 1.0, 1e-12) << "offset " << o.x << " order " << order;
                    Vec3 axis{};
                    const bool hit = order == 0 ? gjk_intersect(*a, xa, *b, xb, axis, nullptr)
                                                : gjk_intersect(*b, xb, *a, xa, axis, nullptr);
                    if (!hit) {
                        EXPECT_NEAR(length(axis), 1.0, 1e-12) << "offset " << o.x << " order " << order;
                    }
                }
            }
    // A fuzz finding: a ball of subnormal radius with a point at its centre, neither moving, was a
    // miss (its scale factor overflowed to inf). Both casts, both orders of the shape cast.
    {
        SphereShape sub(1.067154952430554e-315);
        const Transform at0 = make_transform({0, 0, 0}, Quat{});
        EXPECT_TRUE(shape_cast(sub, at0, {0, 0, 0}, point, at0, {0, 0, 0}, 1e-10, 256).hit);
        EXPECT_TRUE(shape_cast(point, at0, {0, 0, 0}, sub, at0, {0, 0, 0}, 1e-10, 256).hit);
        EXPECT_TRUE(ray_cast(sub, at0, {0, 0, 0}, {0, 0, 0}, 1e-10, 256).hit);
        EXPECT_TRUE(ray_cast(sub, at0, {1e-316, 0, 0}, {0, 0, 0}, 1e-10, 256).hit);
        EXPECT_FALSE(ray_cast(sub, at0, {3e-315, 0, 0}, {0, 0, 0}, 1e-10, 256).hit);
    }
    // Casts: a point moving onto a ball across a subnormal gap, and a subnormal motion.
    for (const Vec3& o : offsets) {
        SphereShape ball(1e-321);
        const CastResult c = shape_cast(point, make_transform(4 * o, Quat{}), -8 * o, ball,
                                        make_transform({0, 0, 0}, Quat{}), {0, 0, 0}, 1e-10, 256);
        if (c.hit) {
            EXPECT_NEAR(length(c.normal), 1.0, 1e-12) << "offset " << o.x;
        }
    }
}

// A fuzz finding: a point cast head-on onto a ball 1.6e-250 wide 10 away came back with a normal
// along the motion. The entry point's offset from the centre was formed as s + toi r, whose
// rounding (1e-15 of |s|) was all of it. Head-on and nearly head-on casts onto balls from 1e-250
// to 1e-8 of the distance, point onto ball and ball onto ball, both argument orders, ray casts
// too: the normal is unit and opposes the relative motion, as the true normal at any entry does.
TEST(ClosedForms, TinyBallsMetHeadOnGiveANormalAgainstTheMotion) {
    const uint64_t seed = 131;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    PointShape point;
    int cases = 0, hits = 0, failures = 0;
    for (double ratio : {1e-250, 1e-100, 1e-30, 1e-17, 1e-15, 1e-8}) {
        for (int i = 0; i < 200; ++i) {
            const double far = std::ldexp(1.0, int(u(rng) * 20));
            // Small-integer starts and directions (the fuzz case's was (1, 0, 1) at integers), so
            // the centres' line is exact and its rounding alone decides a hit; random ones too.
            const Vec3 lattice[] = {{1, 0, 1}, {1, 1, 0}, {-1, 1, 1}, {3, 0, -4}, {1, 2, 2}};
            const Vec3 a0 = far * Vec3{std::round(8 * u(rng)), std::round(8 * u(rng)), std::round(8 * u(rng))};
            const Vec3 dir = i % 6 < 5 ? lattice[i % 6] : Vec3{u(rng), u(rng), u(rng)};
            const double gap = far * std::round(1 + 8 * std::fabs(u(rng)));
            SphereShape ball(ratio * gap * length(dir));
            const Vec3 b0 = a0 + gap * dir;
            // A moves toward B, B toward A (sometimes still): they would meet near the middle.
            const double share = i % 4 == 0 ? 1.0 : (i % 4 == 1 ? 0.5 : 0.75);
            const Vec3 ta = 1.25 * share * gap * dir, tb = -1.25 * (1 - share) * gap * dir;
            const Transform xa = make_transform(a0, random_rotation(rng)), xb = make_transform(b0, random_rotation(rng));
            for (int order = 0; order < 2; ++order) {
                const Shape& sa = i % 2 ? static_cast<const Shape&>(point) : static_cast<const Shape&>(ball);
                const CastResult c = order == 0 ? shape_cast(sa, xa, ta, ball, xb, tb, 1e-10, 256)
                                                : shape_cast(ball, xb, tb, sa, xa, ta, 1e-10, 256);
                const Vec3 rel = order == 0 ? tb - ta : ta - tb;  // B's motion relative to A's
                ++cases;
                if (!c.hit) continue;
                ++hits;
                const double along = dot(c.normal, rel) / length(rel);
                if (!(std::fabs(length(c.normal) - 1) <= 1e-12) || !(along < 0)) {
                    if (++failures <= 8)
                        ADD_FAILURE() << "shape cast normal (" << c.normal.x << " " << c.normal.y << " " << c.normal.z
                                      << ") along the relative motion by " << along << "; ratio " << ratio << " case "
                                      << i << " order " << order << " seed " << seed;
                }
            }
            // The ray of A's start along A's motion onto B (still).
            const CastResult r = ray_cast(ball, xb, a0, ta, 1e-10, 256);
            ++cases;
            if (r.hit) {
                ++hits;
                const double along = dot(r.normal, ta) / length(ta);
                if (!(along < 0) && ++failures <= 8)
                    ADD_FAILURE() << "ray cast normal along the ray by " << along << "; ratio " << ratio << " case " << i
                                  << " seed " << seed;
            }
        }
    }
    std::printf("tiny balls head on: %d casts, %d hits\n", cases, hits);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    // A head-on ray misses a ball narrower than its rounding (ratio 1e-17 and below) at times.
    EXPECT_GT(hits, cases / 5) << "seed " << seed;
}

}  // namespace

// A fuzz finding: a ball of radius 1e-15 about 4 units from the start of a head-on cast. The
// closest approach s + m u keeps about eps |s| = 1e-15 along u, as much as the radius, so the entry
// normal could follow the motion instead of opposing it. Random directions and offsets within the
// radius, both shape-cast orders and the ray cast; the normal must oppose the relative motion.
TEST(ClosedForms, TinyBallFarAlongTheMotionGivesAnOpposingNormal) {
    std::mt19937_64 rng(20261127);
    std::uniform_real_distribution<double> unit(-1, 1);
    SphereShape big(1e-15), small(9.6e-300);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        Vec3 u{unit(rng), unit(rng), unit(rng)};
        if (!(dot(u, u) > 0.01)) continue;
        u = u / length(u);
        const Vec3 across = cross(u, Vec3{unit(rng), unit(rng), unit(rng)});
        const double off = 0.9e-15 * std::fabs(unit(rng));
        const Vec3 start = -4.0 * u + (length(across) > 0 ? (off / length(across)) * across : Vec3{});
        const Vec3 r = 61.0 * u;
        const Transform at0 = make_transform({0, 0, 0}, Quat{}), from = make_transform(start, Quat{});
        const CastResult c[3] = {shape_cast(small, from, r, big, at0, {0, 0, 0}, 1e-10, 256),
                                 shape_cast(big, at0, {0, 0, 0}, small, from, r, 1e-10, 256),
                                 ray_cast(big, at0, start, r, 1e-10, 256)};
        // Normal . u: > 0 when A moves onto B (from A toward B), < 0 when B moves onto A and for
        // the ray (outward from the ball).
        const double sign[3] = {-1, 1, 1};
        for (int k = 0; k < 3; ++k) {
            if (!c[k].hit) continue;
            ++hits;
            EXPECT_LE(sign[k] * dot(c[k].normal, u), 1e-6)
                << "case " << i << " query " << k << " normal (" << c[k].normal.x << ", " << c[k].normal.y << ", "
                << c[k].normal.z << ")";
        }
    }
    EXPECT_GT(hits, 3000);  // most of the 3 x ~1900 queries hit: the offsets lie within the radius
}
