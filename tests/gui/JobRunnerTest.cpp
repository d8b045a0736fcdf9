// The GUI's background jobs: results come back on the GUI thread, a newer job makes an older
// one's result stale (dropped), and cancel() reaches the core through ProgressFn returning false.
#include "ui/jobs/JobRunner.h"

#include <QSignalSpy>
#include <QTest>
#include <QThread>
#include <atomic>
#include <gtest/gtest.h>

using scanpick::ui::JobRunner;
namespace core = scanpick::core;

TEST(JobRunner, ResultArrivesOnGuiThread) {
  JobRunner runner;
  QThread* gui = QThread::currentThread();
  QThread* done_thread = nullptr;
  int value = 0;
  runner.run<int>([](const core::ProgressFn&) { return 42; },
                  [&](std::shared_ptr<const int> v) {
                    value = *v;
                    done_thread = QThread::currentThread();
                  });
  QSignalSpy spy(&runner, &JobRunner::jobFinished);
  ASSERT_TRUE(spy.wait(5000));
  EXPECT_EQ(value, 42);
  EXPECT_EQ(done_thread, gui);
}

TEST(JobRunner, StaleResultIsDropped) {
  JobRunner runner;
  // Job 1 ignores cancellation and only ends when released, after job 2 was started, so its
  // result certainly arrives late.
  std::atomic<bool> release{false};
  std::vector<int> delivered;
  QSignalSpy spy(&runner, &JobRunner::jobFinished);
  runner.run<int>(
      [&release](const core::ProgressFn&) {
        while (!release.load())
          QThread::msleep(2);
        return 1;
      },
      [&](std::shared_ptr<const int> v) { delivered.push_back(*v); });
  const quint64 second =
      runner.run<int>([](const core::ProgressFn&) { return 2; },
                      [&](std::shared_ptr<const int> v) { delivered.push_back(*v); });
  release = true;
  ASSERT_TRUE(QTest::qWaitFor([&] { return spy.count() == 2; }, 5000));
  ASSERT_EQ(delivered.size(), 1u);
  EXPECT_EQ(delivered.front(), 2);
  EXPECT_EQ(runner.droppedCount(), 1);
  EXPECT_GE(runner.generation(), second);
}

TEST(JobRunner, CancelStopsTheWorkThroughProgress) {
  JobRunner runner;
  std::atomic<int> steps{0};
  bool done_called = false;
  runner.run<int>(
      [&steps](const core::ProgressFn& progress) {
        // A long loop that checks progress like the core's algorithms do.
        for (int i = 0; i < 100000; ++i) {
          core::reportProgress(progress, i / 100000.0);
          ++steps;
          QThread::usleep(100);
        }
        return 0;
      },
      [&](std::shared_ptr<const int>) { done_called = true; });
  QSignalSpy spy(&runner, &JobRunner::jobFinished);
  ASSERT_TRUE(QTest::qWaitFor([&] { return steps.load() > 5; }, 5000));
  runner.cancel();
  ASSERT_TRUE(spy.wait(5000));
  EXPECT_FALSE(spy.first().at(1).toBool()) << "a cancelled job is not accepted";
  EXPECT_FALSE(done_called);
  EXPECT_LT(steps.load(), 100000) << "the job ran to the end despite cancel()";
  EXPECT_FALSE(runner.busy());
}

TEST(JobRunner, ErrorMessageReachesTheGui) {
  JobRunner runner;
  QString message;
  runner.run<int>([](const core::ProgressFn&) -> int { throw core::Error("bad input: fix it"); },
                  [](std::shared_ptr<const int>) {}, [&](const QString& e) { message = e; });
  QSignalSpy spy(&runner, &JobRunner::jobFinished);
  ASSERT_TRUE(spy.wait(5000));
  EXPECT_EQ(message, QStringLiteral("bad input: fix it"));
}

TEST(JobRunner, CancelBeforeStartDeliversNothing) {
  JobRunner runner;
  bool done_called = false;
  runner.run<int>(
      [](const core::ProgressFn& progress) {
        core::reportProgress(progress, 0.0);
        return 1;
      },
      [&](std::shared_ptr<const int>) { done_called = true; });
  runner.cancel();
  QSignalSpy spy(&runner, &JobRunner::jobFinished);
  ASSERT_TRUE(spy.wait(5000));
  EXPECT_FALSE(spy.first().at(1).toBool());
  EXPECT_FALSE(done_called);
}

TEST(JobRunner, CancelAfterTheWorkEndedStillDropsTheResult) {
  JobRunner runner;
  bool done_called = false;
  std::atomic<bool> ran{false};
  runner.run<int>(
      [&ran](const core::ProgressFn&) {
        ran = true;
        return 1;
      },
      [&](std::shared_ptr<const int>) { done_called = true; });
  // The work finishes on the pool; its result waits for the event loop, which has not run yet.
  while (!ran.load())
    QThread::msleep(1);
  QThread::msleep(20);
  runner.cancel();
  QSignalSpy spy(&runner, &JobRunner::jobFinished);
  ASSERT_TRUE(spy.wait(5000));
  EXPECT_FALSE(spy.first().at(1).toBool());
  EXPECT_FALSE(done_called) << "the operator cancelled: nothing may be shown";
}
