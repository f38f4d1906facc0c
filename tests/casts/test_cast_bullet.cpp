// SPDX-License-Identifier: MIT
// Peer cross-check: Bullet's double build btSubsimplexConvexCast (the same GJK ray cast) and Kairos
// on the same random casts, both judged by the long double oracle. Kairos must be exact to its
// tolerance; Bullet's disagreements with the oracle are recorded (printed), not asserted.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "cast_peer_bullet.hpp"
#include "cast_test_support.hpp"
#include "casts/cast.hpp"

using namespace kairos;
using namespace cast_test;

namespace {

struct Tally {
    int casts = 0, truth_hits = 0, misses = 0, false_hits = 0, late = 0;
    std::vector<double> toi_err, angle;
    void add(const Verdict& v, const cast_oracle::Truth& t) {
        ++casts;
        truth_hits += t.hit;
        misses += v.miss;
        false_hits += v.false_hit;
        late += v.late;
        if (v.compared) {
            toi_err.push_back(v.toi_error);
            angle.push_back(v.normal_angle);
        }
    }
    void print(const char* who, const char* pair) const {
        std::printf(
            "[%-8s %-16s] casts %d (truth hits %d) misses %d false hits %d late %d | toi err median %.2g max %.2g | "
            "normal angle median %.2g max %.2g\n",
            who, pair, casts, truth_hits, misses, false_hits, late, median(toi_err), maximum(toi_err), median(angle),
            maximum(angle));
    }
};

}  // namespace

TEST(CastPeerBullet, SubsimplexCastAgainstOracle) {
    const std::pair<Kind, Kind> pairs[] = {{Kind::Box, Kind::Box},       {Kind::Hull, Kind::Hull},
                                           {Kind::Cylinder, Kind::Cone}, {Kind::Capsule, Kind::Hull},
                                           {Kind::Sphere, Kind::Box},    {Kind::Box, Kind::Cylinder}};
    uint64_t seed = 7100;
    for (auto [ka, kb] : pairs) {
        std::mt19937_64 rng(++seed);
        Tally kt, bt;
        int shown = 0;
        const bool curved = ka == Kind::Cylinder || ka == Kind::Cone || kb == Kind::Cylinder || kb == Kind::Cone;
        const int count = curved ? 100 : 250;
        for (int i = 0; i < count; ++i) {
            Solid a = random_solid(rng, ka), b = random_solid(rng, kb);
            const Cast c = random_cast(rng, a, b);
            place(a.body, c.pa);
            place(b.body, c.pb);
            const cast_oracle::Truth t = cast_oracle::toi(a.body, b.body, p3(c.ta), p3(c.tb));
            const double size = static_cast<double>(cast_oracle::size_of(a.body, b.body));
            const double allow = std::max(1e-7, curved ? 1e-5 : 0.0);
            const double toi_allow = allow * size / length(c.tb - c.ta);

            const CastResult k = shape_cast(*a.shape, c.pa, c.ta, *b.shape, c.pb, c.tb, 1e-10, 256);
            const Verdict kv = judge(a.body, b.body, p3(c.ta), p3(c.tb), t, k, toi_allow, allow);
            kt.add(kv, t);
            EXPECT_FALSE(kv.miss || kv.false_hit || kv.late)
                << kind_name(ka) << "/" << kind_name(kb) << " seed " << seed << " case " << i;

            const auto sa = cast_peer::bullet_shape(a.body), sb = cast_peer::bullet_shape(b.body);
            const CastResult r = cast_peer::bullet_cast(*sa, *sb, c);
            const Verdict bv =
                judge(a.body, b.body, p3(c.ta), p3(c.tb), t, r, toi_allow, 1e300);  // Bullet's point: not judged
            bt.add(bv, t);
            if ((bv.miss || bv.late) && ++shown <= 3)
                std::printf(
                    "  bullet disagrees: %s/%s seed %llu case %d: bullet hit %d toi %.17g, oracle hit %d toi %.17g\n",
                    kind_name(ka), kind_name(kb), static_cast<unsigned long long>(seed), i, int(r.hit), r.toi,
                    int(t.hit), static_cast<double>(t.toi));
        }
        char name[64];
        std::snprintf(name, sizeof name, "%s/%s", kind_name(ka), kind_name(kb));
        kt.print("kairos", name);
        bt.print("bullet64", name);
        // The harness is sound when Bullet agrees with the oracle where docs/peers.md found it reliable
        // (polytopes). Elsewhere its disagreements are findings, recorded in the output: with a
        // capsule (radius as margin) against a hull it is late in about a third of the hits, by up
        // to half the step, while Kairos and the oracle agree (and Kairos's contact points are
        // certified on both shapes).
        if (cast_oracle::is_polytope(ka) && cast_oracle::is_polytope(kb)) {
            EXPECT_LT(bt.misses + bt.late, bt.casts / 20) << name;
        }
        // Kairos is never less accurate than Bullet's double build.
        EXPECT_LE(maximum(kt.toi_err), std::max(maximum(bt.toi_err), 1e-12)) << name;
    }
}
