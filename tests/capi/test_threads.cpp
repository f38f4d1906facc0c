// SPDX-License-Identifier: MIT
// Threads, through the shared library (run under ThreadSanitizer by the `tsan` preset): shapes
// shared by several threads are queried, retained, released and built into composites at once;
// each thread steps its own world over shared shapes; every answer is bit-identical to the one
// computed on one thread first, and each thread's last error is its own.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "kairos/kairos.h"

namespace {

constexpr int kThreads = 4;

kairos_pose at(double x, double y, double z) { return {{x, y, z}, {0, 0, 0, 1}}; }

struct SharedShapes {
    std::vector<kairos_shape*> all;
    SharedShapes() {
        kairos_shape* s = nullptr;
        EXPECT_EQ(kairos_shape_box({0.5, 0.3, 0.2}, &s), KAIROS_OK);
        all.push_back(s);
        EXPECT_EQ(kairos_shape_sphere(0.4, &s), KAIROS_OK);
        all.push_back(s);
        const kairos_vec3 pts[6] = {{0, 0, 0.6}, {0.5, 0, 0}, {0, 0.5, 0}, {-0.5, 0, 0}, {0, -0.5, 0}, {0, 0, -0.6}};
        EXPECT_EQ(kairos_shape_convex_hull(pts, 6, &s), KAIROS_OK);
        all.push_back(s);
        EXPECT_EQ(kairos_shape_triangle({-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, &s), KAIROS_OK);
        all.push_back(s);
        EXPECT_EQ(kairos_shape_minkowski_sum(all[0], all[1], &s), KAIROS_OK);
        all.push_back(s);
    }
    ~SharedShapes() {
        for (kairos_shape* s : all) kairos_shape_release(s);
    }
};

// A fixed batch of distance, shape-cast and motion-cast queries over every pair of shapes; the
// results as raw bytes (determinism is bit-for-bit).
std::vector<unsigned char> query_batch(const SharedShapes& shapes) {
    std::vector<unsigned char> bytes;
    auto keep = [&](const void* p, size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        bytes.insert(bytes.end(), b, b + n);
    };
    for (size_t i = 0; i < shapes.all.size(); ++i)
        for (size_t j = 0; j < shapes.all.size(); ++j) {
            const double k = static_cast<double>(i * 7 + j);
            const kairos_pose pa = at(0, 0, 0), pb = at(1.5 + 0.1 * std::sin(k), 0.3 * std::cos(k), 0.2);
            kairos_distance_result d;
            EXPECT_EQ(kairos_distance(shapes.all[i], &pa, shapes.all[j], &pb, nullptr, &d), KAIROS_OK);
            keep(&d.distance, sizeof d.distance);
            keep(&d.point_a, sizeof d.point_a);
            kairos_cast_result r;
            EXPECT_EQ(kairos_shape_cast(shapes.all[i], &pa, {2, 0, 0}, shapes.all[j], &pb, {0, 0, 0}, nullptr, &r),
                      KAIROS_OK);
            keep(&r.toi, sizeof r.toi);
            keep(&r.normal, sizeof r.normal);
            const kairos_motion ma{pa, {{2, 0, 0}, {0, 0, std::sqrt(0.5), std::sqrt(0.5)}}}, mb{pb, pb};
            EXPECT_EQ(kairos_motion_cast(shapes.all[i], &ma, shapes.all[j], &mb, nullptr, &r), KAIROS_OK);
            keep(&r.toi, sizeof r.toi);
        }
    return bytes;
}

// A world of shared shapes stepped a few times; its contacts as raw bytes.
std::vector<unsigned char> world_run(const SharedShapes& shapes, int32_t broad_phase, uint32_t workers = 0) {
    kairos_world_settings s;
    kairos_world_settings_init(&s);
    s.broad_phase = broad_phase;
    s.worker_count = workers;
    kairos_world* w = nullptr;
    EXPECT_EQ(kairos_world_create(&s, &w), KAIROS_OK);
    std::vector<kairos_object_id> ids;
    for (int i = 0; i < 60; ++i) {
        kairos_pose p = at(1.1 * (i % 10), 1.1 * (i / 10), 0);
        kairos_object_id id = 0;
        EXPECT_EQ(kairos_world_add(w, shapes.all[static_cast<size_t>(i) % shapes.all.size()], &p,
                                   static_cast<uint64_t>(i), &id),
                  KAIROS_OK);
        ids.push_back(id);
    }
    std::vector<unsigned char> bytes;
    for (int step = 1; step <= 4; ++step) {
        for (size_t i = 0; i < ids.size(); i += 3) {
            const double k = static_cast<double>(i);
            kairos_pose p = at(1.1 * static_cast<double>(i % 10) + 0.4 * step * std::sin(k),
                               1.1 * static_cast<double>(i / 10), 0.3 * std::cos(k));
            EXPECT_EQ(kairos_world_move(w, ids[i], &p), KAIROS_OK);
        }
        EXPECT_EQ(kairos_world_step(w), KAIROS_OK);
        const kairos_contact* c = nullptr;
        size_t n = 0;
        EXPECT_EQ(kairos_world_contacts(w, &c, &n), KAIROS_OK);
        const auto* b = reinterpret_cast<const unsigned char*>(c);
        bytes.insert(bytes.end(), b, b + n * sizeof(kairos_contact));
    }
    kairos_world_destroy(w);
    return bytes;
}

TEST(Threads, SharedShapesQueriedRetainedAndReleasedAtOnce) {
    SharedShapes shapes;
    const std::vector<unsigned char> reference = query_batch(shapes);
    ASSERT_FALSE(reference.empty());
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (int round = 0; round < 20; ++round) {
                // Extra references and composites built from the shared parts, dropped again.
                for (kairos_shape* s : shapes.all) kairos_shape_retain(s);
                kairos_shape* sum = nullptr;
                kairos_shape* both = nullptr;
                if (kairos_shape_minkowski_sum(shapes.all[static_cast<size_t>(t) % 5], shapes.all[2], &sum) !=
                    KAIROS_OK)
                    ++mismatches;
                if (kairos_shape_hull(shapes.all[3], shapes.all[1], &both) != KAIROS_OK) ++mismatches;
                if (query_batch(shapes) != reference) ++mismatches;
                kairos_shape_release(sum);
                kairos_shape_release(both);
                for (kairos_shape* s : shapes.all) kairos_shape_release(s);
            }
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
}

TEST(Threads, OneWorldPerThreadOverSharedShapes) {
    SharedShapes shapes;
    const int32_t phases[3] = {KAIROS_BROAD_PHASE_SPACETIME_SAP, KAIROS_BROAD_PHASE_ENCAPSULATING_SAP,
                               KAIROS_BROAD_PHASE_BRUTE_FORCE};
    std::vector<std::vector<unsigned char>> reference;
    for (int32_t bp : phases) reference.push_back(world_run(shapes, bp));
    ASSERT_FALSE(reference[0].empty());
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (int round = 0; round < 3; ++round) {
                const size_t k = static_cast<size_t>(t + round) % 3;
                if (world_run(shapes, phases[k]) != reference[k]) ++mismatches;
            }
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
}

// A world's own worker threads (worker_count 2 and 4): the same contacts as one thread, also
// while other threads step worlds of their own with workers.
TEST(Threads, WorldWorkersGiveTheSameContacts) {
    SharedShapes shapes;
    const std::vector<unsigned char> reference = world_run(shapes, KAIROS_BROAD_PHASE_SPACETIME_SAP);
    ASSERT_FALSE(reference.empty());
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t) {
        threads.emplace_back([&, t] {
            for (int round = 0; round < 2; ++round)
                if (world_run(shapes, KAIROS_BROAD_PHASE_SPACETIME_SAP, t == 0 ? 2u : 4u) != reference) ++mismatches;
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
}

// World queries are const: several threads query one world at once (nothing changes it meanwhile)
// and each gets the answers a single thread gets.
TEST(Threads, ConcurrentWorldQueries) {
    SharedShapes shapes;
    kairos_world* w = nullptr;
    ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
    for (int i = 0; i < 60; ++i) {
        kairos_pose p = at(1.1 * (i % 10), 1.1 * (i / 10), 0.2 * (i % 3));
        kairos_object_id id = 0;
        ASSERT_EQ(kairos_world_add(w, shapes.all[static_cast<size_t>(i) % shapes.all.size()], &p,
                                   static_cast<uint64_t>(i), &id),
                  KAIROS_OK);
    }
    ASSERT_EQ(kairos_world_step(w), KAIROS_OK);
    auto queries = [&] {
        std::vector<unsigned char> bytes;
        for (int q = 0; q < 40; ++q) {
            const double k = q;
            kairos_world_hit hit;
            EXPECT_EQ(kairos_world_ray_cast(w, {-2, 0.3 * k / 4, 0.1}, {14, 0.05 * k, 0}, nullptr, &hit), KAIROS_OK);
            bytes.insert(bytes.end(), reinterpret_cast<unsigned char*>(&hit),
                         reinterpret_cast<unsigned char*>(&hit) + sizeof hit);
            const kairos_motion m{at(-2, 0.25 * k, 1.5), at(12, 0.25 * k, -0.5)};
            EXPECT_EQ(kairos_world_shape_cast(w, shapes.all[static_cast<size_t>(q) % 5], &m, nullptr, nullptr, &hit),
                      KAIROS_OK);
            bytes.insert(bytes.end(), reinterpret_cast<unsigned char*>(&hit),
                         reinterpret_cast<unsigned char*>(&hit) + sizeof hit);
            kairos_object_id ids[64];
            size_t n = 0;
            EXPECT_EQ(kairos_world_query_box(w, {0.2 * k, 0, -1}, {0.2 * k + 2, 6, 1}, nullptr, ids, 64, &n), KAIROS_OK);
            bytes.insert(bytes.end(), reinterpret_cast<unsigned char*>(ids),
                         reinterpret_cast<unsigned char*>(ids) + n * sizeof(kairos_object_id));
        }
        return bytes;
    };
    const std::vector<unsigned char> reference = queries();
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&] {
            if (queries() != reference) ++mismatches;
        });
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
    kairos_world_destroy(w);
}

TEST(Threads, LastErrorIsPerThread) {
    std::atomic<int> wrong{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
        threads.emplace_back([&, t] {
            for (int round = 0; round < 200; ++round) {
                kairos_shape* s = nullptr;
                const double bad = -1.0 - t;  // each thread its own bad radius
                if (kairos_shape_sphere(bad, &s) != KAIROS_ERROR_INVALID_ARGUMENT) ++wrong;
                const std::string expected = "(got " + std::to_string(static_cast<int>(bad)) + ")";
                if (std::string(kairos_last_error()).find(expected) == std::string::npos) ++wrong;
            }
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(wrong.load(), 0);
}

}  // namespace
