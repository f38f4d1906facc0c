// SPDX-License-Identifier: MIT
// Shared by the motion cast peer checks and the benchmark: the random rotating cases the peers can
// take (kinds with an exact peer shape: sphere, box, capsule, cylinder, cone, hull), with the
// reference's verdict, and the tally of a peer's answers against it.
#pragma once

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "motion_test_support.hpp"

namespace motion_peer {

using cast_test::Kind;
using motion_test::CaseShape;
using motion_test::MotionCase;

inline constexpr Kind kPeerKinds[] = {Kind::Sphere, Kind::Box, Kind::Capsule, Kind::Cylinder, Kind::Cone, Kind::Hull};

struct PeerCase {
    cast_test::Solid a, b;
    MotionCase motion;
    motion_ref::Pair::Contact ref;
    double size = 0;  // the reference's size (for distances)
};

// per_pair cases per pair of peer kinds; translate: B (and A) translate too; max_angle per body;
// B starts gap_lo..gap_hi sums of bounding radii from A.
inline std::vector<PeerCase> peer_cases(uint64_t seed, int per_pair, bool translate, double max_angle,
                                        double gap_lo = 0.8, double gap_hi = 1.3) {
    std::vector<PeerCase> out;
    int k = 0;
    for (Kind ka : kPeerKinds)
        for (Kind kb : kPeerKinds) {
            std::mt19937_64 rng(seed + uint64_t(++k));
            CaseShape cs;
            cs.translate = translate;
            cs.max_angle = max_angle;
            cs.gap_lo = gap_lo;
            cs.gap_hi = gap_hi;
            for (int i = 0; i < per_pair; ++i) {
                PeerCase c;
                c.a = cast_test::random_solid(rng, ka);
                c.b = cast_test::random_solid(rng, kb);
                c.motion = motion_test::random_case(rng, c.a, c.b, cs);
                const motion_ref::Pair p = motion_test::reference_pair(c.a, c.b, c.motion);
                c.ref = p.first_contact();
                c.size = double(p.size);
                out.push_back(std::move(c));
            }
        }
    return out;
}

// A peer's (or Kairos') answers against the reference.
struct PeerTally {
    int cases = 0, ref_hits = 0, hits = 0, misses = 0, late = 0, false_hits = 0, failures = 0;
    std::vector<double> early;  // reference - toi, both hitting
    void add(const PeerCase& c, bool answered, bool hit, double toi, double late_allowance) {
        ++cases;
        if (!c.ref.decided) return;
        if (!answered) {
            ++failures;
            return;
        }
        ref_hits += c.ref.hit;
        hits += hit;
        if (c.ref.hit && !hit) ++misses;
        if (!c.ref.hit && hit) ++false_hits;  // a near miss within the peer's slop, or wrong
        if (c.ref.hit && hit) {
            early.push_back(double(c.ref.toi) - toi);
            if (toi > double(c.ref.toi) + late_allowance) ++late;
        }
    }
    void print(const std::string& name) const {
        std::vector<double> e = early;
        std::sort(e.begin(), e.end());
        const double med = e.empty() ? 0 : e[e.size() / 2], mn = e.empty() ? 0 : e.front(),
                     mx = e.empty() ? 0 : e.back();
        std::printf(
            "[%-34s] cases %4d ref hits %4d hits %4d misses %3d late %3d false hits %3d failures %3d | "
            "ref - toi: min %.2g median %.2g max %.2g\n",
            name.c_str(), cases, ref_hits, hits, misses, late, false_hits, failures, mn, med, mx);
    }
};

}  // namespace motion_peer
