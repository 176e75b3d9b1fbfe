#include "pool.hpp"

#include <pthread.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <new>
#include <thread>
#include <vector>

namespace kmpy {

namespace {

class Pool {
public:
    //! false: stop() said true and some blocks were left.
    bool run(int blocks, int workers, const std::function<void(int)>& fn,
             const std::function<bool()>& stop) {
        std::unique_lock<std::mutex> batch(batch_, std::try_to_lock);
        if (!batch.owns_lock()) {  // another thread's batch holds the pool: run alone
            return run_alone(blocks, fn, stop);
        }
        const int helpers = workers - 1;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (static_cast<int>(threads_.size()) < helpers) {
                const int index = static_cast<int>(threads_.size());
                threads_.emplace_back([this, index] { loop(index); });
            }
            job_ = &fn;
            blocks_ = blocks;
            next_.store(0);
            stopped_.store(false);
            wanted_ = helpers;
            running_ = helpers;
            ++generation_;
        }
        wake_.notify_all();
        for (int b = take(); b < blocks_; b = take()) {
            (*job_)(b);
            if (stop && next_.load(std::memory_order_relaxed) < blocks_ && stop()) {
                stopped_.store(true);
            }
        }
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return running_ == 0; });
        job_ = nullptr;
        return !stopped_.load();
    }

    //! Every block on the caller's thread, stop() asked after each.
    static bool run_alone(int blocks, const std::function<void(int)>& fn,
                          const std::function<bool()>& stop) {
        for (int b = 0; b < blocks; ++b) {
            fn(b);
            if (b + 1 < blocks && stop && stop()) return false;
        }
        return true;
    }

    //! In a forked child: the threads are gone (their objects are leaked, never joined).
    void reset_after_fork() {
        new (&mutex_) std::mutex();
        new (&batch_) std::mutex();
        new (&wake_) std::condition_variable();
        new (&done_) std::condition_variable();
        new std::vector<std::thread>(std::move(threads_));
        threads_ = std::vector<std::thread>();
        job_ = nullptr;
        running_ = 0;
        wanted_ = 0;
    }

private:
    //! The next block to run; blocks_ (none) once the batch is stopped.
    int take() { return stopped_.load(std::memory_order_relaxed) ? blocks_ : next_.fetch_add(1); }

    void work() {
        for (int b = take(); b < blocks_; b = take()) (*job_)(b);
    }

    void loop(int index) {
        long seen = 0;
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return generation_ != seen && index < wanted_; });
                seen = generation_;
            }
            work();
            std::lock_guard<std::mutex> lock(mutex_);
            if (--running_ == 0) done_.notify_one();
        }
    }

    std::mutex batch_;  // one batch at a time uses the pool
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<std::thread> threads_;
    const std::function<void(int)>* job_ = nullptr;
    std::atomic<int> next_{0};
    std::atomic<bool> stopped_{false};  // the caller's stop() said true: no block starts
    int blocks_ = 0;
    int wanted_ = 0;
    int running_ = 0;
    long generation_ = 0;
};

// Never destroyed: threads still waiting at exit must not meet a destroyed pool.
Pool& pool() {
    static Pool* p = [] {
        auto* created = new Pool();
        pthread_atfork(nullptr, nullptr, [] { pool().reset_after_fork(); });
        return created;
    }();
    return *p;
}

}  // namespace

int hardware_threads() {
    // read once: glibc reads /sys/devices/system/cpu/online on every call (10-15 µs, as
    // much as a batch of a few targets), and the machine's threads do not change under a
    // running process
    static const int threads = [] {
        const unsigned n = std::thread::hardware_concurrency();
        return n == 0 ? 1 : static_cast<int>(n);
    }();
    return threads;
}

bool parallel_for(int blocks, int workers, const std::function<void(int)>& fn,
                  const std::function<bool()>& stop) {
    if (blocks <= 0) return true;
    if (workers > blocks) workers = blocks;
    if (workers <= 1) return Pool::run_alone(blocks, fn, stop);
    return pool().run(blocks, workers, fn, stop);
}

}  // namespace kmpy
