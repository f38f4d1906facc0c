// SPDX-License-Identifier: MIT
// The world's queries against brute force, and the step's scaling with worker threads.
//
// world_query/<kind>/<variant>: one scene of n mixed objects (boxes, spheres, capsules, cylinders,
// hulls; a tenth of them static, all turned at random) in a cube sized for a fixed density; a
// fixed list of queries: rays (random origin and direction, 0.1 of the scene long), box queries
// (2 units wide) and sphere shape casts (0.05 of the scene). "world" calls World's query, "brute"
// runs the same pair query on every object (the answer the tests compare against).
//
// world_workers/n/workers: n objects all moving and turning each step (boxes, spheres, capsules),
// stepped with 1, 2, ... worker threads; counters give the broad and narrow phase's times per
// step (wall clock: the narrow phase's is what the workers share).
//
// Run: build/release/bench/bench_world_queries [--benchmark_filter=...]
//      build/release/bench/bench_world_queries --interleaved   (the worker scaling, robust ratios)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "casts/cast.hpp"
#include "motion/motion.hpp"
#include "scene_rng.hpp"
#include "shapes/shape.hpp"
#include "world/world.hpp"

namespace {

using namespace kairos;
using scene::Rng;

struct Release {
    void operator()(const Shape* s) const {
        if (s) s->release();
    }
};
using ShapePtr = std::unique_ptr<const Shape, Release>;

ShapePtr mixed_shape(Rng& rng) {
    switch (rng.below(5)) {
        case 0: return ShapePtr(new BoxShape({rng.uniform(0.2, 0.6), rng.uniform(0.2, 0.6), rng.uniform(0.2, 0.6)}));
        case 1: return ShapePtr(new SphereShape(rng.uniform(0.2, 0.5)));
        case 2: return ShapePtr(new CapsuleShape(rng.uniform(0.1, 0.3), rng.uniform(0.2, 0.5)));
        case 3: return ShapePtr(new CylinderShape(rng.uniform(0.2, 0.5), rng.uniform(0.2, 0.5)));
        default: {
            std::vector<Vec3> pts;
            for (int i = 0; i < 12; ++i) pts.push_back(rng.in_cube(0.5));
            ConvexHullShape* h = nullptr;
            if (make_convex_hull(pts.data(), pts.size(), &h) != HullStatus::Ok || h == nullptr)
                return ShapePtr(new SphereShape(0.4));
            return ShapePtr(h);
        }
    }
}

Transform rigid(const Pose& p) { return make_transform(p.position, p.orientation); }

// A world of n mixed objects at one object per 8 cubic units.
struct QueryScene {
    World world;
    std::vector<ShapePtr> shapes;
    std::vector<uint64_t> ids;
    double half = 0;
    explicit QueryScene(int n) {
        half = 0.5 * std::cbrt(8.0 * n);
        Rng rng(0x51de + static_cast<uint64_t>(n));
        for (int i = 0; i < n; ++i) {
            shapes.push_back(mixed_shape(rng));
            const uint64_t id = world.add(*shapes.back(), {rng.in_cube(half), rng.orientation()}, static_cast<uint64_t>(i));
            if (i % 10 == 0) world.set_static(id, true);
            ids.push_back(id);
        }
        world.step();
    }
};

enum class Query { Ray, Box, ShapeCast };

void run_query(benchmark::State& state, Query kind, bool brute) {
    const int n = static_cast<int>(state.range(0));
    static std::unique_ptr<QueryScene> scene;
    static int scene_n = 0;
    if (!scene || scene_n != n) {
        scene = std::make_unique<QueryScene>(n);
        scene_n = n;
    }
    const World& w = scene->world;
    Rng rng(77);
    constexpr int kQueries = 512;
    std::vector<Vec3> from(kQueries), along(kQueries);
    for (int i = 0; i < kQueries; ++i) {
        from[static_cast<std::size_t>(i)] = rng.in_cube(scene->half);
        along[static_cast<std::size_t>(i)] = rng.direction() * (kind == Query::Ray ? 0.2 : 0.1) * scene->half;
    }
    const SphereShape ball(0.3);
    std::vector<uint64_t> found;
    uint64_t hits = 0, queries = 0;
    for (auto _ : state) {
        for (int i = 0; i < kQueries; ++i) {
            const Vec3 o = from[static_cast<std::size_t>(i)], d = along[static_cast<std::size_t>(i)];
            if (kind == Query::Box) {
                const Aabb q{o - Vec3{1, 1, 1}, o + Vec3{1, 1, 1}};
                if (!brute) {
                    w.query_box(q, nullptr, found);
                } else {
                    found.clear();
                    for (uint64_t id : scene->ids) {
                        const World::Object* ob = w.find(id);
                        Aabb b;
                        bounds(*ob->shape, rigid(ob->pose), b.min, b.max);
                        if (boxes_overlap(b, q)) found.push_back(id);
                    }
                }
                hits += found.size();
            } else if (!brute) {
                const WorldHit h = kind == Query::Ray ? w.ray_cast(o, d, nullptr)
                                                      : w.shape_cast(ball, {o, {0, 0, 0, 1}}, {o + d, {0, 0, 0, 1}},
                                                                     nullptr, 1e-10, 256);
                hits += h.hit ? 1 : 0;
            } else {
                double best = 2;
                for (uint64_t id : scene->ids) {
                    const World::Object* ob = w.find(id);
                    const CastResult r =
                        kind == Query::Ray
                            ? ray_cast(*ob->shape, rigid(ob->pose), o, d, 1e-10, 256)
                            : shape_cast(ball, make_transform(o, {0, 0, 0, 1}), d, *ob->shape, rigid(ob->pose), {},
                                         1e-10, 256);
                    if (r.hit && r.toi < best) best = r.toi;
                }
                hits += best <= 1 ? 1 : 0;
            }
            ++queries;
        }
    }
    state.SetItemsProcessed(static_cast<int64_t>(queries));
    state.counters["hits_per_query"] = static_cast<double>(hits) / static_cast<double>(queries);
}

// n objects (boxes, spheres, capsules) in a world, all moving and turning every step; the same
// moves whatever the worker count.
struct SpinningScene {
    World world;
    std::vector<ShapePtr> shapes;
    std::vector<uint64_t> ids;
    std::vector<Pose> pose;
    std::vector<Vec3> velocity, spin_axis;
    double half;
    SpinningScene(int n, uint32_t workers) : world(settings(workers)), half(0.5 * std::cbrt(4.0 * n)) {
        Rng rng(0xfeed + static_cast<uint64_t>(n));
        for (int i = 0; i < n; ++i) {
            switch (rng.below(3)) {
                case 0: shapes.push_back(ShapePtr(new BoxShape({0.4, 0.3, 0.2}))); break;
                case 1: shapes.push_back(ShapePtr(new SphereShape(0.35))); break;
                default: shapes.push_back(ShapePtr(new CapsuleShape(0.2, 0.3))); break;
            }
            pose.push_back({rng.in_cube(half), rng.orientation()});
            velocity.push_back(rng.in_cube(0.15));
            spin_axis.push_back(rng.direction());
            ids.push_back(world.add(*shapes.back(), pose.back(), static_cast<uint64_t>(i)));
        }
        world.step();  // inserts every object
    }
    static WorldSettings settings(uint32_t workers) {
        WorldSettings s;
        s.worker_count = workers;
        return s;
    }
    void step() {
        for (std::size_t k = 0; k < ids.size(); ++k) {
            Pose& p = pose[k];
            p.position = p.position + velocity[k];
            for (int a = 0; a < 3; ++a)  // stay in the cube: bounce
                if (std::fabs(p.position[a]) > half) velocity[k][a] = -velocity[k][a];
            p.orientation = normalized(axis_angle(spin_axis[k], 0.2) * p.orientation);
            world.move(ids[k], p);
        }
        world.step();
    }
};

void run_workers(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    state.PauseTiming();
    SpinningScene scene(n, static_cast<uint32_t>(state.range(1)));
    state.ResumeTiming();
    World& world = scene.world;
    double broad = 0, narrow = 0;
    uint64_t steps = 0, contacts = 0, queries = 0;
    for (auto _ : state) {
        scene.step();
        broad += world.counters().broad_phase_seconds;
        narrow += world.counters().narrow_phase_seconds;
        contacts += world.contacts().size();
        queries += world.counters().narrow_phase_queries;
        ++steps;
    }
    const double k = 1.0 / static_cast<double>(steps);
    state.counters["broad_ms"] = 1e3 * broad * k;
    state.counters["narrow_ms"] = 1e3 * narrow * k;
    state.counters["casts"] = static_cast<double>(queries) * k;
    state.counters["contacts"] = static_cast<double>(contacts) * k;
}

void register_all() {
    for (Query q : {Query::Ray, Query::Box, Query::ShapeCast}) {
        const char* name = q == Query::Ray ? "ray" : q == Query::Box ? "box" : "sphere_cast";
        for (bool brute : {false, true}) {
            const std::string full = std::string("world_query/") + name + (brute ? "/brute" : "/world");
            auto* b = benchmark::RegisterBenchmark(full.c_str(), [q, brute](benchmark::State& st) { run_query(st, q, brute); });
            b->Arg(10000)->Unit(benchmark::kMicrosecond);
            if (!brute) b->Arg(100000);
        }
    }
    auto* w = benchmark::RegisterBenchmark("world_workers", run_workers);
    w->ArgNames({"n", "workers"})->Unit(benchmark::kMillisecond)->UseRealTime();
    // A fixed number of steps: every run then steps through the same scene.
    for (int n : {10000, 100000})
        for (int workers : {1, 2}) w->Args({n, workers});
    w->Iterations(6);
}

}  // namespace

// Interleaved: one world per worker count over the same scene, stepped in turn, so that a
// shared machine's swings slow them alike; prints each phase's wall time per step and the
// narrow phase's speed-up over one worker.
void run_interleaved(int n, int steps) {
    std::vector<std::unique_ptr<SpinningScene>> scenes;
    const uint32_t counts[] = {1, 2};
    for (uint32_t w : counts) scenes.push_back(std::make_unique<SpinningScene>(n, w));
    std::vector<double> broad(scenes.size()), narrow(scenes.size());
    for (int s = 0; s < steps; ++s)
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            scenes[k]->step();
            broad[k] += scenes[k]->world.counters().broad_phase_seconds;
            narrow[k] += scenes[k]->world.counters().narrow_phase_seconds;
        }
    for (std::size_t k = 0; k < scenes.size(); ++k)
        std::printf("n %6d  workers %u  broad %8.2f ms  narrow %8.2f ms  narrow speed-up %.2fx  (%zu casts per step)\n", n,
                    counts[k], 1e3 * broad[k] / steps, 1e3 * narrow[k] / steps, narrow[0] / narrow[k],
                    static_cast<std::size_t>(scenes[k]->world.counters().narrow_phase_queries));
}

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--interleaved") == 0) {
            run_interleaved(10000, 20);
            run_interleaved(100000, 6);
            return 0;
        }
    }
    register_all();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
