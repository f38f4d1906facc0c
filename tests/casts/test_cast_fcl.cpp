// SPDX-License-Identifier: MIT
// Peer cross-check: FCL's continuousCollide with translation motion and conservative advancement
// (GST_INDEP), every call in a forked child, against the long double oracle. Its known misses
// (docs/peers.md: a step landing exactly on the contact) are counted and printed, not asserted; the
// test asserts that the harness agrees with the oracle on most casts.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "cast_peer_fcl.hpp"
#include "cast_test_support.hpp"

using namespace kairos;
using namespace cast_test;

TEST(CastPeerFcl, ConservativeAdvancementAgainstOracle) {
    const std::pair<Kind, Kind> pairs[] = {{Kind::Box, Kind::Box},
                                           {Kind::Hull, Kind::Hull},
                                           {Kind::Cylinder, Kind::Cone},
                                           {Kind::Capsule, Kind::Hull},
                                           {Kind::Sphere, Kind::Box}};
    uint64_t seed = 7200;
    for (auto [ka, kb] : pairs) {
        std::mt19937_64 rng(++seed);
        const int count = 150;
        std::vector<Solid> as, bs;
        std::vector<Cast> casts;
        std::vector<cast_oracle::Truth> truth;
        for (int i = 0; i < count; ++i) {
            Solid a = random_solid(rng, ka), b = random_solid(rng, kb);
            const Cast c = random_cast(rng, a, b);
            place(a.body, c.pa);
            place(b.body, c.pb);
            truth.push_back(cast_oracle::toi(a.body, b.body, p3(c.ta), p3(c.tb)));
            as.push_back(std::move(a));
            bs.push_back(std::move(b));
            casts.push_back(c);
        }
        const std::vector<cast_peer::FclOut> r = cast_peer::run_guarded(count, [&](int i) {
            const auto ga = cast_peer::fcl_shape(as[size_t(i)].body), gb = cast_peer::fcl_shape(bs[size_t(i)].body);
            return cast_peer::fcl_cast(ga.get(), gb.get(), casts[size_t(i)]);
        });
        int misses = 0, false_hits = 0, late = 0, died = 0, threw = 0, hits = 0, shown = 0;
        std::vector<double> err;
        for (int i = 0; i < count; ++i) {
            const auto& t = truth[size_t(i)];
            const auto& f = r[size_t(i)];
            if (f.status == 2) ++died;
            if (f.status == 1) ++threw;
            if (f.status != 0) continue;
            hits += t.hit;
            const double rlen = length(casts[size_t(i)].tb - casts[size_t(i)].ta);
            const double size = static_cast<double>(cast_oracle::size_of(as[size_t(i)].body, bs[size_t(i)].body));
            // FCL's toc_err (1e-4 of the step) plus its distance tolerance, relative to the motion.
            const double allow = 1e-4 + 1e-6 * size / rlen;
            const bool miss = t.hit && !t.grazing && !f.hit;
            const bool fh = !t.hit && f.hit && !t.grazing;
            const bool lt = t.hit && f.hit && f.toi > static_cast<double>(t.toi) + allow;
            misses += miss;
            false_hits += fh;
            late += lt;
            if (t.hit && f.hit) err.push_back(std::fabs(f.toi - static_cast<double>(t.toi)));
            if ((miss || fh || lt) && ++shown <= 3)
                std::printf("  fcl disagrees: %s/%s seed %llu case %d: fcl hit %d toi %.9g, oracle hit %d toi %.9g\n",
                            kind_name(ka), kind_name(kb), static_cast<unsigned long long>(seed), i, f.hit, f.toi,
                            int(t.hit), static_cast<double>(t.toi));
        }
        std::printf(
            "[fcl_ca %s/%s] casts %d (truth hits %d) misses %d false hits %d late %d threw %d died %d | toi err median "
            "%.2g max %.2g\n",
            kind_name(ka), kind_name(kb), count, hits, misses, false_hits, late, threw, died, median(err),
            maximum(err));
        // The harness is sound: FCL answers, and agrees with the oracle on most casts.
        EXPECT_LT(died + threw, count / 10);
        EXPECT_LT(misses + false_hits + late, count / 4) << kind_name(ka) << "/" << kind_name(kb);
    }
}
