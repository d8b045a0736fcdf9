// The depth image view (View → Depth image): an organized scan's own grid, shaded by depth, with
// the detections tinted in their results-table colours and numbered, as in the 3D view; for an
// unorganized cloud it says why it stays empty.
#include "ui/panels/DepthView.h"

#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/gui/SyntheticScenes.h"
#include "tests/unit/pipeline/IdealScene.h"
#include "ui/MainWindow.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"

#include <QDockWidget>
#include <QMenu>
#include <QMenuBar>
#include <QSignalSpy>
#include <QTest>
#include <gtest/gtest.h>

using namespace scanpick;
using ui::DepthView;
using ui::MainWindow;

namespace {

/// Pixels of `colour`'s hue (within 12°), saturated and bright enough not to be a grey: the view
/// tints a detection's points in its colour, scaled by a part of their depth shade.
int countHue(const QImage& image, const QColor& colour) {
  int n = 0;
  const int hue = colour.hsvHue();
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QColor p = image.pixelColor(x, y);
      const int d = std::abs(p.hsvHue() - hue);
      if (p.hsvSaturation() > 128 && p.value() > 100 && std::min(d, 360 - d) <= 12)
        ++n;
    }
  return n;
}

} // namespace

TEST(DepthImage, ShowsTheOrganizedScanWithTheDetectionInItsColour) {
  // The demo's teach scene (a PhoXi M scan of one support on a table) and the support taught from
  // it through the core: recognizing it there finds the support where it was taught.
  const test::DemoScenes scenes;
  const core::RecognitionParams params =
      core::loadPreset(test::phoxiBinPreset().toStdString()).params;
  const auto model =
      scenes.teachView(scenes.teach_scan, scenes.teach_truth, "support.spmodel", params);
  MainWindow window;
  window.resize(1200, 800);
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  auto* dock = window.findChild<QDockWidget*>(QStringLiteral("DepthDock"));
  ASSERT_NE(dock, nullptr);
  // Listed in the View menu like every panel.
  QMenu* view = nullptr;
  for (QAction* a : window.menuBar()->actions())
    if (a->menu() && a->text() == QStringLiteral("&View"))
      view = a->menu();
  ASSERT_NE(view, nullptr);
  EXPECT_TRUE(view->actions().contains(dock->toggleViewAction()));
  dock->show();
  dock->raise();
  DepthView* depth = window.depthView();
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->state(), DepthView::State::NoScan);
  EXPECT_FALSE(depth->message().isEmpty());

  ASSERT_TRUE(window.openModel(QString::fromStdString(model.string())));
  QSignalSpy loaded(&window, &MainWindow::scanLoaded);
  QSignalSpy drawn(&window, &MainWindow::depthViewUpdated);
  window.openScan(QString::fromStdString(scenes.teach_scan.string()));
  ASSERT_TRUE(loaded.wait(30000)) << window.logDock()->text().toStdString();
  const auto scan = window.scan();
  ASSERT_TRUE(scan->isOrganized());
  // The scan alone: its depth image, no detection yet.
  ASSERT_TRUE(drawn.count() > 0 || drawn.wait(30000)) << window.logDock()->text().toStdString();
  EXPECT_EQ(depth->state(), DepthView::State::Image);
  EXPECT_EQ(depth->image().size(), QSize(int(scan->width), int(scan->height)));
  EXPECT_TRUE(depth->marks().empty());
  EXPECT_EQ(countHue(depth->image(), ui::detectionColour(0)), 0);
  // Near light, far dark: the nearest valid cell is lighter than the farthest.
  std::size_t nearest = 0, farthest = 0;
  for (std::size_t i = 0; i < scan->size(); ++i) {
    if (!core::isValid(scan->points_mm[i]))
      continue;
    if (!core::isValid(scan->points_mm[nearest]) ||
        scan->points_mm[i].z() < scan->points_mm[nearest].z())
      nearest = i;
    if (!core::isValid(scan->points_mm[farthest]) ||
        scan->points_mm[i].z() > scan->points_mm[farthest].z())
      farthest = i;
  }
  const auto pixel = [&](std::size_t i) {
    return depth->image().pixelColor(int(i % scan->width), int(i / scan->width));
  };
  EXPECT_GT(pixel(nearest).value(), pixel(farthest).value() + 100);

  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  drawn.clear();
  window.recognize();
  ASSERT_TRUE(finished.wait(120000)) << window.logDock()->text().toStdString();
  ASSERT_TRUE(finished.first().at(0).toBool()) << window.logDock()->text().toStdString();
  ASSERT_NE(window.lastResult(), nullptr);
  const auto& detections = window.lastResult()->detections;
  ASSERT_GE(detections.size(), 1u) << window.logDock()->text().toStdString();
  ASSERT_TRUE(drawn.wait(30000)) << window.logDock()->text().toStdString();
  ASSERT_EQ(depth->state(), DepthView::State::Image);
  const QImage image = depth->image();
  image.save(test::screenshotDir() + "/depth-view.png");
  EXPECT_EQ(image.size(), QSize(int(scan->width), int(scan->height)));
  // The support covers a few thousand cells of the scan; its visible points carry the colour of
  // row 1 of the results table.
  const int tinted = countHue(image, ui::detectionColour(0));
  EXPECT_GT(tinted, 1000);
  ASSERT_EQ(depth->marks().size(), detections.size());
  EXPECT_EQ(depth->marks()[0].pixels, std::size_t(tinted))
      << "only the detection's cells have its hue";
  // Its ID sits on its own cells: the cell under the label has the detection's hue.
  const Eigen::Vector2d label = depth->marks()[0].label_px;
  ASSERT_GE(label.x(), 0);
  ASSERT_LT(label.x(), image.width());
  ASSERT_GE(label.y(), 0);
  ASSERT_LT(label.y(), image.height());
  int near_label = 0;
  for (int dy = -10; dy <= 10; ++dy)
    for (int dx = -10; dx <= 10; ++dx) {
      const QPoint at(int(label.x()) + dx, int(label.y()) + dy);
      if (image.rect().contains(at) &&
          countHue(image.copy(QRect(at, QSize(1, 1))), ui::detectionColour(0)) == 1)
        ++near_label;
    }
  EXPECT_GT(near_label, 20) << "the ID is not on the detection";
  EXPECT_EQ(depth->marks()[0].grips_px.size(), detections[0].grip_points_scene.size());
  // What the widget shows: the image scaled into it, with the colour visible.
  const QImage shown = depth->grab().toImage();
  shown.save(test::screenshotDir() + "/depth-view-widget.png");
  EXPECT_GT(countHue(shown, ui::detectionColour(0)), 50);
  test::saveDocImage(window, "gui-depth-image.png");

  // Selecting the row keeps the image and highlights that detection.
  window.resultsTable()->selectRow(0);
  EXPECT_EQ(depth->image().size(), image.size());
}

TEST(DepthImage, SaysWhyAnUnorganizedCloudHasNone) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  auto* dock = window.findChild<QDockWidget*>(QStringLiteral("DepthDock"));
  ASSERT_NE(dock, nullptr);
  dock->show();
  dock->raise();
  Eigen::Isometry3d at700 = Eigen::Isometry3d::Identity();
  at700.translation() = Eigen::Vector3d(0, 0, 700);
  window.setScan(std::make_shared<const core::PointCloud>(
                     test::idealScene(test::idealPartPoints(), {at700}, 0.0, 1)),
                 QStringLiteral("list"));
  ASSERT_FALSE(window.scan()->isOrganized());
  EXPECT_EQ(window.depthView()->state(), DepthView::State::Unorganized);
  EXPECT_TRUE(window.depthView()->image().isNull());
  EXPECT_TRUE(window.depthView()->message().contains(QStringLiteral("unorganized")))
      << window.depthView()->message().toStdString();
  EXPECT_FALSE(window.depthJobs()->busy()) << "nothing to draw";
}
