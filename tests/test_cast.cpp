// Tests of the GJK ray cast and shape cast (src/cast.hpp) against the long double oracles of
// tests/oracle/cast_oracle.hpp: random casts of every pair of shape kinds, closed forms, hard cases.
#include <gtest/gtest.h>

#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include "cast.hpp"
#include "cast_test_support.hpp"

using namespace kairos;
using namespace cast_test;

namespace {

constexpr double kTol = 1e-10;  // the public default
constexpr uint32_t kMaxIt = 256;

[[maybe_unused]] Pose at(Vec3 p, Quat q = {}) { return make_pose(p, q); }

struct Stats {
    int casts = 0, hits = 0, truth_hits = 0, misses = 0, false_hits = 0, late = 0, grazing = 0;
    std::vector<double> toi_err, normal_gap, normal_angle, point_err, iterations;
    void add(const Verdict& v, const cast_oracle::Truth& t, const CastResult& r) {
        ++casts;
        hits += r.hit;
        truth_hits += t.hit;
        misses += v.miss;
        false_hits += v.false_hit;
        late += v.late;
        grazing += t.grazing;
        iterations.push_back(r.iterations);
        if (v.compared) {
            toi_err.push_back(v.toi_error);
            normal_gap.push_back(v.normal_gap);
            normal_angle.push_back(v.normal_angle);
        }
        if (r.hit) point_err.push_back(v.point_error);
    }
    void print(const char* name) const {
        double it = 0;
        for (double x : iterations) it += x;
        std::printf("[%-18s] casts %5d hits %5d (truth %5d) misses %d false %d late %d grazing %d | toi err med %.2g max %.2g | "
                    "normal gap med %.2g max %.2g angle max %.2g | point med %.2g max %.2g | iterations %.2f\n",
                    name, casts, hits, truth_hits, misses, false_hits, late, grazing, median(toi_err), maximum(toi_err),
                    median(normal_gap), maximum(normal_gap), maximum(normal_angle), median(point_err), maximum(point_err),
                    casts ? it / casts : 0);
    }
};

// Runs `count` random casts of kind ka against kind kb and checks each against the oracle.
Stats run_pair(uint64_t seed, Kind ka, Kind kb, int count, double tolerance, double scale = 1, Vec3 base = {},
               double motion_scale = 1, cast_detail::ClipPolicy policy = cast_detail::kDefaultPolicy) {
    std::mt19937_64 rng(seed);
    Stats st;
    // Allowances: a hit stops within tolerance * size of M; toi, normal and point errors scale with it
    // (over the cosine of the approach angle), plus rounding of the far-from-origin coordinates.
    const double rounding = 1e-14 * (1 + length(base) / scale);
    // Curved shapes (cylinder and cone rims, cone apex): GJK about a point on a curved surface
    // converges linearly and stalls at about 1e-7 of the size in double precision, so a tighter
    // tolerance stops there (early, never late).
    const bool curved = ka == Kind::Cylinder || ka == Kind::Cone || kb == Kind::Cylinder || kb == Kind::Cone;
    const double point_allow = std::max(1e3 * tolerance, curved ? 1e-5 : 0.0) + 1e3 * rounding;
    for (int i = 0; i < count; ++i) {
        Solid a = random_solid(rng, ka, scale), b = random_solid(rng, kb, scale);
        const Cast c = random_cast(rng, a, b, base, motion_scale);
        place(a.body, c.pa);
        place(b.body, c.pb);
        const CastResult r = cast_detail::shape_cast(*a.shape, c.pa, c.ta, *b.shape, c.pb, c.tb, tolerance, kMaxIt, policy);
        const cast_oracle::Truth t = cast_oracle::toi(a.body, b.body, p3(c.ta), p3(c.tb));
        const double rlen = length(c.tb - c.ta);
        const double size = static_cast<double>(cast_oracle::size_of(a.body, b.body));
        const double toi_allow = rlen > 0 ? point_allow * size / rlen : 1;
        const Verdict v = judge(a.body, b.body, p3(c.ta), p3(c.tb), t, r, toi_allow, point_allow);
        st.add(v, t, r);
        const bool bad = v.miss || v.false_hit || v.late || !std::isfinite(r.toi) || r.toi < 0 || r.toi > 1 ||
                         (r.hit && (!is_finite(r.point) || std::fabs(length(r.normal) - 1) > 1e-12));
        EXPECT_FALSE(bad) << kind_name(ka) << "/" << kind_name(kb) << " seed " << seed << " case " << i << ": hit " << r.hit
                          << " toi " << r.toi << " truth hit " << t.hit << " toi " << static_cast<double>(t.toi) << " grazing "
                          << t.grazing << " point err " << v.point_error << " termination " << int(r.termination)
                          << " iterations " << r.iterations;
    }
    return st;
}

bool solid_kind(Kind k) { return k != Kind::Point && k != Kind::Segment; }

}  // namespace

// ---- Random casts of every pair of kinds -------------------------------------------------------

TEST(CastRandom, EveryPairOfKindsAgainstOracle) {
    uint64_t seed = 5000;
    Stats all;
    for (Kind ka : kAllKinds)
        for (Kind kb : kAllKinds) {
            if (!solid_kind(ka) && !solid_kind(kb)) continue;  // M without volume: hits have measure zero
            const bool dual = !(cast_oracle::is_polytope(ka) || cast_oracle::is_round(ka)) ||
                              !(cast_oracle::is_polytope(kb) || cast_oracle::is_round(kb));
            const Stats st = run_pair(++seed, ka, kb, dual ? 60 : 120, kTol);
            char name[64];
            std::snprintf(name, sizeof name, "%s/%s", kind_name(ka), kind_name(kb));
            st.print(name);
            // Hit rate between bounds: the set keeps exercising both outcomes.
            EXPECT_GT(st.truth_hits, st.casts / 5) << name;
            EXPECT_LT(st.truth_hits, 4 * st.casts / 5) << name;
            for (double e : st.normal_gap) EXPECT_LT(e, 1e-6) << name;
            all.misses += st.misses;
            all.false_hits += st.false_hits;
            all.casts += st.casts;
        }
    std::printf("all pairs: %d casts, %d misses, %d false hits\n", all.casts, all.misses, all.false_hits);
}
