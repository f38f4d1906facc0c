// SPDX-License-Identifier: MIT
// Tests of the motion cast (src/motion/motion_cast.hpp) against the conservative-advancement reference of
// tests/support/oracle/motion_reference.hpp and closed forms: random rotating pairs of every kind, spinning
// rods through thin walls, a spinning box grazing a sphere, rotation about a point outside the hull.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "motion_test_support.hpp"

using namespace kairos;
using namespace motion_test;
using cast_test::kAllKinds;
using cast_test::kind_name;

namespace {

constexpr uint32_t kMaxIt = 256;
constexpr double kPi = std::numbers::pi;

struct Tally {
    int cases = 0, undecided = 0, ref_hits = 0, hits = 0, misses = 0, late = 0, far = 0, guards = 0;
    std::vector<double> early, casts, distances, iterations, gaps;
    void add(const Verdict& v, const CastResult& r, const MotionCastStats& s) {
        ++cases;
        undecided += v.undecided;
        if (v.undecided) return;
        ref_hits += v.ref_hit;
        hits += r.hit;
        misses += v.miss;
        late += v.late;
        far += v.far;
        guards += r.hit && r.termination != Termination::Hit;
        if (v.ref_hit && r.hit) early.push_back(v.early);
        if (r.hit) gaps.push_back(v.gap_at_toi);
        casts.push_back(s.casts);
        distances.push_back(s.distances);
        iterations.push_back(r.iterations);
    }
    static double mean(const std::vector<double>& x) {
        double s = 0;
        for (double v : x) s += v;
        return x.empty() ? 0 : s / double(x.size());
    }
    void merge(const Tally& t) {
        cases += t.cases;
        undecided += t.undecided;
        ref_hits += t.ref_hits;
        hits += t.hits;
        misses += t.misses;
        late += t.late;
        far += t.far;
        guards += t.guards;
        for (auto [to, from] : {std::pair{&early, &t.early},
                                {&casts, &t.casts},
                                {&distances, &t.distances},
                                {&iterations, &t.iterations},
                                {&gaps, &t.gaps}})
            to->insert(to->end(), from->begin(), from->end());
    }
    void print(const std::string& name) const {
        std::printf(
            "[%-22s] cases %4d undecided %d ref hits %4d hits %4d misses %d late %d far %d guards %d | early med %.2g "
            "max %.2g | gap max %.2g | casts %.1f (max %.0f) distances %.1f iterations %.1f\n",
            name.c_str(), cases, undecided, ref_hits, hits, misses, late, far, guards, cast_test::median(early),
            cast_test::maximum(early), cast_test::maximum(gaps), mean(casts), cast_test::maximum(casts),
            mean(distances), mean(iterations));
    }
};

// Allowance on the distance at a reported hit beyond the contact distance (relative to the size):
// GJK on curved surfaces stalls near 1e-7 of the size in double precision.
double allowance_for(Kind ka, Kind kb) {
    const bool curved = ka == Kind::Cylinder || ka == Kind::Cone || kb == Kind::Cylinder || kb == Kind::Cone ||
                        ka == Kind::Sphere || kb == Kind::Sphere || ka == Kind::Capsule || kb == Kind::Capsule;
    return curved ? 1e-6 : 1e-11;
}

// count random cases of ka against kb; every failure prints its seed and trial.
Tally run_pair(uint64_t seed, Kind ka, Kind kb, int count, double tolerance, const CaseShape& cs) {
    std::mt19937_64 rng(seed);
    Tally t;
    for (int i = 0; i < count; ++i) {
        const Solid a = cast_test::random_solid(rng, ka), b = cast_test::random_solid(rng, kb);
        const MotionCase c = random_case(rng, a, b, cs);
        const motion_ref::Pair p = reference_pair(a, b, c);
        const auto ref = p.first_contact();
        MotionCastStats st;
        const CastResult r =
            motion_cast(*a.shape, Motion(c.a0, c.a1), *b.shape, Motion(c.b0, c.b1), tolerance, kMaxIt, &st);
        const double delta = contact_distance(*a.shape, *b.shape, tolerance);
        const Verdict v = judge(p, ref, r, tolerance, delta, allowance_for(ka, kb));
        t.add(v, r, st);
        const bool bad = v.miss || v.late || v.far || std::isnan(v.gap_at_toi) || !std::isfinite(r.toi) || r.toi < 0 ||
                         r.toi > 1 || (r.hit && (!is_finite(r.point) || std::fabs(length(r.normal) - 1) > 1e-9));
        if (bad) {
            ADD_FAILURE() << kind_name(ka) << "/" << kind_name(kb) << " seed " << seed << " trial " << i << " tol "
                          << tolerance << ": ref hit " << ref.hit << " toi " << double(ref.toi) << " min d "
                          << double(ref.min_distance) << " | cast hit " << r.hit << " toi " << r.toi << " termination "
                          << int(r.termination) << " gap " << v.gap_at_toi << " delta " << delta << " casts "
                          << st.casts;
        }
    }
    return t;
}

}  // namespace

namespace {

// Every pair of kinds, with and without translation, rotations up to 1.5 pi (the shortest arc is
// taken), end quaternions negated half of the time.
Tally every_kind(uint64_t seed, int per_pair, double tolerance) {
    Tally all;
    CaseShape cs;
    int k = 0;
    for (Kind ka : kAllKinds)
        for (Kind kb : kAllKinds) {
            ++k;
            cs.translate = (k % 2) == 0;
            all.merge(run_pair(seed + k, ka, kb, per_pair, tolerance, cs));
        }
    return all;
}

void expect_sound(const Tally& t) {
    EXPECT_EQ(t.undecided, 0);
    EXPECT_EQ(t.misses, 0);
    EXPECT_EQ(t.late, 0);
    EXPECT_EQ(t.far, 0);
    // The cases are meaningful: the reference hits in a fair share of them.
    EXPECT_GT(t.ref_hits, t.cases / 5);
    EXPECT_LT(t.ref_hits, t.cases * 4 / 5);
}

}  // namespace

TEST(MotionCast, RandomPairsEveryKindDefaultTolerance) {
    const Tally t = every_kind(20240601, 10, 1e-10);
    t.print("every kind, 1e-10");
    expect_sound(t);
}

TEST(MotionCast, RandomPairsEveryKindCoarseTolerance) {
    const Tally t = every_kind(20240701, 10, 1e-3);
    t.print("every kind, 1e-3");
    expect_sound(t);
}

// Conservative, and converging to the reference as the tolerance shrinks: the median and the
// 90th percentile of (reference - toi) fall with the tolerance.
TEST(MotionCast, ConvergesAsToleranceShrinks) {
    const uint64_t seed = 99;
    double last_median = INFINITY, last_p90 = INFINITY;
    for (double tol : {1e-2, 1e-4, 1e-6, 1e-9}) {
        Tally all;
        CaseShape cs;
        int k = 0;
        for (Kind ka : {Kind::Box, Kind::Hull, Kind::Capsule, Kind::Segment, Kind::Sphere})
            for (Kind kb : {Kind::Box, Kind::Hull, Kind::Sphere}) {
                cs.translate = (++k % 2) == 0;
                all.merge(run_pair(seed + k, ka, kb, 8, tol, cs));
            }
        all.print("converge " + std::to_string(tol));
        expect_sound(all);
        std::vector<double> e = all.early;
        std::sort(e.begin(), e.end());
        ASSERT_FALSE(e.empty());
        const double med = e[e.size() / 2], p90 = e[e.size() * 9 / 10];
        EXPECT_GE(e.front(), -tol) << "seed " << seed;
        EXPECT_LE(med, last_median) << tol;
        EXPECT_LE(p90, last_p90) << tol;
        last_median = med;
        last_p90 = p90;
    }
    EXPECT_LT(last_median, 1e-8);
    EXPECT_LT(last_p90, 1e-6);
}

// The advancement near contact: over a span the separation along the distance's axis is bounded
// below by a concave function of the span (Body::support_bound), and the step is the longest span
// it proves, found by chords (the first-order bound alone, rho * angle per body, crawls in steps
// of the distance over that speed). Turning pairs with no translation that meet after the start,
// where only these bounds move t0: the distance queries per cast (one per step) must stay well
// under what a ladder of spans a factor 4 apart, longest first, took on this set (mean 55.5,
// largest 549; the chords: 31.4 and 285).
TEST(MotionCast, SecondOrderStepsTakeTheLongestProvenSpan) {
    const double tol = 1e-9;
    CaseShape cs;
    cs.translate = false;
    cs.max_angle = kPi / 2;
    cs.gap_lo = 0.55;  // near enough for many cases to hit, as in bench_motion_cast
    cs.gap_hi = 1.0;
    std::vector<double> queries;
    uint64_t seed = 7100;
    for (auto [ka, kb] : {std::pair{Kind::Box, Kind::Box},
                          {Kind::Hull, Kind::Hull},
                          {Kind::Capsule, Kind::Box},
                          {Kind::Cylinder, Kind::Cone},
                          {Kind::Segment, Kind::Hull}}) {
        std::mt19937_64 rng(++seed);
        int found = 0;
        for (int trial = 0; found < 16 && trial < 1000; ++trial) {
            const Solid a = cast_test::random_solid(rng, ka), b = cast_test::random_solid(rng, kb);
            const MotionCase c = random_case(rng, a, b, cs);
            const motion_ref::Pair p = reference_pair(a, b, c);
            const auto ref = p.first_contact();
            if (!ref.decided || !ref.hit || ref.toi == 0) continue;
            ++found;
            MotionCastStats st;
            const CastResult r =
                motion_cast(*a.shape, Motion(c.a0, c.a1), *b.shape, Motion(c.b0, c.b1), tol, kMaxIt, &st);
            const Verdict v = judge(p, ref, r, tol, contact_distance(*a.shape, *b.shape, tol), allowance_for(ka, kb));
            EXPECT_TRUE(r.hit && !v.late && !v.far)
                << kind_name(ka) << "/" << kind_name(kb) << " seed " << seed << " trial " << trial;
            queries.push_back(st.distances);
        }
        EXPECT_EQ(found, 16) << kind_name(ka) << "/" << kind_name(kb) << " seed " << seed;
    }
    std::sort(queries.begin(), queries.end());
    std::printf("distance queries per cast: mean %.2f, median %.0f, largest %.0f over %zu casts\n",
                Tally::mean(queries), queries[queries.size() / 2], queries.back(), queries.size());
    EXPECT_LT(Tally::mean(queries), 40);
    EXPECT_LT(queries.back(), 400);
}

// ---- Closed forms --------------------------------------------------------------------------------

namespace {

Pose state(Vec3 p, Quat q = {}) { return {p, q}; }
Quat about_z(double angle) { return {0, 0, std::sin(0.5 * angle), std::cos(0.5 * angle)}; }

}  // namespace

// A rod (segment of half length h, or capsule of radius r) spinning about its centre (z axis) from
// along y toward x, against a wall whose face is the plane x = D: the tip reaches it when
// h cos(phi) + r = D with phi = pi/2 - alpha t, so t* = (pi/2 - acos((D - r) / h)) / alpha.
TEST(MotionCast, SpinningRodAgainstWallClosedForm) {
    int hits = 0, cases = 0;
    for (double radius : {0.0, 0.05})
        for (double h : {0.5, 1.0, 3.0})
            for (double ratio : {0.1, 0.5, 0.9, 0.999})
                for (double alpha : {0.5, 2.0, kPi * 0.999, kPi}) {
                    const double D = radius + ratio * h;
                    const double t_star = (kPi / 2 - std::acos((D - radius) / h)) / alpha;
                    SphereShape unused(1);
                    Shape* rod = radius > 0 ? static_cast<Shape*>(new CapsuleShape(radius, h)) : new SegmentShape(h);
                    const BoxShape wall({0.05, 50, 50});
                    // Local z of the rod along world y at the start: rotate -pi/2 about x.
                    const Quat to_y{-std::sin(kPi / 4), 0, 0, std::cos(kPi / 4)};
                    const Quat start = to_y;
                    // Spin about world z by -alpha (from +y toward +x).
                    const Quat end = normalized(about_z(-alpha) * to_y);
                    const Motion ma(state({0, 0, 0}, start), state({0, 0, 0}, end));
                    const Motion mb(state({D + 0.05, 0, 0}), state({D + 0.05, 0, 0}));
                    for (double tol : {1e-3, 1e-10}) {
                        ++cases;
                        const CastResult r = motion_cast(*rod, ma, wall, mb, tol, kMaxIt);
                        SCOPED_TRACE(::testing::Message()
                                     << "h " << h << " D " << D << " alpha " << alpha << " tol " << tol);
                        if (t_star <= 1) {
                            ASSERT_TRUE(r.hit);
                            ++hits;
                            EXPECT_LE(r.toi, t_star + tol);
                            // Early by at most the contact distance over the tip's approach speed.
                            const double speed = alpha * h * std::sin(std::acos((D - radius) / h));
                            EXPECT_GE(r.toi, t_star - 2 * contact_distance(*rod, wall, tol) / speed - 1e-12);
                            EXPECT_NEAR(r.normal.x, 1, 1e-6);
                        } else if (D - radius - h * std::sin(alpha) > contact_distance(*rod, wall, tol)) {
                            EXPECT_FALSE(r.hit) << r.toi;  // the tip stops short of the wall
                        }
                    }
                    rod->release();
                }
    EXPECT_GT(hits, cases / 3);
}

// A thin rod turning by pi per step through a thin wall: start and end poses are the same set (a
// segment turned by pi), and translation-only casts see nothing; the motion cast must hit.
TEST(MotionCast, ThinRodsTunnelThroughThinWalls) {
    std::mt19937_64 rng(4242);
    std::uniform_real_distribution<double> u(0, 1);
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        SCOPED_TRACE(::testing::Message() << "seed 4242 trial " << i);
        const double h = 0.5 + 2 * u(rng);
        const SegmentShape rod(h);
        const double thickness = 1e-3 * (1 + 9 * u(rng));
        const BoxShape wall({thickness, 20, 20});
        const double D = h * (0.05 + 0.9 * u(rng));  // the wall cuts the rod's circle
        const double angle = kPi * (0.9 + 0.1 * u(rng)) * (u(rng) < 0.5 ? 1 : -1);
        const Quat to_y{-std::sin(kPi / 4), 0, 0, std::cos(kPi / 4)};
        const Quat end = normalized(about_z(angle) * to_y);
        const Vec3 slide{0, 0.1 * (u(rng) - 0.5), 0.1 * (u(rng) - 0.5)};
        const Motion ma(state({0, 0, 0}, to_y),
                        state(slide, u(rng) < 0.5 ? end : Quat{-end.x, -end.y, -end.z, -end.w}));
        const Motion mb(state({D + thickness, 0, 0}), state({D + thickness, 0, 0}));
        // Translation only (the two end poses): no hit.
        const CastResult lin = shape_cast(rod, make_transform({0, 0, 0}, to_y), slide, wall,
                                          make_transform({D + thickness, 0, 0}, {}), {}, 1e-10, kMaxIt);
        EXPECT_FALSE(lin.hit);
        const CastResult r = motion_cast(rod, ma, wall, mb, 1e-10, kMaxIt);
        ASSERT_TRUE(r.hit);
        ++hits;
        // The tip (or the slide) brings the rod to the wall's face; the reference decides when.
        const auto p = motion_ref::Pair(
            rod,
            [&] {
                auto b = cast_oracle::make_body(Kind::Segment);
                b.half = h;
                cast_oracle::finish_body(b);
                return b;
            }(),
            ma.start(), ma.end(), wall,
            [&] {
                auto b = cast_oracle::make_body(Kind::Box);
                b.half_extents = {thickness, 20, 20};
                cast_oracle::finish_body(b);
                return b;
            }(),
            mb.start(), mb.end());
        const auto ref = p.first_contact();
        ASSERT_TRUE(ref.hit);
        EXPECT_LE(r.toi, double(ref.toi) + 1e-10);
        EXPECT_LE(double(p.distance(r.toi)), contact_distance(rod, wall, 1e-10) + 1e-12);
    }
    EXPECT_EQ(hits, 200);
}

// A box spinning by pi per step about its z axis, and a sphere just outside (miss) or just inside
// (hit) the circle swept by its vertical edges. Closed form of the hit: the edge at radius rho
// reaches the sphere (centre at distance c from the axis, radius r) at angle acos((rho^2 + c^2 -
// r^2) / (2 rho c)) before the sphere's direction.
TEST(MotionCast, FastSpinningBoxGrazesSphere) {
    const Vec3 he{1.0, 0.3, 0.5};
    const BoxShape box(he);
    const double rho = std::hypot(he.x, he.y);
    const double r = 0.2;
    const SphereShape ball(r);
    const double edge_angle = std::atan2(he.y, he.x);  // the edge's angle at the start
    for (double gap : {1e-2, 1e-4, 1e-6, -1e-6, -1e-4, -1e-2}) {
        for (double tol : {1e-3, 1e-6, 1e-10}) {
            SCOPED_TRACE(::testing::Message() << "gap " << gap << " tol " << tol);
            const double c = rho + r + gap;
            // The sphere at angle edge_angle + 2 (radians ahead of the edge, which turns by pi).
            const double ang = edge_angle + 2.0;
            const Vec3 centre{c * std::cos(ang), c * std::sin(ang), 0};
            const Motion ma(state({0, 0, 0}), state({0, 0, 0}, about_z(kPi)));
            const Motion mb(state(centre), state(centre));
            MotionCastStats st;
            const CastResult res = motion_cast(box, ma, ball, mb, tol, kMaxIt, &st);
            const double delta = contact_distance(box, ball, tol);
            if (gap > delta) {
                EXPECT_FALSE(res.hit) << res.toi;
            } else if (gap < 0) {
                ASSERT_TRUE(res.hit);
                const double meet = std::acos((rho * rho + c * c - r * r) / (2 * rho * c));
                const double t_star = (2.0 - meet) / kPi;
                EXPECT_LE(res.toi, t_star + tol);
                EXPECT_GE(res.toi, t_star - 1e-2);
            }
            EXPECT_LT(st.steps, kMaxMotionSteps);
            std::printf("[grazing] gap %8.1e tol %6.0e: hit %d toi %.9f steps %u casts %u distances %u\n", gap, tol,
                        res.hit, res.toi, st.steps, st.casts, st.distances);
        }
    }
}

// Pure rotation about a point outside the shape's hull: a box whose local origin lies 3 units
// from it (a hammer head on an invisible handle) swings about that origin into a target.
TEST(MotionCast, PureRotationAboutPointOutsideHull) {
    const BoxShape head({0.3, 0.2, 0.2});
    Mat3 identity;
    const TransformedShape hammer(head, identity, {3, 0, 0});
    std::vector<Vec3> corners;
    for (int i = 0; i < 8; ++i) corners.push_back({3 + (i & 1 ? 0.3 : -0.3), i & 2 ? 0.2 : -0.2, i & 4 ? 0.2 : -0.2});
    auto body = cast_oracle::make_body(Kind::Hull);
    for (const Vec3& v : corners) body.verts.push_back({v.x, v.y, v.z});
    cast_oracle::finish_body(body);
    auto target_body = cast_oracle::make_body(Kind::Box);
    target_body.half_extents = {0.25, 0.25, 0.25};
    cast_oracle::finish_body(target_body);
    const BoxShape target({0.25, 0.25, 0.25});
    std::mt19937_64 rng(31337);
    std::uniform_real_distribution<double> u(0, 1);
    int hits = 0;
    for (int i = 0; i < 100; ++i) {
        SCOPED_TRACE(::testing::Message() << "seed 31337 trial " << i);
        // The target on the circle of radius 3 ahead of the head, sometimes off it.
        const double at = 0.3 + 2.5 * u(rng);
        const double off = (u(rng) - 0.5) * 1.6;
        const Vec3 tp{(3 + off) * std::cos(at), (3 + off) * std::sin(at), (u(rng) - 0.5) * 0.5};
        const double swing = kPi * u(rng);
        const Motion ma(state({0, 0, 0}), state({0, 0, 0}, about_z(swing)));
        const Motion mb(state(tp), state(tp));
        const auto p = motion_ref::Pair(hammer, body, ma.start(), ma.end(), target, target_body, mb.start(), mb.end());
        const auto ref = p.first_contact();
        ASSERT_TRUE(ref.decided);
        const CastResult r = motion_cast(hammer, ma, target, mb, 1e-10, kMaxIt);
        if (ref.hit) {
            ASSERT_TRUE(r.hit);
            ++hits;
            EXPECT_LE(r.toi, double(ref.toi) + 1e-10);
        }
        if (r.hit) {
            EXPECT_LE(double(p.distance(r.toi)), contact_distance(hammer, target, 1e-10) + 1e-12);
        }
    }
    EXPECT_GT(hits, 20);
    EXPECT_LT(hits, 90);
}

// ---- Special motions -----------------------------------------------------------------------------

// Equal orientations (q and -q included) are a pure translation: exactly shape_cast's answer.
TEST(MotionCast, PureTranslationIsTheShapeCast) {
    std::mt19937_64 rng(5);
    for (int i = 0; i < 100; ++i) {
        const Solid a = cast_test::random_solid(rng, Kind::Box), b = cast_test::random_solid(rng, Kind::Hull);
        CaseShape cs;
        cs.max_angle = 0;
        MotionCase c = random_case(rng, a, b, cs);
        c.a1.orientation = c.a0.orientation;
        c.b1.orientation = {-c.b0.orientation.x, -c.b0.orientation.y, -c.b0.orientation.z, -c.b0.orientation.w};
        MotionCastStats st;
        const CastResult r =
            motion_cast(*a.shape, Motion(c.a0, c.a1), *b.shape, Motion(c.b0, c.b1), 1e-10, kMaxIt, &st);
        const CastResult s = shape_cast(
            *a.shape, make_transform(c.a0.position, c.a0.orientation), c.a1.position - c.a0.position, *b.shape,
            make_transform(c.b0.position, c.b0.orientation), c.b1.position - c.b0.position, 1e-10, kMaxIt);
        EXPECT_EQ(r.hit, s.hit);
        EXPECT_EQ(r.toi, s.toi);
        EXPECT_EQ(st.casts, 1u);
        EXPECT_EQ(st.distances, 0u);
    }
}

// Tiny rotations (1e-12 rad) and rotations of exactly pi: sound, and bounded work.
TEST(MotionCast, TinyAndHalfTurnRotations) {
    std::mt19937_64 rng(6);
    Tally t;
    for (double angle : {1e-12, 1e-9, kPi}) {
        for (int i = 0; i < 40; ++i) {
            const Kind ka = kAllKinds[i % 8], kb = kAllKinds[(i / 8 + 3) % 8];
            const Solid a = cast_test::random_solid(rng, ka), b = cast_test::random_solid(rng, kb);
            CaseShape cs;
            cs.max_angle = 0;
            MotionCase c = random_case(rng, a, b, cs);
            c.a1.orientation = turn(c.a0.orientation, cast_test::random_unit(rng), angle);
            const motion_ref::Pair p = reference_pair(a, b, c);
            const auto ref = p.first_contact();
            MotionCastStats st;
            const CastResult r =
                motion_cast(*a.shape, Motion(c.a0, c.a1), *b.shape, Motion(c.b0, c.b1), 1e-10, kMaxIt, &st);
            const Verdict v =
                judge(p, ref, r, 1e-10, contact_distance(*a.shape, *b.shape, 1e-10), allowance_for(ka, kb));
            t.add(v, r, st);
            EXPECT_FALSE(v.miss || v.late || v.far)
                << "seed 6 angle " << angle << " trial " << i << " " << kind_name(ka) << "/" << kind_name(kb) << " ref "
                << double(ref.toi) << " cast " << r.hit << " " << r.toi << " termination " << int(r.termination);
            EXPECT_LT(st.steps, 200u) << "angle " << angle << " trial " << i;
        }
    }
    t.print("tiny and half turns");
}

// Any finite input ends: points (zero extent), huge and tiny scales, far from the origin, NaN
// tolerance; the answers stay conservative.
TEST(MotionCast, DegenerateInputsTerminate) {
    const PointShape point;
    const SphereShape unit(1);
    const Motion spin(state({0, 0, 0}), state({0, 0, 0}, about_z(3)));
    const Motion toward(state({3, 0, 0}), state({-3, 0, 0}, about_z(-2)));
    for (double tol : {std::nan(""), 0.0, -1.0, 1e-300, 0.9, 1.0}) {
        const CastResult r = motion_cast(point, spin, unit, toward, tol, kMaxIt);
        EXPECT_TRUE(r.hit);
        EXPECT_LE(r.toi, 1 / 3.0 + 1e-6);  // the point at the origin meets the sphere at t = 1/3
        const CastResult q = motion_cast(point, spin, point, toward, tol, kMaxIt);
        EXPECT_TRUE(std::isfinite(q.toi));
    }
    // Far from the origin, huge and tiny scales.
    for (double scale : {1e-6, 1.0, 1e6}) {
        for (double far : {0.0, 1e6}) {
            const BoxShape box({scale, 0.1 * scale, 0.1 * scale});
            const Vec3 base{far, -far, far};
            const Motion ma(state(base), state(base, about_z(kPi)));
            const Motion mb(state(base + Vec3{0, 0.8 * scale, 0}), state(base + Vec3{0, 0.8 * scale, 0}));
            MotionCastStats st;
            const CastResult r = motion_cast(box, ma, unit, mb, 1e-10, kMaxIt, &st);
            EXPECT_TRUE(std::isfinite(r.toi));
            EXPECT_LT(st.steps, kMaxMotionSteps);
            if (scale == 1.0) {
                EXPECT_TRUE(r.hit) << far;
            }
        }
    }
    // max_iterations 0 and 1: still terminates, conservative.
    for (uint32_t it : {0u, 1u, 3u}) {
        const CastResult r = motion_cast(unit, spin, unit, toward, 1e-10, it);
        EXPECT_TRUE(std::isfinite(r.toi));
        if (r.hit) {
            EXPECT_LE(r.toi, 1 / 6.0 + 1e-9);
        }
    }
}

// ---- The long run (disabled; run with --gtest_also_run_disabled_tests) -----------------------------

TEST(MotionCastLong, DISABLED_HundredThousandRotatingCasts) {
    const char* env = std::getenv("KAIROS_MOTION_LONG_COUNT");
    const int per_pair = env ? std::atoi(env) : 1600;  // 64 pairs of kinds
    for (double tol : {1e-10}) {
        Tally all;
        CaseShape cs;
        int k = 0;
        for (Kind ka : kAllKinds)
            for (Kind kb : kAllKinds) {
                ++k;
                cs.translate = (k % 2) == 0;
                all.merge(run_pair(7000000 + k, ka, kb, per_pair, tol, cs));
            }
        all.print("long run " + std::to_string(tol));
        std::vector<double> e = all.early;
        std::sort(e.begin(), e.end());
        if (!e.empty())
            std::printf("early: min %.3g median %.3g p99 %.3g max %.3g (n %zu)\n", e.front(), e[e.size() / 2],
                        e[e.size() * 99 / 100], e.back(), e.size());
        EXPECT_EQ(all.misses, 0);
        EXPECT_EQ(all.late, 0);
        EXPECT_EQ(all.far, 0);
    }
}

// A fuzz finding: tolerance * min(rA, rB) underflowed to 0 for a segment 5e-324 long against a
// ball, and the translation-only path then cast at the caller's tolerance 0.5, relative to the
// reach: a hit 1e-3 short of contact. Tiny and subnormal shapes against a unit ball at coarse
// tolerances, orientations equal at both ends (q to -q included): the distance at toi is within
// tolerance * min(rA, rB) plus rounding.
TEST(MotionCast, AContactDistanceThatUnderflowsIsExact) {
    SphereShape ball(1);
    const Quat q = normalized(Quat{-0.45685833960288719, -0.036867058988877571, 0.72938138426138655, 0.50786403080997722});
    const Quat minus_q{-q.x, -q.y, -q.z, -q.w};
    for (double h : {4.9406564584124654e-324, 1e-310, 1e-300})
        for (double tolerance : {0.5, 0.1, 1e-3}) {
            SegmentShape seg(h);
            const Vec3 a0{-1.2187075608453499, -1.2078431372549021, -1.2078431372549021};
            const Motion ma(state(a0, q), state(a0, minus_q));
            const Motion mb(state({0, 0, 0}), state({-1.2757656214236668, -1.2078431372549021, -1.2078431372549021}));
            const CastResult c = motion_cast(seg, ma, ball, mb, tolerance, 256);
            ASSERT_TRUE(c.hit) << "h " << h << " tolerance " << tolerance;
            const Pose pb = mb.at(c.toi);
            const double gap = length(pb.position - a0) - 1;
            EXPECT_LE(gap, 1e-9) << "h " << h << " tolerance " << tolerance << " toi " << c.toi;
            EXPECT_GE(gap, -1e-9) << "h " << h << " tolerance " << tolerance << " toi " << c.toi;
        }
}
