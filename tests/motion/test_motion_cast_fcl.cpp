// SPDX-License-Identifier: MIT
// Peer cross-check: FCL's continuousCollide with screw motion and zero translation (pure rotation,
// the only FCL rotation mode that works; docs/peers.md), conservative advancement, GST_INDEP, every call
// in a forked child, against the motion reference, beside Kairos on the same motions. FCL's known
// failures (early answers, misses, crashes) are printed, not asserted; Kairos' are asserted.
#include <gtest/gtest.h>

#include <fcl/narrowphase/continuous_collision.h>

#include "cast_peer_fcl.hpp"
#include "motion_peers.hpp"

using namespace kairos;
using namespace motion_peer;

namespace {

cast_peer::FclOut fcl_screw(const fcl::CollisionGeometryd* a, const fcl::CollisionGeometryd* b, const MotionCase& m) {
    fcl::ContinuousCollisionRequestd req;
    req.ccd_motion_type = fcl::CCDM_SCREW;
    req.gjk_solver_type = fcl::GST_INDEP;
    req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    fcl::ContinuousCollisionResultd res;
    cast_peer::FclOut out;
    auto pose = [](const Pose& s) { return cast_peer::fcl_pose(make_transform(s.position, s.orientation)); };
    try {
        fcl::continuousCollide(a, pose(m.a0), pose(m.a1), b, pose(m.b0), pose(m.b1), req, res);
        out.hit = res.is_collide ? 1 : 0;
        out.toi = res.is_collide ? res.time_of_contact : 1;
    } catch (...) {
        out.status = 1;
    }
    return out;
}

}  // namespace

TEST(MotionCastFcl, ScrewMotionZeroTranslation) {
    const uint64_t seed = 8080;
    // Rotations below pi (FCL's screw motion does not promise the shortest arc at and beyond it).
    const std::vector<PeerCase> cases = peer_cases(seed, 6, false, 0.9 * std::numbers::pi, 0.55, 1.0);
    std::vector<std::shared_ptr<fcl::CollisionGeometryd>> ga, gb;
    for (const auto& c : cases) {
        ga.push_back(cast_peer::fcl_shape(c.a.body));
        gb.push_back(cast_peer::fcl_shape(c.b.body));
    }
    const auto fcl = cast_peer::run_guarded(int(cases.size()), [&](int i) {
        return fcl_screw(ga[size_t(i)].get(), gb[size_t(i)].get(), cases[size_t(i)].motion);
    });
    PeerTally kt, ft;
    for (size_t i = 0; i < cases.size(); ++i) {
        const auto& c = cases[i];
        const CastResult r = motion_cast(*c.a.shape, Motion(c.motion.a0, c.motion.a1), *c.b.shape,
                                         Motion(c.motion.b0, c.motion.b1), 1e-6, 256);
        kt.add(c, true, r.hit, r.toi, 1e-6);
        ft.add(c, fcl[i].status == 0, fcl[i].hit != 0, fcl[i].toi, 1e-6);
        const bool kairos_bad =
            c.ref.decided && ((c.ref.hit && !r.hit) || (c.ref.hit && r.hit && r.toi > double(c.ref.toi) + 1e-6));
        EXPECT_FALSE(kairos_bad) << "seed " << seed << " case " << i << " " << cast_test::kind_name(c.a.body.kind)
                                 << "/" << cast_test::kind_name(c.b.body.kind);
        const bool fcl_odd = fcl[i].status != 0 || (c.ref.hit && !fcl[i].hit) ||
                             (c.ref.hit && fcl[i].hit && fcl[i].toi > double(c.ref.toi) + 1e-6);
        if (fcl_odd)
            std::printf("  FCL case %zu %s/%s: ref %s %.9f | FCL status %d hit %d toi %.9f | kairos %d %.9f\n", i,
                        cast_test::kind_name(c.a.body.kind), cast_test::kind_name(c.b.body.kind),
                        c.ref.hit ? "hit" : "miss", double(c.ref.toi), fcl[i].status, fcl[i].hit, fcl[i].toi, r.hit,
                        r.toi);
    }
    kt.print("kairos (tol 1e-6)");
    ft.print("FCL CA screw, zero translation");
    EXPECT_EQ(kt.misses, 0);
    EXPECT_EQ(kt.late, 0);
    EXPECT_GT(kt.ref_hits, kt.cases / 5);
    EXPECT_LT(kt.ref_hits, kt.cases * 4 / 5);
}
