// A small task pool for the BVH builder: the calling thread plus `extra`
// workers run submitted tasks, largest priority first. Tasks never block, so
// a thread waiting in helpUntil runs queued tasks instead of sleeping while
// there are any. The first exception a task throws is rethrown by helpUntil
// once the pool has drained.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <queue>
#include <thread>
#include <vector>

namespace strata {

class TaskPool {
public:
    explicit TaskPool(unsigned extraThreads) {
        for (unsigned i = 0; i < extraThreads; ++i) {
            try {
                workers_.emplace_back([this] { workerLoop(); });
            } catch (const std::system_error&) {
                break;  // fewer threads than asked for; the caller still runs tasks
            }
        }
    }
    ~TaskPool() {
        {
            std::lock_guard lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : workers_) t.join();
    }
    TaskPool(const TaskPool&) = delete;
    TaskPool& operator=(const TaskPool&) = delete;

    unsigned threads() const { return unsigned(workers_.size()) + 1; }

    void submit(std::uint64_t priority, std::function<void()> fn) {
        {
            std::lock_guard lock(mutex_);
            queue_.push(Entry{priority, seq_++, std::move(fn)});
            ++pending_;
        }
        wake_.notify_one();
    }

    // Runs tasks on this thread until every submitted task has finished.
    void drain() {
        helpUntil([this] { return pending_ == 0; });
        if (error_) std::rethrow_exception(error_);
    }

    // Calls fn(i) for i in [0, count) on the pool; returns when all are done.
    void parallelFor(std::uint32_t count, const std::function<void(std::uint32_t)>& fn) {
        if (count == 1 || workers_.empty()) {
            for (std::uint32_t i = 0; i < count; ++i) fn(i);
            return;
        }
        std::atomic<std::uint32_t> left{count};
        for (std::uint32_t i = 0; i < count; ++i) {
            submit(~std::uint64_t(0), [&fn, &left, i] {
                struct Done {
                    std::atomic<std::uint32_t>& n;
                    ~Done() { n.fetch_sub(1); }
                } done{left};
                fn(i);
            });
        }
        helpUntil([&left] { return left.load() == 0; });
        if (error_) std::rethrow_exception(error_);
    }

private:
    struct Entry {
        std::uint64_t priority;
        std::uint64_t seq;
        std::function<void()> fn;
        bool operator<(const Entry& o) const {  // max-heap: high priority, then FIFO
            return priority != o.priority ? priority < o.priority : seq > o.seq;
        }
    };

    // Runs one task taken under `lock`; returns with the lock held.
    void runOne(std::unique_lock<std::mutex>& lock) {
        std::function<void()> fn = std::move(const_cast<Entry&>(queue_.top()).fn);
        queue_.pop();
        lock.unlock();
        try {
            fn();
        } catch (...) {
            std::lock_guard g(errorMutex_);
            if (!error_) error_ = std::current_exception();
        }
        fn = nullptr;
        lock.lock();
        --pending_;
        wake_.notify_all();  // waiters re-check their condition
    }

    void helpUntil(const std::function<bool()>& done) {
        std::unique_lock lock(mutex_);
        while (!done()) {
            if (!queue_.empty()) {
                runOne(lock);
            } else {
                wake_.wait(lock);
            }
        }
    }

    void workerLoop() {
        std::unique_lock lock(mutex_);
        for (;;) {
            if (!queue_.empty()) {
                runOne(lock);
            } else if (stop_) {
                return;
            } else {
                wake_.wait(lock);
            }
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::priority_queue<Entry> queue_;
    std::uint64_t seq_ = 0;
    std::uint64_t pending_ = 0;  // submitted and not finished (guarded by mutex_)
    bool stop_ = false;
    std::mutex errorMutex_;
    std::exception_ptr error_;
    std::vector<std::thread> workers_;
};

}  // namespace strata
