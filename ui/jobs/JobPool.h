#pragma once
/// @file JobPool.h
/// The threads a window's background jobs run on: a bounded QThreadPool, and a TBB arena
/// (JobArena) for the core's parallel loops. A job's core work runs inside the arena, isolated
/// from the other jobs. The GUI thread stays outside it: when the GUI thread runs a parallel loop
/// of its own (VTK computes bounds and ranges with TBB while it renders), TBB lets it wait only
/// on its own tasks, never on a job's long task, so the event loop keeps turning while jobs run.

#include "ui/jobs/JobArena.h"

#include <QThreadPool>
#include <functional>

namespace scanpick::ui {

class JobPool {
public:
  /// At most `threads` jobs run at once (more wait in the queue); their parallel loops use at
  /// most `threads` + ideal thread count − 1 threads together. 0 takes
  /// max(2, QThread::idealThreadCount()), so that a preview and a recognition run side by side.
  explicit JobPool(int threads = 0);
  /// Waits for the running jobs (cancel them first).
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  [[nodiscard]] QThreadPool* threadPool() { return &m_threads; }
  /// Runs a job's `work` on the calling (pool) thread, in the jobs' arena (JobArena::execute).
  void execute(const std::function<void()>& work) { m_arena->execute(work); }

private:
  QThreadPool m_threads;
  std::unique_ptr<JobArena> m_arena;
};

} // namespace scanpick::ui
