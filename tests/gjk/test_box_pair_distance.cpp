// SPDX-License-Identifier: MIT
// The distance of two boxes by the separating axis test with witness points (gjk/box_pair_distance),
// against the long double polytope oracle (brute force over the boxes' vertices, no supports):
// random pairs of cubes, needles and slabs at gaps from 1e-12 to 1 of the size, turned at random,
// up to 1e4 sizes from the origin, sizes 1e-120 to 1e120, both argument orders; boxes resting on boxes
// (faces parallel, or tilted by 1e-12 to 1e-3 rad) at the same gaps; and the pairs it must leave
// to the GJK loop (overlapping, touching).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "gjk/box_pair_distance.hpp"
#include "gjk/gjk.hpp"
#include "gjk_test_support.hpp"

using namespace kairos;
using namespace gjk_test;

namespace {

constexpr double kEps = 2.220446049250313e-16;
constexpr double kTol = 1e-10;

// Whether the closed form answers the pair itself (else gjk_distance runs the loop).
bool closed_form_answers(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb) {
    gjk_detail::LocalDistance l;
    Vec3 offset;
    return gjk_detail::box_pair_distance(kernels::classify(a), pa, kernels::classify(b), pb, l, offset);
}

struct Errors {
    int pairs = 0, closed = 0, touching = 0;
    double worst_closed = 0, worst = 0;  // |distance - oracle| / reach
};

// One pair in both orders against the oracle: the distance, the witness points (their distance is
// the answer's, each on its box), the axes opposite.
void check_pair(Vec3 ha, const Transform& pa, Vec3 hb, const Transform& pb, const char* what, Errors& e) {
    const BoxShape a(ha), b(hb);
    const oracle::Polytope oa = world_polytope(box_vertices(ha), pa), ob = world_polytope(box_vertices(hb), pb);
    const oracle::Result o = oracle::distance(oa, ob);
    if (o.intersecting) {  // a gap of 1e-12 placed by a loop at 1e-14 can come out as a touch
        ++e.touching;
        return;
    }
    const double truth = static_cast<double>(o.distance);
    const double size = length(ha) + length(hb);
    const double reach = size + length(pb.translation - pa.translation);
    const double world = reach + length(pa.translation);
    const DistanceResult r = gjk_distance(a, pa, b, pb, kTol, 256);
    const DistanceResult s = gjk_distance(b, pb, a, pa, kTol, 256);
    const bool closed = closed_form_answers(a, pa, b, pb);
    ++e.pairs;
    e.closed += closed;
    const double err = std::fabs(r.distance - truth) / reach;
    e.worst = std::max(e.worst, err);
    if (closed) {
        e.worst_closed = std::max(e.worst_closed, err);
        EXPECT_EQ(r.iterations, 1u) << what;
        // Exact to the rounding of the coordinates, whatever the gap.
        EXPECT_LE(std::fabs(r.distance - truth), 128 * kEps * reach) << what << ": truth " << truth;
    } else {
        EXPECT_LE(std::fabs(r.distance - truth), kTol * truth + 128 * kEps * reach) << what << ": truth " << truth;
    }
    EXPECT_FALSE(r.intersecting) << what;
    EXPECT_NEAR(s.distance, r.distance, kTol * truth + 128 * kEps * reach) << what << ": the swapped order";
    EXPECT_NEAR(length(r.point_b - r.point_a), r.distance, 64 * kEps * world + kTol * truth) << what;
    EXPECT_LE(static_cast<double>(oracle::plane_excess(oa, to_p3(r.point_a))), 64 * kEps * world) << what;
    EXPECT_LE(static_cast<double>(oracle::plane_excess(ob, to_p3(r.point_b))), 64 * kEps * world) << what;
    if (truth > 1e-9 * size) {
        EXPECT_LE(dot(r.axis, s.axis), -1 + 1e-9) << what << ": the axes";
    }
}

// B moved toward A along the distance's axis so that the gap becomes `gap` (a translation along
// the closest points' direction shortens the distance by its length, while it stays positive).
Transform at_gap(const BoxShape& a, const Transform& pa, const BoxShape& b, Transform pb, double gap) {
    const DistanceResult d = gjk_distance(a, pa, b, pb, 1e-14, 256);
    pb.translation = pb.translation - (d.distance - gap) * d.axis;
    return pb;
}

}  // namespace

TEST(BoxPairDistance, RandomCubesNeedlesAndSlabsAgainstTheOracle) {
    const uint64_t seed = 57011;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.5, 1.5);
    Errors e;
    const Vec3 forms[3] = {{1, 1, 1}, {3, 0.02, 0.03}, {1.5, 1.2, 0.01}};  // cube, needle, slab
    for (double scale : {1e-120, 1e-3, 1.0, 1e3, 1e120})
        for (double far : {0.0, 1e4})
            for (double gap : {1e-12, 1e-9, 1e-6, 1e-3, 0.1, 1.0})
                for (int i = 0; i < 12; ++i) {
                    const Vec3 fa = forms[i % 3], fb = forms[(i / 3) % 3];
                    const Vec3 ha = scale * Vec3{fa.x * u(rng), fa.y * u(rng), fa.z * u(rng)};
                    const Vec3 hb = scale * Vec3{fb.x * u(rng), fb.y * u(rng), fb.z * u(rng)};
                    const BoxShape a(ha), b(hb);
                    const Transform pa = make_transform(far * scale * random_unit(rng), random_quat(rng));
                    Transform pb = make_transform(pa.translation + 4 * scale * random_unit(rng), random_quat(rng));
                    pb = at_gap(a, pa, b, pb, gap * scale);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g gap %g case %d",
                                  static_cast<unsigned long long>(seed), scale, far, gap, i);
                    check_pair(ha, pa, hb, pb, what, e);
                }
    std::printf(
        "[box pairs] %d pairs, %d answered by the closed form; worst error %.2g of the reach (closed form %.2g)\n",
        e.pairs, e.closed, e.worst, e.worst_closed);
    // Random pairs: a vertex over a face or two crossing edges is the rule, a vertex by an edge the
    // exception.
    EXPECT_GT(e.closed, 4 * e.pairs / 10);
    EXPECT_LT(e.closed, e.pairs);
    EXPECT_LT(e.touching, 10);
    // Boxes 1e-3 in size 10 from the origin carry the world coordinates' rounding (42 eps of the
    // reach measured); near the origin the answers are within 2 eps.
    EXPECT_LT(e.worst_closed, 64 * kEps);
}

// A box resting on a box: faces parallel, or tilted by 1e-12 to 1e-3 rad about a random horizontal
// axis, B off A's centre by up to half A's width, at gaps 1e-12 to 1e-2 of the size (the case where
// GJK answered 1e5 times off, in version 0.1).
TEST(BoxPairDistance, BoxesRestingOnBoxesAtGapsFromOneEMinusTwelve) {
    const uint64_t seed = 57012;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> off(-0.5, 0.5), turn(0, 6.283185307179586);
    Errors e;
    const Vec3 ha{1, 0.5, 0.3}, hb{0.4, 0.6, 0.2};
    for (double far : {0.0, 1e4})
        for (double tilt : {0.0, 1e-12, 1e-9, 1e-6, 1e-3})
            for (double gap : {1e-12, 1e-9, 1e-6, 1e-3, 1e-2})
                for (int i = 0; i < 6; ++i) {
                    const Quat qa = random_quat(rng);
                    const double phi = turn(rng);
                    const Quat qb =
                        qa * axis_angle({std::cos(phi), std::sin(phi), 0}, tilt) * axis_angle({0, 0, 1}, turn(rng));
                    const Transform pa = make_transform(far * random_unit(rng), qa);
                    // B's lowest point over A's top face, `gap` above it.
                    const BoxShape b(hb);
                    Transform pb = make_transform({0, 0, 0}, qb);
                    const Vec3 up = pa.rotation * Vec3{0, 0, 1};
                    const double low = dot(up, support(b, pb, -1.0 * up));
                    const Vec3 local{off(rng) * ha.x, off(rng) * ha.y, ha.z + gap - low};
                    pb.translation = pa.apply(local);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu far %g tilt %g gap %g case %d",
                                  static_cast<unsigned long long>(seed), far, tilt, gap, i);
                    check_pair(ha, pa, hb, pb, what, e);
                }
    std::printf(
        "[resting boxes] %d pairs, %d answered by the closed form; worst error %.2g of the reach (closed form %.2g)\n",
        e.pairs, e.closed, e.worst, e.worst_closed);
    EXPECT_GT(e.closed, e.pairs / 2);
    // Exact: a few eps of the reach (an incident edge taken as parallel to the face within 64 eps
    // of the reach, not 4, put 9.3e-15 here).
    EXPECT_LT(e.worst_closed, 4 * kEps);
}

// Overlapping boxes are the loop's (its conventions for contact); boxes touching to the placement's
// rounding are the loop's or answered exactly.
TEST(BoxPairDistance, OverlappingAndTouchingBoxesAreLeftToTheLoop) {
    const uint64_t seed = 57013;
    std::mt19937_64 rng(seed);
    int cases = 0, touching_closed = 0;
    for (double gap : {-0.3, -1e-6, 0.0}) {
        for (int i = 0; i < 40; ++i) {
            const BoxShape a({1, 0.7, 0.4}), b({0.5, 0.9, 0.3});
            const Transform pa = make_transform((i % 2 ? 1e4 : 0.0) * random_unit(rng), random_quat(rng));
            Transform pb = make_transform(pa.translation + 4 * random_unit(rng), random_quat(rng));
            if (gap == 0) {
                pb = at_gap(a, pa, b, pb, 0);
            } else {
                const DistanceResult d = gjk_distance(a, pa, b, pb, 1e-14, 256);
                pb.translation = pb.translation - (d.distance - gap) * d.axis;
            }
            ++cases;
            if (gap < 0) {
                EXPECT_FALSE(closed_form_answers(a, pa, b, pb)) << "gap " << gap << " case " << i;
                EXPECT_FALSE(closed_form_answers(b, pb, a, pa)) << "gap " << gap << " case " << i << ": swapped";
                EXPECT_TRUE(gjk_distance(a, pa, b, pb, kTol, 256).intersecting) << "gap " << gap << " case " << i;
                continue;
            }
            // Touching, as far as a loop at 1e-14 placed it (a residual gap of up to 1e-13): either
            // left to the loop, or answered exactly.
            const oracle::Result o = oracle::distance(world_polytope(box_vertices(a.half_extents), pa),
                                                      world_polytope(box_vertices(b.half_extents), pb));
            const double reach =
                length(a.half_extents) + length(b.half_extents) + length(pb.translation - pa.translation);
            for (int order = 0; order < 2; ++order) {
                const bool closed = order ? closed_form_answers(b, pb, a, pa) : closed_form_answers(a, pa, b, pb);
                touching_closed += closed;
                const DistanceResult r =
                    order ? gjk_distance(b, pb, a, pa, kTol, 256) : gjk_distance(a, pa, b, pb, kTol, 256);
                if (closed) {
                    EXPECT_NEAR(r.distance, static_cast<double>(o.distance), 128 * kEps * reach)
                        << "touching, case " << i << " order " << order;
                }
            }
        }
    }
    EXPECT_EQ(cases, 120);
    std::printf("[touching boxes] %d of 80 answered by the closed form\n", touching_closed);
}
