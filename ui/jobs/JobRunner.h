#pragma once
/// @file JobRunner.h
/// Background jobs for the GUI: QtConcurrent::run with a QPromise, results back on the GUI thread
/// through a QFutureWatcher. Each job has a generation number; starting a job cancels the
/// running one (its ProgressFn returns false) and a result from an older generation is dropped,
/// so a slow stale job can never overwrite a newer preview. Jobs run on a JobPool (bounded, and
/// isolated from the GUI thread) or, without one, on Qt's global pool. Never blocks the GUI
/// thread.

#include "core/common/Error.h"
#include "core/common/Progress.h"
#include "ui/jobs/JobPool.h"

#include <QFutureWatcher>
#include <QObject>
#include <QPromise>
#include <QString>
#include <QtConcurrent/QtConcurrentRun>
#include <exception>
#include <functional>
#include <memory>

namespace scanpick::ui {

/// Result of one job: an immutable value shared with the GUI thread, or an error message.
template <typename R> struct JobOutcome {
  std::shared_ptr<const R> value; ///< null when the job failed or was cancelled
  QString error;                  ///< the core::Error text, empty on success
  bool cancelled = false;
};

/// Runs one kind of job at a time (e.g. "preview", "recognize"); see the file comment.
class JobRunner : public QObject {
  Q_OBJECT
public:
  explicit JobRunner(QObject* parent = nullptr) : QObject(parent) {}
  /// Runs its jobs on `pool`, which must outlive the jobs (JobPool's destructor waits for them).
  explicit JobRunner(JobPool* pool, QObject* parent = nullptr) : QObject(parent), m_pool(pool) {}
  ~JobRunner() override;

  /// Starts `work` on the thread pool, cancelling the running job. `on_done` runs on the GUI
  /// thread with the result if this job is still the newest; `on_error` with the message if it
  /// threw. Returns the job's generation.
  template <typename R>
  quint64 run(std::function<R(const core::ProgressFn&)> work,
              std::function<void(std::shared_ptr<const R>)> on_done,
              std::function<void(const QString&)> on_error = {});

  /// Cancels the running job; its result is dropped even if it was already computed.
  void cancel();
  [[nodiscard]] bool busy() const { return m_running > 0; }
  /// Generation of the newest job (cancel() advances it, so numbers may skip).
  [[nodiscard]] quint64 generation() const { return m_generation; }
  /// Results that arrived after a newer job had started and were discarded.
  [[nodiscard]] int droppedCount() const { return m_dropped; }

signals:
  /// Progress of the newest job, in [0, 1].
  void progress(double fraction);
  void busyChanged(bool busy);
  /// A job ended: `accepted` is false when its result was stale, cancelled or an error.
  void jobFinished(quint64 generation, bool accepted);

private:
  void jobStarted(QFutureWatcherBase* watcher);
  void jobEnded(QFutureWatcherBase* watcher);

  JobPool* m_pool = nullptr;
  QFutureWatcherBase* m_current = nullptr;
  quint64 m_generation = 0;
  int m_running = 0;
  int m_dropped = 0;
};

template <typename R>
quint64 JobRunner::run(std::function<R(const core::ProgressFn&)> work,
                       std::function<void(std::shared_ptr<const R>)> on_done,
                       std::function<void(const QString&)> on_error) {
  cancel();
  const quint64 gen = ++m_generation;
  auto* watcher = new QFutureWatcher<JobOutcome<R>>(this);
  connect(watcher, &QFutureWatcherBase::progressValueChanged, this, [this, gen](int value) {
    if (gen == m_generation)
      emit progress(value / 1000.0);
  });
  connect(watcher, &QFutureWatcherBase::finished, this, [this, watcher, gen, on_done, on_error] {
    jobEnded(watcher);
    const auto future = watcher->future();
    // A cancelled QPromise discards its result, so a cancelled job has none.
    const bool has_result = future.resultCount() > 0;
    JobOutcome<R> outcome = has_result ? future.result() : JobOutcome<R>{{}, {}, true};
    const bool newest = gen == m_generation;
    bool accepted = false;
    if (!newest || outcome.cancelled) {
      ++m_dropped;
    } else if (outcome.value) {
      on_done(outcome.value);
      accepted = true;
    } else if (on_error) {
      on_error(outcome.error);
    }
    emit jobFinished(gen, accepted);
  });
  JobPool* pool = m_pool;
  auto job = [work = std::move(work), pool](QPromise<JobOutcome<R>>& promise) {
    // Cancelled while it waited in the queue: nothing to do.
    if (promise.isCanceled())
      return;
    promise.setProgressRange(0, 1000);
    const core::ProgressFn progress = [&promise](double fraction) {
      promise.setProgressValue(static_cast<int>(fraction * 1000));
      return !promise.isCanceled();
    };
    JobOutcome<R> outcome;
    try {
      const auto compute = [&] { outcome.value = std::make_shared<const R>(work(progress)); };
      if (pool)
        pool->execute(compute);
      else
        compute();
    } catch (const core::Cancelled&) {
      outcome.cancelled = true;
    } catch (const std::exception& e) {
      outcome.error = QString::fromStdString(e.what());
    }
    promise.addResult(std::move(outcome));
  };
  watcher->setFuture(pool ? QtConcurrent::run(pool->threadPool(), std::move(job))
                          : QtConcurrent::run(std::move(job)));
  jobStarted(watcher);
  return gen;
}

} // namespace scanpick::ui
