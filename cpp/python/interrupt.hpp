// A batch that Ctrl-C stops: the GIL released while it runs, Python's signals read
// between its blocks.
//
// Python's own handler of SIGINT only notes the signal; the KeyboardInterrupt is raised
// when the interpreter next runs (PyErr_CheckSignals), which it does not while the core
// holds the caller's thread for a whole batch. So the caller's thread, between the blocks
// it runs, takes the GIL back at most every POLL_INTERVAL and asks; on a pending
// KeyboardInterrupt (or any exception a signal handler raises) no further block starts,
// the blocks running finish, and the call raises it: the results are dropped, the
// interpreter and the core's threads are as before.
#pragma once

#include <nanobind/nanobind.h>

#include <chrono>
#include <functional>

#include "pool.hpp"

namespace kmpy {

namespace nb = nanobind;

//! Longest wait (s) between two looks at Python's signals during a batch: a Ctrl-C stops
//! it within this plus one block's time (a block: FK_BLOCK configurations, TARGET_BLOCK
//! targets). A look costs taking the GIL (about a microsecond when no other thread holds
//! it), 1e-4 of the time at this interval.
constexpr double POLL_INTERVAL = 0.01;

//! A look at Python's signals from a thread that released the GIL, at most every
//! POLL_INTERVAL: true when a signal handler raised (KeyboardInterrupt), the exception
//! then set on this thread for nb::python_error to raise once the GIL is held again.
class SignalPoll {
public:
    bool operator()() {
        const Clock::time_point now = Clock::now();
        if (now - last_ < interval_) return false;
        last_ = now;
        nb::gil_scoped_acquire acquire;
        return PyErr_CheckSignals() != 0;
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::duration interval_ =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(POLL_INTERVAL));
    Clock::time_point last_ = Clock::now();
};

//! Run fn(b) for every block b in [0, blocks) on up to `workers` threads, the GIL
//! released, called with the GIL held; a signal handler's exception (KeyboardInterrupt)
//! stops it between blocks and is raised here. fn must not throw or touch Python.
inline void run_blocks(int blocks, int workers, const std::function<void(int)>& fn) {
    SignalPoll interrupted;
    bool done = false;
    {
        nb::gil_scoped_release release;
        done = parallel_for(blocks, workers, fn, std::ref(interrupted));
    }
    if (!done) throw nb::python_error();
}

//! Rows [0, rows) in blocks of `block` rows, fn(begin, end) for each, through run_blocks. A
//! batch of one block runs here, the GIL held: it is over within a block's time anyway
//! (there is no look between blocks to make), and releasing and taking back the GIL
//! would cost more than a single row of the cheapest batches (wrap, so3_log: 20-30 ns).
template <class Fn>
void run_rows(long rows, long block, int workers, const Fn& fn) {
    if (rows <= block) {
        if (rows > 0) fn(0L, rows);
        return;
    }
    const int blocks = static_cast<int>((rows + block - 1) / block);
    run_blocks(blocks, workers, [&](int blk) {
        const long begin = static_cast<long>(blk) * block;
        fn(begin, begin + block < rows ? begin + block : rows);
    });
}

}  // namespace kmpy

