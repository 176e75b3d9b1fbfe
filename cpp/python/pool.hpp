// The core's own threads: a batch runs its blocks on up to `workers` of them.
//
// The pool starts its threads when a batch first asks for them and keeps them waiting
// between batches. A call never changes a process-wide setting: each batch says how many
// threads it uses. A batch from a second Python thread while one runs (the GIL is
// released) runs on its caller's thread alone. After fork() the child starts afresh.
#pragma once

#include <functional>

namespace kmpy {

//! Run fn(b) for every block b in [0, blocks) on up to `workers` threads (the caller's
//! included); returns when all are done. After each block the caller's thread runs (but the
//! last) it asks stop(), when given: once that says true no thread starts another block
//! (those running finish theirs), and the call returns false. fn and stop must not throw.
bool parallel_for(int blocks, int workers, const std::function<void(int)>& fn,
                  const std::function<bool()>& stop = {});

//! The number of threads the machine offers (at least 1).
int hardware_threads();

}  // namespace kmpy
