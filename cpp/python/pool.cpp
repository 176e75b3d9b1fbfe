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
    void run(int blocks, int workers, const std::function<void(int)>& fn) {
        std::unique_lock<std::mutex> batch(batch_, std::try_to_lock);
        if (!batch.owns_lock()) {  // another thread's batch holds the pool: run alone
            for (int b = 0; b < blocks; ++b) fn(b);
            return;
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
            wanted_ = helpers;
            running_ = helpers;
            ++generation_;
        }
        wake_.notify_all();
        work();
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return running_ == 0; });
        job_ = nullptr;
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
    void work() {
        for (int b = next_.fetch_add(1); b < blocks_; b = next_.fetch_add(1)) (*job_)(b);
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

void parallel_for(int blocks, int workers, const std::function<void(int)>& fn) {
    if (blocks <= 0) return;
    if (workers > blocks) workers = blocks;
    if (workers <= 1) {
        for (int b = 0; b < blocks; ++b) fn(b);
        return;
    }
    pool().run(blocks, workers, fn);
}

}  // namespace kmpy
