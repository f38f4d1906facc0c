// SPDX-License-Identifier: MIT
// Running the ranges of one job on several threads: the world's own pool, or an engine's task
// system through two callbacks (as Box2D v3's enqueueTask / finishTask). The world's narrow phase
// hands it independent items that write disjoint results, so the results never depend on which
// thread ran what.
//
// Thread safety: one job at a time per Workers, started from one thread.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace kairos {

// An engine's scheduler: the C API's kairos_enqueue_task_fn / kairos_finish_task_fn, same types.
using TaskFn = void(uint32_t begin, uint32_t end, uint32_t worker, void* task_context);
struct TaskHook {
    void* (*enqueue)(TaskFn* task, uint32_t count, uint32_t min_range, void* task_context, void* user_context) = nullptr;
    void (*finish)(void* user_task, void* user_context) = nullptr;
    void* user_context = nullptr;
};

class Workers {
public:
    static constexpr uint32_t kMaxThreads = 256;

    // threads: how many run a job, the caller's included (0 and 1: the caller alone); with a hook
    // (enqueue and finish set) the engine's threads run it and none is started here. Throws
    // std::system_error when a thread cannot be started (none is left running).
    Workers(uint32_t threads, const TaskHook& hook);
    ~Workers();
    Workers(const Workers&) = delete;
    Workers& operator=(const Workers&) = delete;

    // Calls f(begin, end) over [0, count) in ranges of at least min_range (but the last), each
    // item once, and returns when all have run. The first exception a range throws is rethrown
    // here after the others have finished (the remaining ranges are skipped).
    template <class F>
    void run(uint32_t count, uint32_t min_range, F& f) {
        run_erased(count, min_range, [](void* c, uint32_t b, uint32_t e) { (*static_cast<F*>(c))(b, e); }, &f);
    }

private:
    using Erased = void (*)(void* context, uint32_t begin, uint32_t end);
    struct Job {
        Erased fn = nullptr;
        void* context = nullptr;
        uint32_t count = 0, chunk = 1;
        std::exception_ptr error;
        std::mutex error_mutex;
        std::atomic_uint32_t next{0};
    };
    void run_erased(uint32_t count, uint32_t min_range, Erased fn, void* context);
    static void work(Job& job);                                                  // claims ranges until none is left
    static void task_entry(uint32_t begin, uint32_t end, uint32_t worker, void* job);  // TaskFn for the hook
    void thread_main();
    void stop_all();

    TaskHook hook_;
    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    Job* job_ = nullptr;
    uint64_t generation_ = 0;
    uint32_t busy_ = 0;  // pool threads still on the current job
    bool stop_ = false;
};

}  // namespace kairos
