#include "ui/jobs/JobArena.h"

#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace scanpick::ui {
namespace {

/// Nice value of the threads doing a job's work: below the GUI thread and the display server,
/// which then get a core as soon as they have something to do (a frame to draw, an event),
/// instead of waiting for a time slice among the job's threads. Jobs lose nothing when the
/// machine is otherwise idle.
constexpr int kJobNice = 10;

/// Lowers the calling thread's scheduling priority to kJobNice (once per thread; Linux sets the
/// nice value per thread). Elsewhere, nothing.
void lowerCurrentThreadPriority() {
#ifdef __linux__
  thread_local bool lowered = false;
  if (lowered)
    return;
  lowered = true;
  const auto tid = static_cast<id_t>(::syscall(SYS_gettid));
  if (::getpriority(PRIO_PROCESS, tid) < kJobNice)
    ::setpriority(PRIO_PROCESS, tid, kJobNice);
#endif
}

/// Lowers the priority of every thread that enters the arena (TBB's workers included).
class LowerPriority : public tbb::task_scheduler_observer {
public:
  explicit LowerPriority(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) {
    observe(true);
  }
  ~LowerPriority() override { observe(false); }
  void on_scheduler_entry(bool /*is_worker*/) override { lowerCurrentThreadPriority(); }
};

} // namespace

struct JobArena::Impl {
  tbb::task_arena arena;
  std::unique_ptr<LowerPriority> lower; // destroyed before the arena it observes
};

JobArena::JobArena(int jobs, int helpers) : m_impl(std::make_unique<Impl>()) {
  m_impl->arena.initialize(jobs + helpers, static_cast<unsigned>(jobs));
  m_impl->lower = std::make_unique<LowerPriority>(m_impl->arena);
}

JobArena::~JobArena() = default;

void JobArena::execute(const std::function<void()>& work) {
  lowerCurrentThreadPriority();
  m_impl->arena.execute([&work] { tbb::this_task_arena::isolate(work); });
}

} // namespace scanpick::ui
