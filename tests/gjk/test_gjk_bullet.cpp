// SPDX-License-Identifier: MIT
// Cross-check of Kairos GJK distance against Bullet's double-precision btGjkPairDetector (the
// best distance reference among the peers). Its own executable: Bullet's float and double builds
// export the same symbols. Disagreements are arbitrated by independent certificates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include "gjk/gjk.hpp"
#include "gjk_peer_bullet.hpp"
#include "gjk_peer_shapes.hpp"

static_assert(sizeof(btScalar) == sizeof(double), "this test needs Bullet's double-precision build");

using namespace kairos;
using peer::bullet_shape;
using peer::bullet_transform;
using peer::Kind;
using peer::Spec;

namespace {

constexpr double kTol = 1e-10;

// Bullet's signed distance (negative when penetrating).
double bullet_distance(const Spec& a, const Spec& b) {
    auto sa = bullet_shape(a), sb = bullet_shape(b);
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector detector(sa.get(), sb.get(), &simplex, &epa);
    btGjkPairDetector::ClosestPointInput in;
    in.m_transformA = bullet_transform(a.pose);
    in.m_transformB = bullet_transform(b.pose);
    btPointCollector out;
    detector.getClosestPoints(in, out, nullptr);
    return out.m_hasResult ? out.m_distance : NAN;
}

}  // namespace

TEST(GjkBullet, DistanceAgainstBulletF64) {
    const uint64_t seed = 9001;
    const std::vector<peer::Pair> pairs = peer::random_pairs(seed, 3600);
    int compared = 0, disagreements = 0, bullet_wrong = 0, hits = 0;
    double max_diff_polytope = 0;
    for (size_t i = 0; i < pairs.size(); ++i) {
        const peer::Pair& p = pairs[i];
        SCOPED_TRACE(testing::Message() << "seed " << seed << " pair " << i << " " << peer::kind_name(p.a.kind) << "/"
                                        << peer::kind_name(p.b.kind));
        auto ka = peer::make_kairos(p.a), kb = peer::make_kairos(p.b);
        const DistanceResult r = gjk_distance(*ka, p.a.pose, *kb, p.b.pose, kTol, 256);
        const double bd = bullet_distance(p.a, p.b);
        hits += r.intersecting;
        if (!std::isfinite(bd)) continue;
        ++compared;
        const double bdist = std::max(bd, 0.0);
        if (peer::is_polytope(p.a) && peer::is_polytope(p.b) && !r.intersecting && bd > 0)
            max_diff_polytope = std::max(max_diff_polytope, std::fabs(bdist - r.distance) / r.distance);
        if (std::fabs(bdist - r.distance) <= 1e-6 * (1 + r.distance)) continue;
        ++disagreements;
        const double tol = 1e-11 * peer::pair_scale(p);
        bool kairos_right =
            r.intersecting ? peer::certify_intersecting(p.a, p.b, r.point_a, tol)
                           : peer::certify_separated(p.a, p.b, r.point_a, r.point_b, r.axis, r.distance, tol, 1e-8).ok;
        if (peer::is_polytope(p.a) && peer::is_polytope(p.b)) {
            const oracle::Result o = oracle::distance(gjk_test::world_polytope(p.a.verts, p.a.pose),
                                                      gjk_test::world_polytope(p.b.verts, p.b.pose));
            kairos_right =
                kairos_right && std::fabs(static_cast<double>(o.distance) - r.distance) <= 1e-9 * (1 + r.distance);
        }
        bullet_wrong += kairos_right;
        std::printf("  Bullet f64 disagrees, pair %zu %s/%s: kairos %.12g bullet %.12g -> %s\n", i,
                    peer::kind_name(p.a.kind), peer::kind_name(p.b.kind), r.distance, bd,
                    kairos_right ? "Bullet wrong (Kairos certified)" : "UNEXPLAINED");
        EXPECT_TRUE(kairos_right);
    }
    std::printf(
        "[Bullet f64 btGjkPairDetector] %zu pairs (%d intersecting), %d compared, %d disagreements beyond 1e-6, "
        "%d explained as Bullet wrong; max relative difference on separated polytopes %.3g\n",
        pairs.size(), hits, compared, disagreements, bullet_wrong, max_diff_polytope);
    EXPECT_EQ(disagreements, bullet_wrong);
    EXPECT_GT(compared, int(pairs.size()) * 9 / 10);
    EXPECT_GT(hits, int(pairs.size()) / 6);
    EXPECT_LT(hits, int(pairs.size()) * 2 / 3);
}
