// SPDX-License-Identifier: MIT
// Workers (see workers.hpp): ranges claimed from an atomic counter by the caller and the pool.
#include "world/workers.hpp"

#include <algorithm>
#include <atomic>

namespace kairos {

Workers::Workers(uint32_t threads, const TaskHook& hook) : hook_(hook) {
    if (hook_.enqueue != nullptr && hook_.finish != nullptr) return;
    hook_ = TaskHook{};
    const uint32_t extra = std::min(threads, kMaxThreads) > 1 ? std::min(threads, kMaxThreads) - 1 : 0;
    threads_.reserve(extra);
    try {
        for (uint32_t i = 0; i < extra; ++i) threads_.emplace_back([this] { thread_main(); });
    } catch (...) {
        stop_all();  // joins the ones started
        throw;
    }
}

Workers::~Workers() { stop_all(); }

void Workers::stop_all() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
    threads_.clear();
}

void Workers::work(Job& job) {
    for (;;) {
        const uint32_t begin = job.next.fetch_add(job.chunk, std::memory_order_relaxed);
        if (begin >= job.count) return;
        const uint32_t end = job.count - begin > job.chunk ? begin + job.chunk : job.count;
        try {
            job.fn(job.context, begin, end);
        } catch (...) {
            std::lock_guard<std::mutex> lock(job.error_mutex);
            if (!job.error) job.error = std::current_exception();
            job.next.store(job.count, std::memory_order_relaxed);  // skip the rest
        }
    }
}

void Workers::task_entry(uint32_t begin, uint32_t end, uint32_t, void* context) {
    Job& job = *static_cast<Job*>(context);
    if (begin >= end || end > job.count) return;
    try {
        job.fn(job.context, begin, end);
    } catch (...) {
        std::lock_guard<std::mutex> lock(job.error_mutex);
        if (!job.error) job.error = std::current_exception();
    }
}

void Workers::thread_main() {
    uint64_t seen = 0;
    for (;;) {
        Job* job = nullptr;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
            job = job_;
        }
        work(*job);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }
}

void Workers::run_erased(uint32_t count, uint32_t min_range, Erased fn, void* context) {
    if (count == 0) return;
    min_range = std::max<uint32_t>(min_range, 1);
    Job job;
    job.fn = fn;
    job.context = context;
    job.count = count;
    if (hook_.enqueue != nullptr) {
        void* handle = hook_.enqueue(&task_entry, count, min_range, &job, hook_.user_context);
        if (handle != nullptr) hook_.finish(handle, hook_.user_context);
    } else if (threads_.empty() || count <= min_range) {
        fn(context, 0, count);
        return;
    } else {
        // Many ranges per thread, so that uneven items balance (a turning pair's motion cast can
        // cost a hundred times a still pair's); claiming one is an atomic add.
        const auto ways = static_cast<uint32_t>(32 * (threads_.size() + 1));
        job.chunk = std::max(min_range, (count + ways - 1) / ways);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            job_ = &job;
            busy_ = static_cast<uint32_t>(threads_.size());
            ++generation_;
        }
        wake_.notify_all();
        work(job);
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [&] { return busy_ == 0; });
        job_ = nullptr;
    }
    if (job.error) std::rethrow_exception(job.error);
}

}  // namespace kairos
