// SPDX-License-Identifier: MIT
// Shared by the cast benchmarks (Kairos with Bullet f64 and FCL, and Bullet f32 in its own
// program): the fixed random sets, their oracle truth, the error summary and the CSV row.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "cast_test_support.hpp"

namespace cast_bench {

using namespace cast_test;

// The sets: the first four are drawn on the chart, sphere/box, sphere/capsule and capsule/capsule
// (closed forms) are in the CSV and the README's table. 512 casts each: few enough to stay in cache (the comparison is of the
// algorithms), enough for stable medians.
constexpr int kCasts = 512;

struct Scenario {
    const char* name;
    Kind a, b;
    uint64_t seed;
};
inline const Scenario kScenarios[] = {{"box/box", Kind::Box, Kind::Box, 2501},
                                      {"hull32/hull32", Kind::Hull, Kind::Hull, 2502},
                                      {"cylinder/cone", Kind::Cylinder, Kind::Cone, 2503},
                                      {"capsule/hull32", Kind::Capsule, Kind::Hull, 2504},
                                      {"sphere/box", Kind::Sphere, Kind::Box, 2505},
                                      {"sphere/capsule", Kind::Sphere, Kind::Capsule, 2506},
                                      {"capsule/capsule", Kind::Capsule, Kind::Capsule, 2507}};

struct Item {
    Solid a, b;
    Cast c;
    cast_oracle::Truth truth;
};

// The fixed set of a scenario (identical in every program built by the same compiler).
inline std::vector<Item> make_set(const Scenario& s, int count = kCasts) {
    std::mt19937_64 rng(s.seed);
    std::vector<Item> out;
    out.reserve(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        Item it{random_solid(rng, s.a, 1, 32), random_solid(rng, s.b, 1, 32), {}, {}};
        it.c = random_cast(rng, it.a, it.b);
        place(it.a.body, it.c.pa);
        place(it.b.body, it.c.pb);
        it.truth = cast_oracle::toi(it.a.body, it.b.body, p3(it.c.ta), p3(it.c.tb));
        out.push_back(std::move(it));
    }
    return out;
}

// Accuracy of one method on a set, against the oracle.
struct Summary {
    int casts = 0, hits = 0, misses = 0, false_hits = 0;
    double iterations = 0;  // mean, when known (else -1)
    std::vector<double> toi_err, angle, point;
};

// judge_point: whether the method's contact point is meaningful (FCL gives none).
// tolerance: a hit whose contact point shows the shapes within max(2 tolerance, 1e-6) of their size
// at toi is a near miss the tolerance allows, not a false hit (methods with a point only).
inline Summary summarize(const std::vector<Item>& set, const std::vector<kairos::CastResult>& results, bool has_normal,
                         bool has_point, bool has_iterations, double tolerance = 0) {
    Summary s;
    double it = 0;
    for (size_t i = 0; i < set.size(); ++i) {
        const Item& x = set[i];
        const kairos::CastResult& r = results[i];
        ++s.casts;
        s.hits += r.hit;
        it += r.iterations;
        const cast_oracle::Truth& t = x.truth;
        if (t.hit && !r.hit && !t.grazing) ++s.misses;
        if (!t.hit && r.hit) {
            const double size = static_cast<double>(cast_oracle::size_of(x.a.body, x.b.body));
            const double gap =
                has_point
                    ? static_cast<double>(point_gap(x.a.body, x.b.body, p3(x.c.ta), p3(x.c.tb), r.toi, p3(r.point))) /
                          size
                    : 1;
            if (gap > std::max(1e-6, 2 * tolerance) && !t.grazing) ++s.false_hits;
        }
        if (t.hit && r.hit && !t.grazing && !t.start_overlap) {
            s.toi_err.push_back(std::fabs(static_cast<double>(Real(r.toi) - t.toi)));
            if (has_normal) {
                const Real nn = cast_oracle::norm(t.normal);
                if (nn > 0) {
                    const Real c = std::clamp(cast_oracle::dot(p3(r.normal), t.normal) / nn, Real(-1), Real(1));
                    s.angle.push_back(static_cast<double>(std::acos(c)));
                }
            }
            if (has_point) {
                const double size = static_cast<double>(cast_oracle::size_of(x.a.body, x.b.body));
                s.point.push_back(
                    static_cast<double>(point_gap(x.a.body, x.b.body, p3(x.c.ta), p3(x.c.tb), r.toi, p3(r.point))) /
                    size);
            }
        }
    }
    s.iterations = has_iterations ? it / s.casts : -1;
    return s;
}

// Time per cast: each cast runs in `batches` batches of `calls` calls; its time is the fastest
// batch's mean (the least disturbed by other work on a shared machine). Reported: the median and
// the mean over the casts of the set.
struct Timing {
    double median = 0, mean = 0;
};
inline Timing time_casts(const std::function<void(size_t)>& one, size_t count, int batches = 5, int calls = 8) {
    std::vector<double> per(count, 1e300);
    // The program's first timed set ran up to 40 % slow on the shared VM (a few milliseconds of
    // work, timed before the core reached its speed): the first call warms up for 300 ms.
    static bool warmed = false;
    if (!warmed) {
        const auto start = std::chrono::steady_clock::now();
        while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(300))
            for (size_t i = 0; i < count; ++i) one(i);
        warmed = true;
    }
    for (size_t i = 0; i < count; ++i) one(i);  // warm up
    for (int b = 0; b < batches; ++b)
        for (size_t i = 0; i < count; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            for (int c = 0; c < calls; ++c) one(i);
            const double ns =
                1e9 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / calls;
            per[i] = std::min(per[i], ns);
        }
    Timing t;
    for (double x : per) t.mean += x;
    t.mean /= static_cast<double>(count);
    t.median = median(per);
    return t;
}

// The CSV destination: argv[1] if given, else standard output. Anything starting with '-' (such as
// --help) gets the usage on standard error and null, instead of becoming a file of that name.
inline FILE* open_output(int argc, char** argv) {
    if (argc > 2 || (argc == 2 && argv[1][0] == '-')) {
        std::fprintf(stderr, "usage: %s [out.csv]   (CSV rows; default: standard output)\n", argv[0]);
        return nullptr;
    }
    if (argc < 2) return stdout;
    FILE* f = std::fopen(argv[1], "w");
    if (!f) std::fprintf(stderr, "%s: cannot write %s\n", argv[0], argv[1]);
    return f;
}

inline void csv_header(FILE* f) {
    std::fprintf(f,
                 "scenario,method,tolerance,ns_median,iterations_mean,toi_err_median,toi_err_max,normal_err_median,"
                 "normal_err_max,point_err_median,point_err_max,misses,false_hits,hits,casts,ns_mean\n");
}

inline void csv_row(FILE* f, const char* scenario, const char* method, double tolerance, Timing ns, const Summary& s) {
    auto opt = [](const std::vector<double>& v, bool median_of) {
        if (v.empty()) return std::string("");
        char b[32];
        std::snprintf(b, sizeof b, "%.3e", median_of ? median(v) : maximum(v));
        return std::string(b);
    };
    char it[32] = "";
    if (s.iterations >= 0) std::snprintf(it, sizeof it, "%.3f", s.iterations);
    std::fprintf(f, "%s,%s,%.0e,%.1f,%s,%s,%s,%s,%s,%s,%s,%d,%d,%d,%d,%.1f\n", scenario, method, tolerance, ns.median,
                 it, opt(s.toi_err, true).c_str(), opt(s.toi_err, false).c_str(), opt(s.angle, true).c_str(),
                 opt(s.angle, false).c_str(), opt(s.point, true).c_str(), opt(s.point, false).c_str(), s.misses,
                 s.false_hits, s.hits, s.casts, ns.mean);
    std::fflush(f);
}

}  // namespace cast_bench
