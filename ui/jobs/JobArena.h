#pragma once
/// @file JobArena.h
/// The TBB arena the background jobs run their core work in (see JobPool). Every thread that
/// works in it runs at a lower scheduling priority than the GUI thread (nice 10 on Linux), so
/// that the event loop and the display server are never starved by a job. Free of Qt: TBB has a
/// function named emit(), which Qt defines away as a keyword.

#include <functional>
#include <memory>

namespace scanpick::ui {

class JobArena {
public:
  /// Room for `jobs` threads running jobs (each has a slot of its own, so no job waits for
  /// another to leave) and `helpers` of TBB's worker threads.
  JobArena(int jobs, int helpers);
  ~JobArena();
  JobArena(const JobArena&) = delete;
  JobArena& operator=(const JobArena&) = delete;

  /// Runs `work` on the calling thread inside the arena, isolated: while this thread waits in
  /// one of the work's parallel loops it runs only that work's tasks, never another job's.
  /// Exceptions from `work` reach the caller.
  void execute(const std::function<void()>& work);

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

} // namespace scanpick::ui
