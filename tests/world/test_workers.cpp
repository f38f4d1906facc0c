// SPDX-License-Identifier: MIT
// Workers (the world's threads and an engine's task hook): every item runs exactly once for any
// count, range and thread count; an exception in one range reaches the caller and leaves the pool
// usable; more ranges run at once when there are threads.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <thread>
#include <vector>

#include "world/workers.hpp"

namespace kairos {
namespace {

TEST(Workers, EveryItemRunsExactlyOnce) {
    for (uint32_t threads : {0u, 1u, 2u, 3u, 8u}) {
        Workers workers(threads, {});
        for (uint32_t count : {0u, 1u, 2u, 31u, 32u, 33u, 1000u, 4097u}) {
            for (uint32_t min_range : {0u, 1u, 7u, 32u, 5000u}) {
                std::vector<std::atomic<uint32_t>> hits(count);
                auto f = [&](uint32_t b, uint32_t e) {
                    ASSERT_LE(b, e);
                    ASSERT_LE(e, count);
                    for (uint32_t i = b; i < e; ++i) hits[i].fetch_add(1);
                };
                workers.run(count, min_range, f);
                for (uint32_t i = 0; i < count; ++i)
                    ASSERT_EQ(hits[i].load(), 1u) << "threads " << threads << " count " << count << " range "
                                                  << min_range << " item " << i;
            }
        }
    }
}

TEST(Workers, AnExceptionReachesTheCallerAndThePoolGoesOn) {
    Workers workers(3, {});
    std::atomic<uint32_t> done{0};
    auto throwing = [&](uint32_t b, uint32_t e) {
        if (b <= 500 && 500 < e) throw std::runtime_error("item 500");
        done.fetch_add(e - b);
    };
    EXPECT_THROW(workers.run(1000, 10, throwing), std::runtime_error);
    EXPECT_LT(done.load(), 1000u);
    std::atomic<uint32_t> after{0};
    auto counting = [&](uint32_t b, uint32_t e) { after.fetch_add(e - b); };
    for (int i = 0; i < 50; ++i) workers.run(1000, 10, counting);
    EXPECT_EQ(after.load(), 50000u);
}

// With two threads, two ranges are in flight at once (each waits, briefly, for the other).
TEST(Workers, TwoThreadsRunRangesAtOnce) {
    Workers workers(2, {});
    std::atomic<int> inside{0}, most{0};
    auto f = [&](uint32_t, uint32_t) {
        const int now = inside.fetch_add(1) + 1;
        int seen = most.load();
        while (now > seen && !most.compare_exchange_weak(seen, now)) {
        }
        const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
        while (most.load() < 2 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        inside.fetch_sub(1);
    };
    workers.run(64, 1, f);
    EXPECT_EQ(most.load(), 2);
}

// The hook: the engine gets the count and the minimum range; its ranges may come in any order
// and from any thread; an exception inside the task stays on the engine's side of the hook and
// reaches the caller of run.
TEST(Workers, TheHookRunsTheEnginesRanges) {
    struct Engine {
        uint32_t count = 0, min_range = 0;
        static void* enqueue(TaskFn* task, uint32_t count, uint32_t min_range, void* ctx, void* user) {
            auto& e = *static_cast<Engine*>(user);
            e.count = count;
            e.min_range = min_range;
            std::thread t([=] {
                for (uint32_t b = count; b > 0;) {
                    const uint32_t lo = b > min_range ? b - min_range : 0;
                    task(lo, b, 5, ctx);
                    b = lo;
                }
            });
            t.join();
            return nullptr;
        }
        static void finish(void*, void*) { ADD_FAILURE() << "finish is called only for a handle"; }
    } engine;
    Workers workers(4, {&Engine::enqueue, &Engine::finish, &engine});
    std::vector<std::atomic<uint32_t>> hits(777);
    auto f = [&](uint32_t b, uint32_t e) {
        for (uint32_t i = b; i < e; ++i) hits[i].fetch_add(1);
    };
    workers.run(777, 40, f);
    EXPECT_EQ(engine.count, 777u);
    EXPECT_EQ(engine.min_range, 40u);
    for (auto& h : hits) ASSERT_EQ(h.load(), 1u);
    auto throwing = [&](uint32_t b, uint32_t) {
        if (b == 0) throw std::runtime_error("first range");
    };
    EXPECT_THROW(workers.run(100, 10, throwing), std::runtime_error);
}

}  // namespace
}  // namespace kairos
