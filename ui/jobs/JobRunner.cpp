#include "ui/jobs/JobRunner.h"

namespace scanpick::ui {

JobRunner::~JobRunner() {
  // Running jobs keep their own copies of inputs; cancel them so they end soon. Their results
  // are dropped with the watchers (children of this object).
  cancel();
}

void JobRunner::cancel() {
  if (m_current) {
    m_current->cancel();
    m_current = nullptr;
    // A result computed before the cancel but not yet delivered is stale too.
    ++m_generation;
  }
}

void JobRunner::jobStarted(QFutureWatcherBase* watcher) {
  m_current = watcher;
  if (m_running++ == 0)
    emit busyChanged(true);
}

void JobRunner::jobEnded(QFutureWatcherBase* watcher) {
  if (m_current == watcher)
    m_current = nullptr;
  watcher->deleteLater();
  if (--m_running == 0)
    emit busyChanged(false);
}

} // namespace scanpick::ui
