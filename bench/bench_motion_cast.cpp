// SPDX-License-Identifier: MIT
// Motion cast benchmark: Kairos's motion cast (rotation by disk bounds with bisection and
// conservative advancement) over tolerances and rotation angles, beside FCL's continuousCollide
// (screw motion, zero translation, conservative advancement, GST_INDEP; forked, timed in the
// child) and Bullet f64's btContinuousConvexCollision on the same motions, in one program and one
// run. Each set: rotating pairs with zero translation (the one FCL rotation mode that works), every
// case's first contact from the long double reference (tests/support/oracle/motion_reference.hpp).
// CSV rows: median ns per query, mean GJK iterations, casts and distance queries per query,
// time-of-impact error against the reference (median, max, over cases both hit), misses, late
// answers (toi > reference + tolerance), hits.
//   bench_motion_cast [out.csv] [cases per set]      (default: standard output, 192)
#include <benchmark/benchmark.h>

#include <BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <fcl/narrowphase/continuous_collision.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <vector>

#include "cast_bench_common.hpp"
#include "cast_peer_bullet.hpp"
#include "cast_peer_fcl.hpp"
#include "motion_test_support.hpp"

using namespace kairos;
using cast_test::Kind;
using cast_test::Solid;
using motion_test::MotionCase;

namespace {

struct Scenario {
    const char* name;
    Kind a, b;
    int hull_points;
    uint64_t seed;
};
const Scenario kScenarios[] = {{"box/box", Kind::Box, Kind::Box, 12, 2701},
                               {"hull32/hull32", Kind::Hull, Kind::Hull, 32, 2702},
                               {"capsule/box", Kind::Capsule, Kind::Box, 12, 2703},
                               {"cylinder/cone", Kind::Cylinder, Kind::Cone, 12, 2704}};
// Largest turn per body per step (each case draws its angles up to it).
const double kAngles[] = {std::numbers::pi / 8, std::numbers::pi / 4, std::numbers::pi / 2, 0.9 * std::numbers::pi};

struct Item {
    Solid a, b;
    MotionCase m;
    motion_ref::Pair::Contact ref;
};

std::vector<Item> make_set(const Scenario& sc, double max_angle, int count) {
    std::mt19937_64 rng(sc.seed + uint64_t(1000 * max_angle));
    motion_test::CaseShape cs;
    cs.translate = false;
    cs.max_angle = max_angle;
    cs.gap_lo = 0.55;
    cs.gap_hi = 1.0;
    std::vector<Item> out;
    int misses = 0;
    while (int(out.size()) < count) {
        Item x;
        x.a = cast_test::random_solid(rng, sc.a, 1, sc.hull_points);
        x.b = cast_test::random_solid(rng, sc.b, 1, sc.hull_points);
        x.m = motion_test::random_case(rng, x.a, x.b, cs);
        x.ref = motion_test::reference_pair(x.a, x.b, x.m).first_contact();
        if (!x.ref.decided) continue;
        if (x.ref.hit && x.ref.toi == 0) continue;        // overlapping at the start says nothing about the methods
        if (!x.ref.hit && 2 * misses >= count) continue;  // at least half of the set hits
        misses += !x.ref.hit;
        out.push_back(std::move(x));
    }
    return out;
}

struct Answer {
    bool hit = false;
    double toi = 1;
};

struct Row {
    double ns_median = 0, iterations = 0, casts = 0, distances = 0, err_median = 0, err_max = 0;
    int misses = 0, late = 0, hits = 0, false_hits = 0, count = 0;
};

Row summarize(const std::vector<Item>& set, const std::vector<Answer>& ans, double late_allowance) {
    Row r;
    std::vector<double> err;
    for (size_t i = 0; i < set.size(); ++i) {
        const Item& x = set[i];
        ++r.count;
        r.hits += ans[i].hit;
        if (x.ref.hit && !ans[i].hit) ++r.misses;
        if (!x.ref.hit && ans[i].hit) ++r.false_hits;
        if (x.ref.hit && ans[i].hit) {
            err.push_back(std::fabs(ans[i].toi - double(x.ref.toi)));
            if (ans[i].toi > double(x.ref.toi) + late_allowance) ++r.late;
        }
    }
    r.err_median = cast_bench::median(err);
    r.err_max = err.empty() ? 0 : *std::max_element(err.begin(), err.end());
    return r;
}

void row(FILE* f, const char* scenario, double angle, const char* method, double tol, const Row& r) {
    std::fprintf(f, "%s,%.6g,%s,%.3g,%.1f,%.2f,%.2f,%.2f,%.3g,%.3g,%d,%d,%d,%d,%d\n", scenario,
                 angle * 180 / std::numbers::pi, method, tol, r.ns_median, r.iterations, r.casts, r.distances,
                 r.err_median, r.err_max, r.misses, r.late, r.false_hits, r.hits, r.count);
    std::fflush(f);
}

}  // namespace

int main(int argc, char** argv) {
    // Anything starting with '-' (such as --help) gets the usage, not a file of that name.
    if (argc > 3 || (argc > 1 && argv[1][0] == '-')) {
        std::fprintf(stderr, "usage: %s [out.csv] [cases per set]   (CSV rows; default: standard output, 192)\n",
                     argv[0]);
        return 2;
    }
    FILE* out = argc > 1 ? std::fopen(argv[1], "w") : stdout;
    if (!out) return 1;
    const int count = argc > 2 ? std::atoi(argv[2]) : 192;
    std::fprintf(out,
                 "scenario,max_angle_deg,method,tolerance,ns_median,iterations_mean,casts_mean,distances_mean,"
                 "toi_err_median,toi_err_max,misses,late,false_hits,hits,cases\n");
    const double tolerances[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10};
    for (const Scenario& sc : kScenarios)
        for (const double angle : kAngles) {
            const std::vector<Item> set = make_set(sc, angle, count);
            std::vector<Answer> ans(set.size());

            // Kairos (the kairos_hybrid and kairos_disk rows of results/motion.csv came from
            // strategies since removed).
            for (const double tol : tolerances) {
                double iterations = 0, casts = 0, distances = 0;
                auto one = [&](size_t i) {
                    const Item& x = set[i];
                    MotionCastStats st;
                    const CastResult r = motion_cast(*x.a.shape, Motion(x.m.a0, x.m.a1), *x.b.shape,
                                                     Motion(x.m.b0, x.m.b1), tol, 256, &st);
                    benchmark::DoNotOptimize(r);
                    ans[i] = {r.hit, r.toi};
                    return std::tuple{r.iterations, st.casts, st.distances};
                };
                for (size_t i = 0; i < set.size(); ++i) {
                    const auto [it, c, d] = one(i);
                    iterations += it;
                    casts += c;
                    distances += d;
                }
                const cast_bench::Timing ns = cast_bench::time_casts([&](size_t i) { one(i); }, set.size(), 3, 4);
                Row r = summarize(set, ans, tol);
                r.ns_median = ns.median;
                r.iterations = iterations / double(set.size());
                r.casts = casts / double(set.size());
                r.distances = distances / double(set.size());
                row(out, sc.name, angle, "kairos", tol, r);
            }

            // Bullet f64 btContinuousConvexCollision: shapes made beforehand, a new solver per query.
            {
                std::vector<std::unique_ptr<btConvexShape>> sa, sb;
                for (const Item& x : set) {
                    sa.push_back(cast_peer::bullet_shape(x.a.body));
                    sb.push_back(cast_peer::bullet_shape(x.b.body));
                }
                auto pose = [](const Pose& s) { return cast_peer::bt_pose(make_transform(s.position, s.orientation)); };
                auto one = [&](size_t i) {
                    btVoronoiSimplexSolver simplex;
                    btGjkEpaPenetrationDepthSolver epa;
                    btContinuousConvexCollision ccd(sa[i].get(), sb[i].get(), &simplex, &epa);
                    btConvexCast::CastResult res;
                    const Item& x = set[i];
                    const bool hit =
                        ccd.calcTimeOfImpact(pose(x.m.a0), pose(x.m.a1), pose(x.m.b0), pose(x.m.b1), res) &&
                        res.m_fraction <= btScalar(1);
                    ans[i] = {hit, hit ? double(res.m_fraction) : 1.0};
                    benchmark::DoNotOptimize(ans[i]);
                };
                const cast_bench::Timing ns = cast_bench::time_casts(one, set.size(), 3, 4);
                Row r = summarize(set, ans, 1e-3);
                r.ns_median = ns.median;
                row(out, sc.name, angle, "bullet64_ccd", 1e-3, r);
            }

            // FCL conservative advancement, screw motion, zero translation; forked, timed in the child.
            {
                std::vector<std::shared_ptr<fcl::CollisionGeometryd>> ga, gb;
                for (const Item& x : set) {
                    ga.push_back(cast_peer::fcl_shape(x.a.body));
                    gb.push_back(cast_peer::fcl_shape(x.b.body));
                }
                auto pose = [](const Pose& s) {
                    return cast_peer::fcl_pose(make_transform(s.position, s.orientation));
                };
                std::vector<double> per(set.size(), 1e300);
                std::vector<cast_peer::FclOut> first;
                for (int rep = 0; rep < 3; ++rep) {
                    const auto res = cast_peer::run_guarded(int(set.size()), [&](int i) {
                        const Item& x = set[size_t(i)];
                        fcl::ContinuousCollisionRequestd req;
                        req.ccd_motion_type = fcl::CCDM_SCREW;
                        req.gjk_solver_type = fcl::GST_INDEP;
                        req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
                        fcl::ContinuousCollisionResultd r;
                        cast_peer::FclOut o;
                        const auto t0 = std::chrono::steady_clock::now();
                        try {
                            fcl::continuousCollide(ga[size_t(i)].get(), pose(x.m.a0), pose(x.m.a1), gb[size_t(i)].get(),
                                                   pose(x.m.b0), pose(x.m.b1), req, r);
                            o.hit = r.is_collide ? 1 : 0;
                            o.toi = r.is_collide ? r.time_of_contact : 1;
                        } catch (...) {
                            o.status = 1;
                        }
                        o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                        return o;
                    });
                    for (size_t i = 0; i < set.size(); ++i) per[i] = std::min(per[i], 1e9 * res[i].seconds);
                    if (rep == 0) first = res;
                }
                for (size_t i = 0; i < set.size(); ++i)
                    ans[i] = {first[i].status == 0 && first[i].hit != 0, first[i].toi};
                Row r = summarize(set, ans, 1e-4);
                r.ns_median = cast_bench::median(per);
                row(out, sc.name, angle, "fcl_ca_screw", 1e-4, r);
            }
        }
    if (out != stdout) std::fclose(out);
    return 0;
}
