#pragma once
/// @file Progress.h
/// Progress and cancellation for the synchronous core algorithms.

#include <functional>

namespace scanpick::core {

/// Called with the fraction done in [0, 1]; returning false asks the algorithm to stop, which it
/// does by throwing scanpick::core::Cancelled at its next check. An empty function never cancels.
using ProgressFn = std::function<bool(double fraction)>;

/// Reports `fraction` to `progress` and throws Cancelled if the callback asked to stop.
void reportProgress(const ProgressFn& progress, double fraction);

/// Maps a sub-task's [0, 1] progress into [begin, end] of the parent's progress.
ProgressFn subProgress(const ProgressFn& parent, double begin, double end);

} // namespace scanpick::core
