// The main window driven like an operator would: load a teach scan generated in code, crop the
// part with the box (undo/redo), place a grip point, preview keypoints/features, tune a
// parameter, teach, load a bin scene, recognize, and check the results table and the picture.
#include "ui/MainWindow.h"

#include "core/common/Log.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/unit/pipeline/IdealScene.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QSignalSpy>
#include <QTest>
#include <QTranslator>
#include <QUndoStack>
#include <gtest/gtest.h>
#include <thread>

using namespace scanpick;
using ui::MainWindow;

namespace {

Eigen::Isometry3d teachPose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 700);
  return T;
}

/// The thesis's ideal part at 700 mm, and a second copy 300 mm to its right that the crop must
/// cut away.
std::shared_ptr<const core::PointCloud> teachScan() {
  Eigen::Isometry3d other = teachPose();
  other.translation().x() = 300;
  return std::make_shared<const core::PointCloud>(
      test::idealScene(test::idealPartPoints(), {teachPose(), other}, 0.0, 1));
}

core::OrientedBox cropAroundPart() {
  core::OrientedBox box;
  box.T_scan_box.translation() = Eigen::Vector3f(15, 0, 700);
  box.half_extents_mm = Eigen::Vector3f(75, 75, 50);
  return box;
}

/// The ideal part's parameters as a named preset: Teach uses a preset's values as they are
/// (the panel's default choice would derive them from the part).
QString idealPreset() {
  const QString path = test::screenshotDir() + "/ideal-preset.json";
  core::savePreset(path.toStdString(),
                   core::Preset{"ideal", "the thesis's ideal part", test::idealParams(0.001)});
  return path;
}

struct WindowFixture : ::testing::Test {
  MainWindow window;
  void SetUp() override {
    window.setPreviewDelay(20);
    window.parameterPanel()->loadPresetFile(idealPreset());
    window.resize(1200, 800);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  }
};

} // namespace

TEST_F(WindowFixture, CropUndoRedoAndGripPoint) {
  const auto scan = teachScan();
  window.setScan(scan, QStringLiteral("teach"));
  EXPECT_EQ(window.part()->size(), scan->size());

  window.setCropBoxVisible(true);
  window.setCropBox(cropAroundPart());
  // The box read back from the VTK widget is the one set.
  const core::OrientedBox read = window.cropBox();
  EXPECT_NEAR(read.T_scan_box.translation().x(), 15.0f, 1e-3);
  EXPECT_NEAR(read.half_extents_mm.x(), 75.0f, 1e-3);
  ASSERT_TRUE(window.applyCrop());
  const std::size_t one_copy = test::idealPartPoints().size();
  EXPECT_EQ(window.part()->validCount(), one_copy) << "the crop keeps exactly the first copy";

  window.undoStack()->undo();
  EXPECT_EQ(window.part()->size(), scan->size());
  window.undoStack()->redo();
  EXPECT_EQ(window.part()->validCount(), one_copy);

  window.addGripPoint(Eigen::Vector3d(0, 0, 700));
  ASSERT_EQ(window.gripPoints().size(), 1u);
  EXPECT_FALSE(window.gripPoints().front().name.empty());
}

TEST_F(WindowFixture, PreviewFollowsParametersAndReusesKeypoints) {
  auto part = std::make_shared<const core::PointCloud>(
      test::idealScene(test::idealPartPoints(), {teachPose()}, 0.0, 1));
  QSignalSpy previews(&window, &MainWindow::previewUpdated);
  window.setScan(part, QStringLiteral("part"));
  ASSERT_TRUE(previews.wait(30000));
  const std::shared_ptr<const ui::PreviewResult> first = window.preview();
  ASSERT_NE(first, nullptr);
  // Δp = -1 keeps every point as a keypoint (thesis ideal test); two lines and two circles.
  EXPECT_EQ(first->keypoints->points_mm.size(), part->size());
  EXPECT_EQ(first->features.features.size(), 4u);
  EXPECT_GT(first->keypoints_ms, 0.0);
  {
    const QImage image = window.screenshot();
    image.save(test::screenshotDir() + "/teach-preview.png");
    EXPECT_GT(test::distinctColours(image), 10) << "blank screenshot";
    // Keypoints are drawn in yellow (255, 220, 0) and lines in cyan (0, 230, 255).
    EXPECT_GT(test::countColour(image, QColor(255, 220, 0)), 50) << "keypoints not drawn";
    EXPECT_GT(test::countColour(image, QColor(0, 230, 255)), 20) << "features not drawn";
  }

  // A features-stage change through the real editor: keypoints come from the cache.
  auto* spin = qobject_cast<QDoubleSpinBox*>(
      window.parameterPanel()->editor("features.circle_threshold_mm"));
  ASSERT_NE(spin, nullptr);
  spin->setValue(1.5);
  ASSERT_TRUE(previews.wait(30000));
  EXPECT_EQ(window.preview()->keypoints_ms, 0.0) << "keypoints were recomputed";
  EXPECT_EQ(window.preview()->keypoints.get(), first->keypoints.get());
  test::saveDocImage(window, "gui-tune.png");

  // Raising the ransac size above every feature's support empties the preview.
  window.parameterPanel()->setValue("features.ransac_size", 5000);
  ASSERT_TRUE(previews.wait(30000));
  EXPECT_TRUE(window.preview()->features.features.empty());
}

TEST_F(WindowFixture, RapidChangesDropStalePreviews) {
  auto part = std::make_shared<const core::PointCloud>(
      test::idealScene(test::idealPartPoints(), {teachPose()}, 0.0, 1));
  QSignalSpy previews(&window, &MainWindow::previewUpdated);
  window.setScan(part, QStringLiteral("part"));
  ASSERT_TRUE(previews.wait(30000));
  previews.clear();
  const int dropped_before = window.previewJobs()->droppedCount();
  // Two keypoint changes, each followed by an immediate preview, without returning to the event
  // loop in between: the first job is stale before its result can be delivered.
  window.parameterPanel()->setValue("keypoints.neighbourhood_radius_mm", 4.0);
  window.refreshPreview();
  window.parameterPanel()->setValue("keypoints.neighbourhood_radius_mm", 5.0);
  window.refreshPreview();
  ASSERT_TRUE(previews.wait(30000));
  ASSERT_TRUE(QTest::qWaitFor([&] { return !window.previewJobs()->busy(); }, 30000));
  QTest::qWait(300); // let the debounce timer started by setValue fire and settle, too
  ASSERT_TRUE(QTest::qWaitFor([&] { return !window.previewJobs()->busy(); }, 30000));
  EXPECT_GE(window.previewJobs()->droppedCount() - dropped_before, 1) << "stale job not dropped";
  ASSERT_NE(window.preview(), nullptr);
  EXPECT_EQ(window.preview()->keypoint_params.neighbourhood_radius_mm, 5.0)
      << "an older job's preview is shown";
}

TEST_F(WindowFixture, TeachRecognizeAndResultsTable) {
  window.setScan(teachScan(), QStringLiteral("teach"));
  window.setCropBoxVisible(true);
  window.setCropBox(cropAroundPart());
  ASSERT_TRUE(window.applyCrop());
  window.addGripPoint(Eigen::Vector3d(0, 0, 700));
  QSignalSpy taught(&window, &MainWindow::modelTaught);
  window.teach();
  ASSERT_TRUE(taught.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_NE(window.model(), nullptr);
  EXPECT_EQ(window.model()->features.size(), 4u);
  EXPECT_EQ(window.model()->grip_points.size(), 1u);

  // The bin scene: the thesis's 12 rotated copies.
  window.setScan(std::make_shared<const core::PointCloud>(
                     test::idealScene(test::idealPartPoints(), test::idealCopyPoses(), 0.0, 2024)),
                 QStringLiteral("bin"));
  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  window.recognize();
  ASSERT_TRUE(finished.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_TRUE(finished.first().at(0).toBool()) << window.logDock()->text().toStdString();
  const core::RecognitionResult* result = window.lastResult();
  ASSERT_NE(result, nullptr);
  EXPECT_EQ(result->detections.size(), 12u);
  ui::ResultsTable* table = window.resultsTable();
  ASSERT_EQ(table->rowCount(), static_cast<int>(result->detections.size()));
  for (int row = 0; row < table->rowCount(); ++row) {
    EXPECT_EQ(table->item(row, 0)->text(), QString::number(result->detections[row].score, 'f', 3));
    EXPECT_EQ(table->item(row, 4)->text().count(QLatin1Char('(')),
              static_cast<int>(result->detections[row].grip_points_scene.size()));
  }

  table->selectRow(0);
  window.viewport()->resetCamera();
  const QImage image = window.screenshot();
  image.save(test::screenshotDir() + "/recognize.png");
  EXPECT_GT(test::distinctColours(image), 20) << "blank screenshot";
  EXPECT_GT(test::countColour(image, ui::detectionColour(0)), 20)
      << "the selected detection's colour is not in the picture";
  test::saveDocImage(window, "gui-recognize-ideal.png");

  // Results export.
  const QString json = test::screenshotDir() + "/results.json";
  EXPECT_TRUE(window.exportResults(json));
  EXPECT_TRUE(QFile::exists(json));
}

// The Teach dock's part name (views of one part share it) and the part's pose in the scan (views
// that know it are joined). A pose that is not 7 numbers with a unit quaternion is refused with a
// dialog, and nothing is taught.
TEST_F(WindowFixture, TeachTakesThePartsNameAndPose) {
  window.setScan(teachScan(), QStringLiteral("teach"));
  window.setCropBoxVisible(true);
  window.setCropBox(cropAroundPart());
  ASSERT_TRUE(window.applyCrop());
  auto* name = window.findChild<QLineEdit*>(QStringLiteral("partNameEdit"));
  auto* pose = window.findChild<QLineEdit*>(QStringLiteral("partPoseEdit"));
  ASSERT_NE(name, nullptr);
  ASSERT_NE(pose, nullptr);
  name->setText(QStringLiteral("widget"));
  for (const QString& wrong : {QStringLiteral("1, 2, 3"), QStringLiteral("0, 0, 700, 1, 0, 0, 1"),
                               QStringLiteral("0, 0, 700, one, 0, 0, 0")}) {
    pose->setText(wrong);
    window.teach();
    EXPECT_EQ(window.model(), nullptr) << wrong.toStdString();
    EXPECT_FALSE(window.jobs()->busy()) << "nothing is taught";
  }
  EXPECT_NE(window.findChild<QMessageBox*>(QStringLiteral("errorDialog")), nullptr);
  EXPECT_TRUE(QTest::qWaitFor(
      [&] { return window.logDock()->text().contains(QStringLiteral("unit quaternion")); }, 5000));

  // A quarter turn about z, 700 mm in front of the camera.
  pose->setText(QStringLiteral("10, 20, 700, 0.70710678, 0, 0, 0.70710678"));
  QSignalSpy taught(&window, &MainWindow::modelTaught);
  window.teach();
  ASSERT_TRUE(taught.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_NE(window.model(), nullptr);
  EXPECT_EQ(window.model()->name, "widget");
  ASSERT_TRUE(window.model()->T_part_model);
  Eigen::Isometry3d T_scan_part = Eigen::Isometry3d::Identity();
  T_scan_part.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_scan_part.translation() = Eigen::Vector3d(10, 20, 700);
  EXPECT_TRUE(
      (T_scan_part * *window.model()->T_part_model).isApprox(window.model()->T_teach_model, 1e-6));
}

TEST_F(WindowFixture, CancelRecognition) {
  window.setScan(std::make_shared<const core::PointCloud>(
                     test::idealScene(test::idealPartPoints(), test::idealCopyPoses(), 0.5, 7)),
                 QStringLiteral("bin"));
  // A model taught directly through the core, then handed to the window through a file.
  core::TeachOptions options;
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  const core::TaughtModel taught =
      core::teach(test::idealScene(test::idealPartPoints(), {teachPose()}, 0.0, 1), options,
                  test::idealParams(0.5));
  const QString path = test::screenshotDir() + "/cancel-test.spmodel";
  core::saveModel(path.toStdString(), taught);
  ASSERT_TRUE(window.openModel(path));

  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  window.recognize();
  ASSERT_TRUE(window.recognizeJobs()->busy());
  // Cancelled right away: whether the job stops at a progress check or has already finished,
  // nothing may be delivered.
  window.cancelRecognition();
  ASSERT_TRUE(finished.wait(60000));
  EXPECT_FALSE(finished.first().at(0).toBool());
  EXPECT_EQ(window.lastResult(), nullptr);
  EXPECT_EQ(window.resultsTable()->rowCount(), 0);
}

// A view's own matching parameters are what the parameter panel shows and tunes; saving the model
// again keeps them.
TEST_F(WindowFixture, AViewsOwnParametersAreThePanelsValues) {
  core::TeachOptions options;
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  core::TaughtModel taught =
      core::teach(test::idealScene(test::idealPartPoints(), {teachPose()}, 0.0, 1), options,
                  test::idealParams(0.5));
  taught.view_params = {{"matching.min_coverage", 0.42}};
  // Verification on: there is something to prepare.
  taught.params.matching.verify_tolerance_mm = 0.5;
  ASSERT_NE(taught.params.matching.min_coverage, 0.42);
  const QString path = test::screenshotDir() + "/own-coverage.spmodel";
  core::saveModel(path.toStdString(), taught);
  ASSERT_TRUE(window.openModel(path));
  EXPECT_EQ(window.parameterPanel()->params().matching.min_coverage, 0.42);
  // The model is prepared for matching in the background right after it is opened.
  ASSERT_TRUE(QTest::qWaitFor([&] { return window.preparedModels() == std::size_t{1}; }, 30000));
  const QString again = test::screenshotDir() + "/own-coverage-again.spmodel";
  ASSERT_TRUE(window.saveModel(again));
  EXPECT_EQ(core::loadModel(again.toStdString()).view_params, taught.view_params);
}

TEST_F(WindowFixture, LogDockReceivesCoreLogFromAnyThread) {
  const int before = window.logDock()->lineCount();
  std::thread worker([] { core::logger()->info("message from a worker thread"); });
  worker.join();
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return window.logDock()->text().contains("message from a worker thread"); }, 5000));
  EXPECT_GT(window.logDock()->lineCount(), before);
}

// The Italian translation (translations/scanpick_it.ts, embedded as :/i18n/scanpick_it.qm) covers
// the window's menus, the teach tools included, in a window made with the translator installed
// (LanguageTest.cpp switches an open window).
TEST(Translation, ItalianMenusOfANewWindow) {
  QTranslator italian;
  ASSERT_TRUE(italian.load(QStringLiteral(":/i18n/scanpick_it.qm")));
  QCoreApplication::installTranslator(&italian);
  QStringList titles;
  QStringList teach_entries, file_entries;
  {
    MainWindow window;
    for (QAction* menu_action : window.menuBar()->actions()) {
      titles << menu_action->text();
      if (menu_action->menu() && menu_action->text() == QStringLiteral("&Insegna"))
        for (QAction* a : menu_action->menu()->actions())
          teach_entries << a->text();
      if (menu_action->menu() && menu_action->text() == QStringLiteral("&File"))
        for (QAction* a : menu_action->menu()->actions())
          file_entries << a->text();
    }
  }
  QCoreApplication::removeTranslator(&italian);
  EXPECT_TRUE(titles.contains(QStringLiteral("&Modifica"))) << titles.join(' ').toStdString();
  EXPECT_TRUE(teach_entries.contains(QStringLiteral("Ritaglio a &lazo")))
      << teach_entries.join(" | ").toStdString();
  EXPECT_TRUE(teach_entries.contains(QStringLiteral("&Anteprima pavimento")));
  EXPECT_TRUE(file_entries.contains(QStringLiteral("&Aggiungi vista del modello…")))
      << file_entries.join(" | ").toStdString();
  EXPECT_EQ(QCoreApplication::translate("scanpick::ui::MainWindow", "&Language"),
            QStringLiteral("&Language"))
      << "without the translator the English text is back";
}

TEST(ResultsTableFreeTurn, MarksATurnTheScanDoesNotShow) {
  // Two detections: one with a free turn axis (a pipe found by a view taken from its side), one
  // without; only the first is marked, and its tooltip names the axis. In Italian too.
  std::vector<core::Detection> detections(2);
  detections[0].score = 0.9;
  detections[0].free_turn_axis = core::FreeTurnAxis{{10, 20, 700}, {0, 1, 0}};
  detections[1].score = 0.8;
  ui::ResultsTable table;
  table.setDetections(detections, {});
  ASSERT_EQ(table.rowCount(), 2);
  EXPECT_TRUE(table.item(0, 2)->text().endsWith(QStringLiteral("(turn free)")))
      << table.item(0, 2)->text().toStdString();
  EXPECT_TRUE(table.item(0, 2)->toolTip().contains(QStringLiteral("0.000, 1.000, 0.000")))
      << table.item(0, 2)->toolTip().toStdString();
  EXPECT_FALSE(table.item(1, 2)->text().contains(QStringLiteral("free")));
  EXPECT_TRUE(table.item(1, 2)->toolTip().isEmpty());

  QTranslator italian;
  ASSERT_TRUE(italian.load(QStringLiteral(":/i18n/scanpick_it.qm")));
  QCoreApplication::installTranslator(&italian);
  table.setDetections(detections, {});
  QCoreApplication::removeTranslator(&italian);
  EXPECT_TRUE(table.item(0, 2)->text().endsWith(QStringLiteral("(rotazione libera)")))
      << table.item(0, 2)->text().toStdString();
  EXPECT_TRUE(table.item(0, 2)->toolTip().contains(QStringLiteral("il manico di una tazza")))
      << table.item(0, 2)->toolTip().toStdString();
}

TEST(ResultsTableFreeTurn, MarksAlternativePosesTheScanCannotTellApart) {
  // A detection with one alternative pose (a near symmetry whose telling detail is hidden) is
  // marked, with the count in its tooltip; in Italian too.
  std::vector<core::Detection> detections(2);
  detections[0].score = 0.9;
  detections[0].alternative_poses = {
      Eigen::Isometry3d(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()))};
  detections[1].score = 0.8;
  ui::ResultsTable table;
  table.setDetections(detections, {});
  ASSERT_EQ(table.rowCount(), 2);
  EXPECT_TRUE(table.item(0, 2)->text().endsWith(QStringLiteral("(turn unsure)")))
      << table.item(0, 2)->text().toStdString();
  EXPECT_TRUE(table.item(0, 2)->toolTip().contains(QStringLiteral("from 1 other pose")))
      << table.item(0, 2)->toolTip().toStdString();
  EXPECT_FALSE(table.item(1, 2)->text().contains(QStringLiteral("unsure")));

  QTranslator italian;
  ASSERT_TRUE(italian.load(QStringLiteral(":/i18n/scanpick_it.qm")));
  QCoreApplication::installTranslator(&italian);
  table.setDetections(detections, {});
  QCoreApplication::removeTranslator(&italian);
  EXPECT_TRUE(table.item(0, 2)->text().endsWith(QStringLiteral("(rotazione incerta)")))
      << table.item(0, 2)->text().toStdString();
  EXPECT_TRUE(table.item(0, 2)->toolTip().contains(QStringLiteral("da 1 altra posa")))
      << table.item(0, 2)->toolTip().toStdString();
}
