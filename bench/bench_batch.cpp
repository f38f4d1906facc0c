// SPDX-License-Identifier: MIT
// The batches through the shared library against the same queries as single C calls, in one run:
// n shape casts one by one, as kairos_shape_cast_batch on the calling thread and on a world's
// threads; n world moves one by one and as kairos_world_move_batch. The scene mirrors
// bench/python/bench_batch.py (boxes, spheres and hulls in turn, positions uniform in
// [-2, 2]^3, random turns, translations uniform in [-4, 4]^3), so its per-query times compare
// with the Python package's.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "kairos/kairos.h"

namespace {

constexpr uint64_t kSeed = 12345;

kairos_pose random_pose(std::mt19937_64& rng, double spread) {
    std::uniform_real_distribution<double> u(-spread, spread);
    std::normal_distribution<double> g(0, 1);
    double q[4] = {g(rng), g(rng), g(rng), g(rng)};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    return {{u(rng), u(rng), u(rng)}, {q[0] / n, q[1] / n, q[2] / n, q[3] / n}};
}

struct CastScene {
    std::vector<kairos_shape*> kinds;
    std::vector<const kairos_shape*> a, b;
    std::vector<kairos_pose> pa, pb;
    std::vector<kairos_vec3> ta, tb;
    explicit CastScene(std::size_t n) {
        kairos_shape* s = nullptr;
        kairos_shape_box({0.5, 0.4, 0.3}, &s);
        kinds.push_back(s);
        kairos_shape_sphere(0.5, &s);
        kinds.push_back(s);
        std::mt19937_64 rng(kSeed);
        std::normal_distribution<double> g(0, 0.5);
        std::vector<kairos_vec3> points(32);
        for (kairos_vec3& p : points) p = {g(rng), g(rng), g(rng)};
        kairos_shape_convex_hull(points.data(), points.size(), &s);
        kinds.push_back(s);
        std::uniform_real_distribution<double> u(-4, 4);
        for (std::size_t i = 0; i < n; ++i) {
            a.push_back(kinds[i % 3]);
            b.push_back(kinds[(i / 3) % 3]);
            pa.push_back(random_pose(rng, 2));
            pb.push_back(random_pose(rng, 2));
            ta.push_back({u(rng), u(rng), u(rng)});
            tb.push_back({u(rng), u(rng), u(rng)});
        }
    }
    ~CastScene() {
        for (kairos_shape* s : kinds) kairos_shape_release(s);
    }
    CastScene(const CastScene&) = delete;
    CastScene& operator=(const CastScene&) = delete;
};

void shape_cast_single(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const CastScene s(n);
    std::vector<kairos_cast_result> out(n);
    for (auto _ : state) {
        for (std::size_t i = 0; i < n; ++i)
            kairos_shape_cast(s.a[i], &s.pa[i], s.ta[i], s.b[i], &s.pb[i], s.tb[i], nullptr, &out[i]);
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["ns_per_query"] =
        benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void shape_cast_batch(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const auto workers = static_cast<uint32_t>(state.range(1));
    const CastScene s(n);
    std::vector<kairos_cast_result> out(n);
    kairos_world* pool = nullptr;
    if (workers > 0) {
        kairos_world_settings ws;
        kairos_world_settings_init(&ws);
        ws.worker_count = workers;
        kairos_world_create(&ws, &pool);
    }
    for (auto _ : state) {
        kairos_shape_cast_batch(s.a.data(), s.pa.data(), s.ta.data(), s.b.data(), s.pb.data(), s.tb.data(), n, nullptr,
                                pool, out.data());
        benchmark::DoNotOptimize(out.data());
    }
    kairos_world_destroy(pool);
    state.counters["ns_per_query"] =
        benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// n spheres in a world; each iteration gives every object a move (the step is not run: only the
// cost of handing the moves over is measured).
struct MoveScene {
    kairos_world* world = nullptr;
    kairos_shape* sphere = nullptr;
    std::vector<kairos_object_id> ids;
    std::vector<kairos_pose> ends;
    explicit MoveScene(std::size_t n) {
        kairos_world_create(nullptr, &world);
        kairos_shape_sphere(0.1, &sphere);
        std::mt19937_64 rng(kSeed + 1);
        for (std::size_t i = 0; i < n; ++i) {
            const kairos_pose p = random_pose(rng, 20);
            kairos_object_id id = 0;
            kairos_world_add(world, sphere, &p, i, &id);
            ids.push_back(id);
            ends.push_back(random_pose(rng, 20));
        }
    }
    ~MoveScene() {
        kairos_shape_release(sphere);
        kairos_world_destroy(world);
    }
    MoveScene(const MoveScene&) = delete;
    MoveScene& operator=(const MoveScene&) = delete;
};

void world_move_single(benchmark::State& state) {
    MoveScene s(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state)
        for (std::size_t i = 0; i < s.ids.size(); ++i) kairos_world_move(s.world, s.ids[i], &s.ends[i]);
    state.counters["ns_per_move"] = benchmark::Counter(static_cast<double>(s.ids.size()),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

void world_move_batch(benchmark::State& state) {
    MoveScene s(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) kairos_world_move_batch(s.world, s.ids.data(), s.ends.data(), s.ids.size());
    state.counters["ns_per_move"] = benchmark::Counter(static_cast<double>(s.ids.size()),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(shape_cast_single)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(shape_cast_batch)->Args({10000, 0})->Args({10000, 2})->ArgNames({"n", "workers"})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(world_move_single)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(world_move_batch)->Arg(1000)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
