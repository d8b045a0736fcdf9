#pragma once
/// @file ParallelProgress.h
/// A parallel loop that reports its progress, for the synchronous core algorithms.

#include "core/common/Progress.h"

#include <cstddef>
#include <mutex>
#include <tbb/parallel_for.h>

namespace scanpick::core {

/// Runs `work(i)` for every i in [0, n) in parallel (TBB) and reports the share of items done to
/// `progress`, one thread at a time, after every `report_every` items and after the last. A
/// Cancelled thrown by the report (or by `work`) stops the loop and reaches the caller.
template <typename Work>
void parallelForWithProgress(std::size_t n, const ProgressFn& progress, Work&& work,
                             std::size_t report_every = 1) {
  std::mutex mutex;
  std::size_t done = 0;
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    work(i);
    if (!progress)
      return;
    const std::lock_guard lock(mutex);
    ++done;
    if (done % report_every == 0 || done == n)
      reportProgress(progress, double(done) / double(n));
  });
}

} // namespace scanpick::core
