#include "ui/jobs/JobPool.h"

#include <QThread>
#include <algorithm>

namespace scanpick::ui {

JobPool::JobPool(int threads) {
  const int cores = std::max(1, QThread::idealThreadCount());
  if (threads <= 0)
    threads = std::max(2, cores);
  m_threads.setMaxThreadCount(threads);
  m_threads.setObjectName(QStringLiteral("scanpick-jobs"));
  m_arena = std::make_unique<JobArena>(threads, cores - 1);
}

JobPool::~JobPool() {
  m_threads.waitForDone();
}

} // namespace scanpick::ui
