// The teach → recognize workflow on simulated PhoXi scans (written at test time by core/sim):
// open the teach scan, preview and remove the floor, crop with the box, teach, open the bin,
// recognize, and compare the results table with the detections. Also the screen-space lasso.
#include "core/cloud/CloudIo.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/gui/SyntheticScenes.h"
#include "tests/unit/pipeline/IdealScene.h"
#include "ui/MainWindow.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QAction>
#include <QSignalSpy>
#include <QTest>
#include <QUndoStack>
#include <gtest/gtest.h>
#include <vtkCamera.h>
#include <vtkRenderer.h>

using namespace scanpick;
using ui::MainWindow;

namespace {

struct Workflow : ::testing::Test {
  MainWindow window;
  void SetUp() override {
    window.setPreviewDelay(20);
    window.resize(1200, 800);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  }
  /// Opens `path` through the asynchronous file loader and waits for it.
  void open(const std::filesystem::path& path) {
    QSignalSpy loaded(&window, &MainWindow::scanLoaded);
    window.openScan(QString::fromStdString(path.string()));
    ASSERT_TRUE(loaded.wait(30000)) << window.logDock()->text().toStdString();
  }
  /// Fits the view to the working cloud (the teach pictures of the user guide).
  void zoomOnPart() {
    const Eigen::AlignedBox3f box = core::boundingBox(*window.part());
    double bounds[6] = {box.min().x(), box.max().x(), box.min().y(),
                        box.max().y(), box.min().z(), box.max().z()};
    window.viewport()->renderer()->ResetCamera(bounds);
    window.viewport()->requestRender();
    QTest::qWait(100);
  }
  /// Renders and grabs the viewport after the pending frame.
  QImage settledScreenshot() {
    window.viewport()->requestRender();
    QTest::qWait(100);
    return window.screenshot();
  }
};

QString rowPosition(const Eigen::Vector3d& t) {
  const auto f = [](double v) { return QString::number(v, 'f', 1); };
  return QStringLiteral("%1, %2, %3").arg(f(t.x()), f(t.y()), f(t.z()));
}

} // namespace

TEST_F(Workflow, SyntheticTeachSceneCropTeachThenRecognizeTheBin) {
  const test::DemoScenes scenes;
  window.parameterPanel()->loadPresetFile(test::phoxiBinPreset());
  EXPECT_EQ(
      core::paramsToJson(window.parameterPanel()->params()).dump(1),
      core::paramsToJson(core::loadPreset(test::phoxiBinPreset().toStdString()).params).dump(1))
      << "the parameter panel changed the preset's values";
  open(scenes.teach_scan);
  const std::size_t scan_points = window.part()->validCount();
  {
    // Recent files and the last preset are remembered for the next window.
    MainWindow next;
    QStringList recent;
    for (QAction* a : next.findChildren<QAction*>())
      recent << a->text();
    EXPECT_TRUE(recent.contains(QStringLiteral("support-teach-side1.pcd")))
        << recent.join(' ').toStdString();
    EXPECT_EQ(next.parameterPanel()->params().matching.min_coverage,
              window.parameterPanel()->params().matching.min_coverage);
  }

  // Floor preview: the table is shown in orange before anything is removed.
  QSignalSpy floor(&window, &MainWindow::floorPreviewReady);
  window.previewFloor();
  ASSERT_TRUE(floor.wait(30000)) << window.logDock()->text().toStdString();
  const std::size_t floor_points = window.floorPreviewCount();
  EXPECT_GT(floor_points, scan_points / 4) << "the table should be most of a teach scan";
  EXPECT_EQ(window.part()->validCount(), scan_points) << "a preview removes nothing";
  {
    const QImage image = settledScreenshot();
    image.save(test::screenshotDir() + "/teach-floor-preview.png");
    EXPECT_GT(test::distinctColours(image), 10) << "blank screenshot";
    EXPECT_GT(test::countColour(image, MainWindow::floorPreviewColour(), 30), 500)
        << "the floor preview colour is not in the picture";
    test::saveDocImage(window, "gui-teach-floor.png");
  }
  window.removeFloorFromPart(); // applies the preview: synchronous and undoable
  EXPECT_EQ(window.part()->validCount(), scan_points - floor_points);
  EXPECT_EQ(window.floorPreviewCount(), 0u) << "the preview belongs to the previous working cloud";

  // Crop with the box where the ground truth says the part is, and place its grip points.
  window.setCropBoxVisible(true);
  window.setCropBox(scenes.cropBox());
  zoomOnPart();
  test::saveDocImage(window, "gui-teach-crop.png");
  ASSERT_TRUE(window.applyCrop());
  const std::size_t part_points = window.part()->validCount();
  EXPECT_GT(part_points, 1000u);
  EXPECT_LE(part_points, scan_points - floor_points);
  for (const Eigen::Vector3d& g : scenes.gripPoints())
    window.addGripPoint(g);

  QSignalSpy taught(&window, &MainWindow::modelTaught);
  window.teach();
  ASSERT_TRUE(taught.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_NE(window.model(), nullptr);
  EXPECT_GE(window.model()->features.size(), 4u);
  EXPECT_EQ(window.model()->grip_points.size(), scenes.gripPoints().size());
  EXPECT_EQ(window.model()->sensor.preset, "phoxi-m-1032") << "sensor taken from the scan's grid";
  zoomOnPart();
  test::saveDocImage(window, "gui-teach-model.png");

  open(scenes.bin_scan);
  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  window.recognize();
  ASSERT_TRUE(finished.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_TRUE(finished.first().at(0).toBool()) << window.logDock()->text().toStdString();
  const core::RecognitionResult* result = window.lastResult();
  ASSERT_NE(result, nullptr);
  EXPECT_GE(result->detections.size(), 1u) << "the support should be found in the bin";
  EXPECT_LE(result->detections.size(), scenes.binInstances());
  // The window shows what the core finds with the same model, scene and parameters.
  {
    core::Recognizer direct(window.model());
    const core::RecognitionResult expected = direct.recognize(
        *window.scan(), core::sensorPreset("phoxi-m-1032"), window.parameterPanel()->params());
    ASSERT_EQ(result->detections.size(), expected.detections.size());
    for (std::size_t i = 0; i < expected.detections.size(); ++i) {
      EXPECT_DOUBLE_EQ(result->detections[i].score, expected.detections[i].score);
      EXPECT_TRUE(
          result->detections[i].T_scene_model.isApprox(expected.detections[i].T_scene_model));
    }
  }

  // The table shows exactly the detections, in order: score, position, grip points.
  ui::ResultsTable* table = window.resultsTable();
  ASSERT_EQ(table->rowCount(), static_cast<int>(result->detections.size()));
  for (int row = 0; row < table->rowCount(); ++row) {
    const core::Detection& d = result->detections[row];
    EXPECT_EQ(table->item(row, 0)->text(), QString::number(d.score, 'f', 3)) << "row " << row;
    EXPECT_EQ(table->item(row, 1)->text(), rowPosition(d.T_scene_model.translation()))
        << "row " << row;
    EXPECT_EQ(table->item(row, 4)->text().count(QLatin1Char('(')),
              static_cast<int>(d.grip_points_scene.size()));
    if (row > 0) {
      EXPECT_LE(d.score, result->detections[row - 1].score) << "best first";
    }
  }

  table->selectRow(0);
  const QImage image = settledScreenshot();
  image.save(test::screenshotDir() + "/synthetic-recognize.png");
  EXPECT_GT(test::distinctColours(image), 10) << "blank screenshot";
  EXPECT_GT(test::countColour(image, ui::detectionColour(0), 30), 50)
      << "the selected detection's colour is not in the picture";
  EXPECT_GT(test::countGrey(image), 1000) << "the scene (greys by depth) is not drawn";
  test::saveDocImage(window, "gui-recognize.png");
}

TEST_F(Workflow, LassoKeepsThePointsDrawnAroundAndIsUndoable) {
  // Two copies of the thesis's ideal part, 300 mm apart along x; looking from the sensor (x to
  // the right), the first lies in the left half of the view and the second in the right half.
  Eigen::Isometry3d left = Eigen::Isometry3d::Identity(), right = left;
  left.translation() = Eigen::Vector3d(0, 0, 700);
  right.translation() = Eigen::Vector3d(300, 0, 700);
  const auto scan = std::make_shared<const core::PointCloud>(
      test::idealScene(test::idealPartPoints(), {left, right}, 0.0, 1));
  window.setScan(scan, QStringLiteral("two parts"));
  window.viewport()->resetCamera();
  QTest::qWait(50);
  const std::size_t one_copy = test::idealPartPoints().size();
  ASSERT_EQ(window.part()->validCount(), 2 * one_copy);

  double camera_before[3];
  window.viewport()->renderer()->GetActiveCamera()->GetPosition(camera_before);
  window.setLassoActive(true);
  // A polygon around the left half, drawn with the mouse like an operator would.
  QWidget* view = window.viewport();
  const int w = view->width(), h = view->height();
  QSignalSpy changed(&window, &MainWindow::partChanged);
  QTest::mousePress(view, Qt::LeftButton, {}, QPoint(4, 4));
  for (const QPoint p : {QPoint(w / 2, 4), QPoint(w / 2, h / 2), QPoint(w / 2, h - 4),
                         QPoint(w / 4, h - 4), QPoint(4, h - 4), QPoint(4, h / 2)})
    QTest::mouseMove(view, p);
  QTest::mouseRelease(view, Qt::LeftButton, {}, QPoint(4, h / 2 + 10));
  ASSERT_TRUE(changed.wait(30000)) << window.logDock()->text().toStdString();
  EXPECT_EQ(window.part()->validCount(), one_copy) << "the lasso keeps exactly the left copy";
  for (const Eigen::Vector3f& p : window.part()->points_mm)
    EXPECT_LT(p.x(), 150.0f);
  double camera_after[3];
  window.viewport()->renderer()->GetActiveCamera()->GetPosition(camera_after);
  EXPECT_EQ(camera_before[0], camera_after[0]) << "dragging the lasso must not turn the camera";
  EXPECT_EQ(camera_before[1], camera_after[1]);

  window.undoStack()->undo();
  EXPECT_EQ(window.part()->validCount(), 2 * one_copy);
  window.undoStack()->redo();
  EXPECT_EQ(window.part()->validCount(), one_copy);

  // A polygon beside every point keeps nothing: refused with a dialog, the part stays.
  window.applyLasso(QPolygonF({QPointF(w - 30, 2), QPointF(w - 2, 2), QPointF(w - 2, 30)}));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] { return window.findChild<QWidget*>(QStringLiteral("errorDialog")) != nullptr; }, 10000));
  EXPECT_EQ(window.part()->validCount(), one_copy);
  // A click (no area) is ignored.
  window.applyLasso(QPolygonF({QPointF(10, 10), QPointF(11, 10)}));
  QTest::qWait(50);
  EXPECT_EQ(window.part()->validCount(), one_copy);
  window.setLassoActive(false);
  EXPECT_EQ(window.undoStack()->count(), 1);
}

TEST_F(Workflow, FloorPreviewShowsThenRemovesAndUndoes) {
  const test::DemoScenes scenes;
  window.parameterPanel()->loadPresetFile(test::phoxiBinPreset());
  open(scenes.teach_scan);
  const std::size_t scan_points = window.part()->validCount();
  const QImage before = settledScreenshot();
  EXPECT_LT(test::countColour(before, MainWindow::floorPreviewColour(), 30), 50)
      << "orange before any preview";

  // Remove floor without a preview: finds the floor, then removes it (one undo step).
  QSignalSpy changed(&window, &MainWindow::partChanged);
  window.removeFloorFromPart();
  ASSERT_TRUE(changed.wait(30000)) << window.logDock()->text().toStdString();
  const std::size_t without_floor = window.part()->validCount();
  EXPECT_LT(without_floor, scan_points / 2);
  EXPECT_GT(without_floor, 1000u) << "the part must survive floor removal";
  EXPECT_EQ(window.undoStack()->count(), 1);

  window.undoStack()->undo();
  EXPECT_EQ(window.part()->validCount(), scan_points);
  // The preview of the restored scan removes nothing until applied, and matches what was removed.
  QSignalSpy floor(&window, &MainWindow::floorPreviewReady);
  window.previewFloor();
  ASSERT_TRUE(floor.wait(30000));
  EXPECT_EQ(window.floorPreviewCount(), scan_points - without_floor);
  EXPECT_EQ(window.part()->validCount(), scan_points);
  const QImage preview = settledScreenshot();
  EXPECT_GT(test::countColour(preview, MainWindow::floorPreviewColour(), 30), 500);
  window.undoStack()->redo();
  EXPECT_EQ(window.part()->validCount(), without_floor);
  EXPECT_EQ(window.floorPreviewCount(), 0u);
  const QImage after = settledScreenshot();
  EXPECT_LT(test::countColour(after, MainWindow::floorPreviewColour(), 30), 50)
      << "the preview must disappear once the working cloud changed";
}

// The part as the demo teaches it, two views (the support resting on its legs, and lying on the
// table), opened together: Recognize searches both, as `scanpick-cli recognize` with two --model
// does, and the table says which view found each detection. In the table view's own teach scan,
// the first view alone finds nothing.
TEST_F(Workflow, ViewsOfOnePartAreSearchedTogether) {
  const test::DemoScenes scenes;
  const core::RecognitionParams params =
      core::loadPreset(test::phoxiBinPreset().toStdString()).params;
  const auto teachView = [&](const std::filesystem::path& scan, const std::filesystem::path& truth,
                             const std::string& name, const char* file) {
    return QString::fromStdString(scenes.teachView(scan, truth, file, params, name).string());
  };
  const QString legs = teachView(scenes.teach_scan, scenes.teach_truth, "support", "legs.spmodel");
  const QString table_view =
      teachView(scenes.table_scan, scenes.table_truth, "support", "table.spmodel");
  const QString other_part =
      teachView(scenes.table_scan, scenes.table_truth, "bracket", "bracket.spmodel");
  open(scenes.table_scan);
  const auto recognizeHere = [&] {
    QSignalSpy finished(&window, &MainWindow::recognitionFinished);
    window.recognize();
    EXPECT_TRUE(finished.wait(60000)) << window.logDock()->text().toStdString();
    EXPECT_TRUE(finished.first().at(0).toBool()) << window.logDock()->text().toStdString();
    return window.lastResult();
  };

  ASSERT_TRUE(window.openModel(legs));
  ASSERT_EQ(window.views().size(), 1u);
  const core::RecognitionResult* alone = recognizeHere();
  ASSERT_NE(alone, nullptr);
  EXPECT_TRUE(alone->detections.empty()) << "the legs view should not see the part lying flat";
  EXPECT_TRUE(window.resultsTable()->isColumnHidden(5)) << "one view: no View column";

  ASSERT_TRUE(window.addModelViews({table_view}));
  ASSERT_EQ(window.views().size(), 2u);
  const core::RecognitionResult* both = recognizeHere();
  ASSERT_NE(both, nullptr);
  ASSERT_EQ(both->detections.size(), 1u);
  EXPECT_EQ(both->detections[0].model_index, 1);
  // What the core finds with the same views, scene and parameters.
  core::Recognizer direct;
  const core::RecognitionResult expected =
      core::recognizeViews(direct, window.views(), *window.scan(),
                           core::sensorPreset("phoxi-m-1032"), window.parameterPanel()->params());
  ASSERT_EQ(expected.detections.size(), both->detections.size());
  EXPECT_DOUBLE_EQ(both->detections[0].score, expected.detections[0].score);
  EXPECT_TRUE(both->detections[0].T_scene_model.isApprox(expected.detections[0].T_scene_model));
  ui::ResultsTable* table = window.resultsTable();
  ASSERT_EQ(table->rowCount(), 1);
  EXPECT_FALSE(table->isColumnHidden(5));
  ASSERT_NE(table->item(0, 5), nullptr);
  EXPECT_EQ(table->item(0, 5)->text(), QStringLiteral("table"));
  const QImage image = settledScreenshot();
  image.save(test::screenshotDir() + "/two-views-recognize.png");
  EXPECT_GT(test::countColour(image, ui::detectionColour(0), 30), 50)
      << "the second view's overlay is not in the picture";
  table->selectRow(0);
  {
    // The user guide's picture: the view where it was found, in the middle.
    Eigen::AlignedBox3f found;
    for (const Eigen::Vector3f& p : window.views()[1]->cloud_mm.points_mm)
      if (core::isValid(p))
        found.extend(both->detections[0].T_scene_model.cast<float>() * p);
    const Eigen::Vector3f margin = 0.5f * found.sizes();
    double bounds[6] = {found.min().x() - margin.x(), found.max().x() + margin.x(),
                        found.min().y() - margin.y(), found.max().y() + margin.y(),
                        found.min().z() - margin.z(), found.max().z() + margin.z()};
    window.viewport()->renderer()->ResetCamera(bounds);
    settledScreenshot();
  }
  test::saveDocImage(window, "gui-views.png");

  // The results name both views; the detection refers to the second.
  const QString json = test::screenshotDir() + "/two-views-results.json";
  ASSERT_TRUE(window.exportResults(json));
  const auto doc = nlohmann::json::parse(core::readFile(json.toStdString()));
  ASSERT_EQ(doc.at("models").size(), 2u);
  EXPECT_EQ(doc.at("models").at(1).at("path").get<std::string>(), table_view.toStdString());
  EXPECT_EQ(doc.at("detections").at(0).at("model").get<int>(), 1);

  // Views of another part are refused, and the part opened stays as it was.
  EXPECT_FALSE(window.addModelViews({other_part}));
  EXPECT_FALSE(window.openModels({legs, other_part}));
  EXPECT_EQ(window.views().size(), 2u);
  EXPECT_EQ(window.model()->name, "support");
  EXPECT_TRUE(QTest::qWaitFor(
      [&] { return window.logDock()->text().contains(QStringLiteral("are different parts")); },
      5000));
}
