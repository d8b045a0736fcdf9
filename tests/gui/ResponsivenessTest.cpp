// The GUI thread never waits on core work: with the whole-bin keypoint preview and a recognition
// of the demo bin running together, a 50 ms timer on the GUI thread keeps firing (no tick a second
// late: a freeze lasts seconds), and Esc stops the recognition within a second. The figures
// against the goals (p99 lateness 100 ms, Esc 200 ms) are printed, not asserted: a shared CI
// machine's scheduling is not the product's.
#include "core/params/ParamsJson.h"
#include "tests/gui/SyntheticScenes.h"
#include "ui/MainWindow.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"

#include <QElapsedTimer>
#include <QSignalSpy>
#include <QTest>
#include <QTimer>
#include <algorithm>
#include <gtest/gtest.h>

using namespace scanpick;
using ui::MainWindow;

namespace {

/// How late a repeating 50 ms timer on the GUI thread fires, tick after tick: each sample is the
/// time between two ticks minus 50 ms. A frozen event loop shows as one large sample.
class TickLateness : public QObject {
public:
  static constexpr int kPeriodMs = 50;
  TickLateness() {
    m_timer.setTimerType(Qt::PreciseTimer);
    m_timer.setInterval(kPeriodMs);
    connect(&m_timer, &QTimer::timeout, this, [this] {
      const qint64 now = m_clock.nsecsElapsed();
      m_late_ms.push_back(static_cast<double>(now - m_last) / 1e6 - kPeriodMs);
      if (m_late_ms.back() > 100)
        m_stalls.push_back({static_cast<double>(now) / 1e6, m_late_ms.back()});
      m_last = now;
    });
  }
  void start() {
    m_late_ms.clear();
    m_clock.start();
    m_last = 0;
    m_timer.start();
  }
  void stop() {
    m_timer.stop();
    // The time since the last tick counts too: a freeze at the very end is a late tick.
    m_late_ms.push_back(static_cast<double>(m_clock.nsecsElapsed() - m_last) / 1e6 - kPeriodMs);
  }
  [[nodiscard]] std::size_t count() const { return m_late_ms.size(); }
  /// Ticks more than 100 ms late: (when, ms since start; how late, ms).
  [[nodiscard]] const std::vector<std::pair<double, double>>& stalls() const { return m_stalls; }
  [[nodiscard]] double quantile(double q) const {
    std::vector<double> sorted = m_late_ms;
    std::sort(sorted.begin(), sorted.end());
    return sorted.empty() ? 0.0
                          : sorted[std::min(sorted.size() - 1,
                                            static_cast<std::size_t>(q * double(sorted.size())))];
  }

private:
  QTimer m_timer;
  QElapsedTimer m_clock;
  qint64 m_last = 0;
  std::vector<double> m_late_ms;
  std::vector<std::pair<double, double>> m_stalls;
};

struct Responsiveness : ::testing::Test {
  test::DemoScenes scenes;
  MainWindow window;
  void SetUp() override {
    const core::RecognitionParams params =
        core::loadPreset(test::phoxiBinPreset().toStdString()).params;
    const auto model =
        scenes.teachView(scenes.teach_scan, scenes.teach_truth, "support.spmodel", params);
    window.setPreviewDelay(20);
    window.resize(1200, 800);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    // Esc reaches the active window only.
    window.activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
    window.parameterPanel()->loadPresetFile(test::phoxiBinPreset());
    ASSERT_TRUE(window.openModel(QString::fromStdString(model.string())));
    QSignalSpy loaded(&window, &MainWindow::scanLoaded);
    window.openScan(QString::fromStdString(scenes.bin_scan.string()));
    ASSERT_TRUE(loaded.wait(30000)) << window.logDock()->text().toStdString();
    // The opened scan's own preview and the model's preparation end first: each run below starts
    // from the same idle window.
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return !window.previewJobs()->busy() && !window.prepareJobs()->busy(); }, 120000));
  }
  /// Starts the whole-bin keypoint/feature preview (the slow one of the issue: every point of
  /// the scan) and a recognition of the bin, together.
  void startPreviewAndRecognition() {
    window.refreshPreview();
    window.recognize();
    ASSERT_TRUE(window.previewJobs()->busy());
    ASSERT_TRUE(window.recognizeJobs()->busy());
  }
};

} // namespace

TEST_F(Responsiveness, EventLoopKeepsTurningDuringPreviewAndRecognition) {
  // For 6 s the operator tunes the keypoint radius while recognizing, over and over: each
  // preview that arrives changes the radius (so the next preview starts, debounced), and each
  // recognition that ends starts another (with the radius of the moment: no stage is cached).
  // Both jobs fill the cores all along, and their results are drawn on the GUI thread.
  constexpr qint64 kTuningMs = 6000;
  QElapsedTimer clock;
  bool tuning = true;
  int previews = 0, recognitions = 0;
  QObject::connect(&window, &MainWindow::previewUpdated, &window, [&] {
    ++previews;
    if (tuning)
      window.parameterPanel()->setValue("keypoints.neighbourhood_radius_mm",
                                        previews % 2 ? 3.2 : 3.0);
  });
  QObject::connect(&window, &MainWindow::recognitionFinished, &window, [&](bool ok) {
    EXPECT_TRUE(ok) << window.logDock()->text().toStdString();
    ++recognitions;
    if (tuning)
      QTimer::singleShot(0, &window, &MainWindow::recognize);
  });
  TickLateness lateness;
  lateness.start();
  clock.start();
  startPreviewAndRecognition();
  ASSERT_TRUE(QTest::qWaitFor([&] { return clock.elapsed() >= kTuningMs; }, kTuningMs + 1000));
  tuning = false;
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return !window.previewJobs()->busy() && !window.recognizeJobs()->busy(); }, 120000));
  lateness.stop();
  std::printf("event loop during %d previews and %d recognitions together (%lld ms, %zu ticks of "
              "50 ms): lateness p50 %.1f ms, p99 %.1f ms, max %.1f ms\n",
              previews, recognitions, static_cast<long long>(clock.elapsed()), lateness.count(),
              lateness.quantile(0.5), lateness.quantile(0.99), lateness.quantile(1.0));
  for (const auto& [when, late] : lateness.stalls())
    std::printf("  tick at %.0f ms came %.0f ms late\n", when, late);
  ASSERT_GE(previews, 2) << "the preview never ran alongside a recognition";
  ASSERT_GE(recognitions, 2);
  EXPECT_LE(lateness.quantile(1.0), 1000.0) << "the GUI thread was blocked";
}

TEST_F(Responsiveness, EscapeStopsTheRecognition) {
  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  QSignalSpy progress(window.recognizeJobs(), &ui::JobRunner::progress);
  startPreviewAndRecognition();
  // Well into the work (past loading and floor removal), with the preview still running.
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return !progress.isEmpty() && progress.last().at(0).toDouble() >= 0.1; }, 60000));
  ASSERT_TRUE(window.recognizeJobs()->busy()) << "the recognition ended before it was cancelled";
  QElapsedTimer clock;
  clock.start();
  QTest::keyClick(&window, Qt::Key_Escape);
  ASSERT_TRUE(finished.wait(5000));
  const qint64 reported_ms = clock.elapsed();
  EXPECT_FALSE(finished.first().at(0).toBool()) << "a cancelled recognition is not accepted";
  ASSERT_TRUE(QTest::qWaitFor([&] { return !window.recognizeJobs()->busy(); }, 5000));
  const qint64 stopped_ms = clock.elapsed();
  std::printf("Esc: recognition reported stopped after %lld ms, its thread free after %lld ms\n",
              static_cast<long long>(reported_ms), static_cast<long long>(stopped_ms));
  EXPECT_LE(stopped_ms, 1000) << "the recognition went on after Esc";
  EXPECT_EQ(window.lastResult(), nullptr);
}

TEST_F(Responsiveness, ANewRecognitionCancelsTheStaleOne) {
  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  window.recognize();
  window.recognize();
  ASSERT_TRUE(QTest::qWaitFor([&] { return finished.count() == 2; }, 120000))
      << window.logDock()->text().toStdString();
  EXPECT_FALSE(finished.at(0).at(0).toBool()) << "the first, stale, recognition was shown";
  EXPECT_TRUE(finished.at(1).at(0).toBool()) << window.logDock()->text().toStdString();
  EXPECT_GE(window.recognizeJobs()->droppedCount(), 1);
  ASSERT_NE(window.lastResult(), nullptr);
}
