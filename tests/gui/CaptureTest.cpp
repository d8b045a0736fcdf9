// Capture and Live through the real devices layer: the `file:` camera replays simulated PhoXi
// scans (written at test time by core/sim) like a camera delivering frames.
#include "core/cloud/CloudIo.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/gui/SyntheticScenes.h"
#include "ui/MainWindow.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/DevicePanel.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMessageBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTest>
#include <gtest/gtest.h>

using namespace scanpick;
using ui::MainWindow;
namespace fs = std::filesystem;

namespace {

struct Capture : ::testing::Test {
  MainWindow window;
  ui::DevicePanel* panel = nullptr;
  void SetUp() override {
    window.resize(1200, 800);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    panel = window.devicePanel();
    ASSERT_NE(panel, nullptr);
  }
  /// Types `id` into the panel and presses Open, as an operator would.
  void openThroughUi(const QString& id) {
    auto* edit = panel->findChild<QLineEdit*>(QStringLiteral("deviceId"));
    auto* open = panel->findChild<QPushButton*>(QStringLiteral("openDeviceButton"));
    ASSERT_TRUE(edit && open);
    edit->setText(id);
    QTest::mouseClick(open, Qt::LeftButton);
  }
};

/// A folder of `copies` replays of the demo bin (file camera frames in name order).
fs::path replayFolder(const test::DemoScenes& scenes, int copies) {
  const fs::path dir = scenes.dir / "replay";
  fs::create_directories(dir);
  for (int i = 0; i < copies; ++i)
    fs::copy_file(scenes.bin_scan, dir / ("frame-" + std::to_string(i) + ".pcd"));
  return dir;
}

} // namespace

TEST_F(Capture, DeviceListOpenSingleShotAndSaveScan) {
  const test::DemoScenes scenes;
  // The device list is refreshed in the background; no camera is attached here, and the panel
  // says how to replay files instead.
  auto* list = panel->findChild<QListWidget*>(QStringLiteral("deviceList"));
  ASSERT_NE(list, nullptr);
  QSignalSpy listed(panel, &ui::DevicePanel::devicesListed);
  panel->findChild<QPushButton*>(QStringLiteral("refreshDevicesButton"))->click();
  ASSERT_TRUE(listed.wait(30000));
  EXPECT_EQ(list->count(), listed.last().at(0).toInt());
  EXPECT_FALSE(panel->stateText().isEmpty());

  QSignalSpy opened(panel, &ui::DevicePanel::cameraOpened);
  openThroughUi(
      QStringLiteral("file:%1").arg(QString::fromStdString(replayFolder(scenes, 2).string())));
  ASSERT_TRUE(opened.wait(30000)) << window.logDock()->text().toStdString();
  ASSERT_NE(panel->camera(), nullptr);
  EXPECT_TRUE(panel->stateText().startsWith(QStringLiteral("Open")));
  {
    // The last device is remembered: a new panel offers it.
    const ui::DevicePanel next;
    EXPECT_EQ(next.findChild<QLineEdit*>(QStringLiteral("deviceId"))->text(),
              panel->findChild<QLineEdit*>(QStringLiteral("deviceId"))->text());
  }

  QSignalSpy frames(panel, &ui::DevicePanel::frameCaptured);
  auto* capture = panel->findChild<QPushButton*>(QStringLiteral("captureButton"));
  ASSERT_TRUE(capture->isEnabled());
  QTest::mouseClick(capture, Qt::LeftButton);
  ASSERT_TRUE(frames.wait(30000)) << window.logDock()->text().toStdString();
  ASSERT_NE(window.scan(), nullptr);
  const core::PointCloud bin =
      core::loadCloud(scenes.bin_scan, core::LengthUnit::Millimetres).cloud;
  EXPECT_EQ(window.scan()->validCount(), bin.validCount()) << "the shot is the replayed scan";
  window.viewport()->requestRender();
  QTest::qWait(100);
  const QImage image = window.screenshot();
  image.save(test::screenshotDir() + "/capture-single-shot.png");
  EXPECT_GT(test::distinctColours(image), 20) << "the captured scan is not drawn";
  test::saveDocImage(window, "gui-capture.png");

  const fs::path saved = scenes.dir / "saved.pcd";
  ASSERT_TRUE(window.saveScan(QString::fromStdString(saved.string())));
  EXPECT_EQ(core::loadCloud(saved, core::LengthUnit::Millimetres).cloud.validCount(),
            bin.validCount());
}

TEST_F(Capture, LiveLoopRunsCyclesUntilStopped) {
  const test::DemoScenes scenes;
  // The demo's two views, taught through the core as `scanpick-cli demo` does, and opened
  // together: Live searches both.
  const core::RecognitionParams params =
      core::loadPreset(test::phoxiBinPreset().toStdString()).params;
  QStringList views;
  for (const auto& path : scenes.teachDemoViews(params))
    views << QString::fromStdString(path.string());
  ASSERT_TRUE(window.openModels(views));
  ASSERT_EQ(window.views().size(), 2u);

  // Live without a camera is refused with a dialog, and the window keeps running.
  window.setLiveRunning(true);
  EXPECT_FALSE(window.liveRunning());
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return window.findChild<QMessageBox*>(QStringLiteral("errorDialog")) != nullptr; },
      5000));

  QSignalSpy opened(panel, &ui::DevicePanel::cameraOpened);
  openThroughUi(
      QStringLiteral("file:%1").arg(QString::fromStdString(replayFolder(scenes, 4).string())));
  ASSERT_TRUE(opened.wait(30000)) << window.logDock()->text().toStdString();

  QSignalSpy cycles(&window, &MainWindow::liveCycleFinished);
  window.setLiveRunning(true);
  ASSERT_TRUE(window.liveRunning());
  ASSERT_TRUE(QTest::qWaitFor([&] { return cycles.count() >= 2; }, 50000));
  window.setLiveRunning(false);
  EXPECT_FALSE(window.liveRunning());
  ASSERT_TRUE(QTest::qWaitFor([&] { return !window.recognizeJobs()->busy(); }, 30000));
  const int after_stop = static_cast<int>(cycles.count());
  QTest::qWait(500);
  EXPECT_EQ(cycles.count(), after_stop) << "cycles went on after Live was stopped";
  EXPECT_LE(after_stop, 3) << "at most the cycle running when stopped may end after it";

  for (const QList<QVariant>& cycle : cycles) {
    EXPECT_GT(cycle.at(0).toDouble(), 0.0) << "cycle time";
    EXPECT_GE(cycle.at(1).toInt(), 0);
  }
  // The latest result is shown: the table has its detections and the status its cycle time.
  ASSERT_NE(window.lastResult(), nullptr);
  {
    // What the core finds in the last captured scene with the same views and parameters.
    core::Recognizer direct;
    const core::RecognitionResult expected =
        core::recognizeViews(direct, window.views(), *window.scan(),
                             core::sensorPreset("phoxi-m-1032"), window.parameterPanel()->params());
    ASSERT_EQ(window.lastResult()->detections.size(), expected.detections.size());
    for (std::size_t i = 0; i < expected.detections.size(); ++i) {
      EXPECT_EQ(window.lastResult()->detections[i].model_index, expected.detections[i].model_index);
      EXPECT_TRUE(window.lastResult()->detections[i].T_scene_model.isApprox(
          expected.detections[i].T_scene_model));
    }
  }
  EXPECT_EQ(window.resultsTable()->rowCount(),
            static_cast<int>(window.lastResult()->detections.size()));
  EXPECT_EQ(window.resultsTable()->rowCount(), cycles.last().at(1).toInt());
  auto* timings = window.findChild<QLabel*>(QStringLiteral("statusTimings"));
  ASSERT_NE(timings, nullptr);
  EXPECT_TRUE(timings->text().startsWith(QStringLiteral("cycle ")))
      << timings->text().toStdString();
  window.viewport()->requestRender();
  QTest::qWait(100);
  const QImage image = window.screenshot();
  image.save(test::screenshotDir() + "/live.png");
  EXPECT_GT(test::countGrey(image), 1000) << "the live scene (greys by depth) is not drawn";
  if (!window.lastResult()->detections.empty()) {
    EXPECT_GT(test::countColour(image, ui::detectionColour(0), 30), 20) << "detection not drawn";
  }
  test::saveDocImage(window, "gui-live.png");
}

TEST_F(Capture, InvalidOrUnpluggedDeviceShowsAnErrorAndTheWindowKeepsRunning) {
  const test::DemoScenes scenes;
  QSignalSpy errors(panel, &ui::DevicePanel::deviceError);
  // A replay folder that is gone (as after unplugging a drive), an unknown kind, a bad index.
  for (const QString& id : {QStringLiteral("file:/nonexistent/scanpick/scans"),
                            QStringLiteral("bogus:1"), QStringLiteral("kinect:abc")}) {
    const int before = static_cast<int>(errors.count());
    openThroughUi(id);
    ASSERT_TRUE(QTest::qWaitFor([&] { return errors.count() > before; }, 30000));
    EXPECT_EQ(panel->camera(), nullptr) << id.toStdString();
    EXPECT_FALSE(errors.last().at(0).toString().isEmpty());
  }
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return window.findChild<QMessageBox*>(QStringLiteral("errorDialog")) != nullptr; },
      5000));
  EXPECT_TRUE(window.logDock()->text().contains(QStringLiteral("Camera")));

  // A camera whose frames run out mid-use: the capture error is reported, nothing crashes.
  QSignalSpy opened(panel, &ui::DevicePanel::cameraOpened);
  openThroughUi(
      QStringLiteral("file:%1").arg(QString::fromStdString(replayFolder(scenes, 1).string())));
  ASSERT_TRUE(opened.wait(30000));
  QSignalSpy frames(panel, &ui::DevicePanel::frameCaptured);
  panel->captureOne();
  ASSERT_TRUE(frames.wait(30000));
  const int before = static_cast<int>(errors.count());
  panel->captureOne();
  ASSERT_TRUE(QTest::qWaitFor([&] { return errors.count() > before; }, 30000));
  EXPECT_NE(window.scan(), nullptr) << "the last good frame stays shown";
  EXPECT_TRUE(window.isVisible());
}
