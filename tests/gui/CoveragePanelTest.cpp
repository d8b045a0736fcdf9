// View → View coverage on real models: two views of the demo support, taught through the core from
// the simulated PhoXi teach scans with the part's pose from each scene's ground truth (so both know
// their place in the part), opened in a real window. The panel states the share core::viewCoverage
// measures, draws the covered and the uncovered directions and each view where it lies, follows
// when a view is added, says what a scan of each view may leave open, and switches language with
// the window.
#include "ui/panels/CoveragePanel.h"

#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/gui/SyntheticScenes.h"
#include "ui/Language.h"
#include "ui/MainWindow.h"
#include "ui/panels/CoverageSphere.h"
#include "ui/panels/LogDock.h"

#include <Eigen/Geometry>
#include <QDockWidget>
#include <QMenu>
#include <QMenuBar>
#include <QSignalSpy>
#include <QTest>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace scanpick;
using ui::CoveragePanel;
using ui::CoverageSphere;
using ui::MainWindow;

namespace {

/// The first instance's pose in a teach scene (its ground truth's T_scene_part).
Eigen::Isometry3d partPose(const std::filesystem::path& truth) {
  const auto rows =
      nlohmann::json::parse(core::readFile(truth)).at("instances").at(0).at("T_scene_part");
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      m(r, c) = rows.at(r).at(c).get<double>();
  return Eigen::Isometry3d(m);
}

/// A view of the support taught from `scan` as the demo teaches it, knowing its place in the part
/// (as `scanpick-cli teach --crop-from-truth` does). Returns the .spmodel file.
QString teachPlacedView(const test::DemoScenes& scenes, const std::filesystem::path& scan,
                        const std::filesystem::path& truth, const std::string& file,
                        const core::RecognitionParams& params) {
  core::TeachOptions options;
  options.name = "support";
  options.crop_oriented = scenes.cropBox(truth);
  options.remove_floor = true;
  options.sensor = core::sensorPreset("phoxi-m-1032");
  options.T_scan_part = partPose(truth);
  const std::filesystem::path path = scenes.dir / file;
  core::saveModel(path, core::teach(core::loadCloud(scan, core::LengthUnit::Millimetres).cloud,
                                    options, params));
  return QString::fromStdString(path.string());
}

/// The summary the panel must show for `c`, made here from the core's numbers (English).
QString expectedSummary(const core::ViewCoverage& c) {
  return QStringLiteral("%1 view(s) placed (%2 left out): %3 % of the viewing directions covered")
      .arg(c.view_directions_part.size())
      .arg(c.unplaced)
      .arg(QString::number(100.0 * c.covered, 'f', 0));
}

double degreesBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 /
         std::numbers::pi;
}

/// Pixels of exactly `colour` (within 8 per channel) inside a (2r+1)² box around `at`.
int colourAround(const QImage& image, QPointF at, const QColor& colour, int r) {
  int n = 0;
  for (int y = int(at.y()) - r; y <= int(at.y()) + r; ++y)
    for (int x = int(at.x()) - r; x <= int(at.x()) + r; ++x) {
      if (!image.valid(x, y))
        continue;
      const QColor p = image.pixelColor(x, y);
      if (std::abs(p.red() - colour.red()) <= 8 && std::abs(p.green() - colour.green()) <= 8 &&
          std::abs(p.blue() - colour.blue()) <= 8)
        ++n;
    }
  return n;
}

} // namespace

TEST(CoveragePanel, ShowsTheShareTheCoreMeasuresAndFollowsTheViews) {
  const test::DemoScenes scenes;
  const core::RecognitionParams params =
      core::loadPreset(test::phoxiBinPreset().toStdString()).params;
  const QString legs =
      teachPlacedView(scenes, scenes.teach_scan, scenes.teach_truth, "legs.spmodel", params);
  const QString table =
      teachPlacedView(scenes, scenes.table_scan, scenes.table_truth, "table.spmodel", params);

  MainWindow window;
  window.resize(1400, 900);
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  CoveragePanel* panel = window.coveragePanel();
  ASSERT_NE(panel, nullptr);
  EXPECT_EQ(panel->state(), CoveragePanel::State::NoModel);
  EXPECT_TRUE(panel->summaryText().startsWith(QStringLiteral("No model")))
      << panel->summaryText().toStdString();

  // Reachable from the View menu like every panel: closed and opened again through its entry.
  auto* dock = window.findChild<QDockWidget*>(QStringLiteral("CoverageDock"));
  ASSERT_NE(dock, nullptr);
  EXPECT_EQ(dock->widget(), panel);
  QMenu* view = nullptr;
  for (QAction* a : window.menuBar()->actions())
    if (a->menu() && a->text() == QStringLiteral("&View"))
      view = a->menu();
  ASSERT_NE(view, nullptr);
  QAction* entry = nullptr;
  for (QAction* a : view->actions())
    if (a->text() == QStringLiteral("View coverage"))
      entry = a;
  ASSERT_NE(entry, nullptr) << "no View coverage entry in the View menu";
  EXPECT_EQ(entry, dock->toggleViewAction());
  if (entry->isChecked())
    entry->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return dock->isHidden(); }, 2000));
  entry->trigger();
  dock->raise();
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel->isVisible(); }, 2000));
  // Floating at a known size, so that the discs are large enough to count pixels on.
  dock->setFloating(true);
  dock->resize(620, 640);
  ASSERT_TRUE(QTest::qWaitForWindowExposed(dock));

  // One view: the share the core measures for the window's views.
  QSignalSpy shown(panel, &CoveragePanel::coverageShown);
  ASSERT_TRUE(window.openModel(legs)) << window.logDock()->text().toStdString();
  ASSERT_TRUE(shown.wait(10000));
  ASSERT_EQ(panel->state(), CoveragePanel::State::Shown);
  const core::ViewCoverage one = core::viewCoverage(window.views());
  ASSERT_EQ(one.view_directions_part.size(), 1u) << "the view knows its place in the part";
  EXPECT_EQ(panel->summaryText(), expectedSummary(one));
  ASSERT_NE(panel->coverage(), nullptr);
  EXPECT_DOUBLE_EQ(panel->coverage()->covered, one.covered);
  // One view's cap of 60° is a quarter of the sphere: (1 - cos 60°) / 2.
  EXPECT_NEAR(one.covered, 0.25, 0.01);
  // The view looked at the part from the teach camera (the scan's origin): from the part's
  // origin towards it, in the part frame. The model's origin (the cloud's centroid) lies a few
  // centimetres from the part's at some 80 cm, hence the margin.
  const Eigen::Isometry3d T_scan_part = partPose(scenes.teach_truth);
  const Eigen::Vector3d towards_camera_part =
      T_scan_part.linear().transpose() * -T_scan_part.translation();
  EXPECT_LT(degreesBetween(one.view_directions_part[0], towards_camera_part), 12.0);
  // The suggestions are listed in words, numbered.
  EXPECT_EQ(one.missing_part.size(), 3u);
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(panel->suggestionsText().contains(
        QString::number(i + 1) + ". " + CoveragePanel::describeDirection(one.missing_part[i])))
        << panel->suggestionsText().toStdString();

  // The drawing: equal-area discs, so the covered colour's share of the disc pixels is the
  // share of the directions; the view's dot where its direction projects, a numbered white disc
  // at the first suggestion.
  CoverageSphere* sphere = panel->sphere();
  ASSERT_TRUE(sphere->isVisible());
  ASSERT_GE(sphere->width(), 400);
  const auto checkImage = [&](const core::ViewCoverage& c, const QString& name) {
    const QImage image = sphere->grab().toImage();
    image.save(test::screenshotDir() + "/" + name);
    const int covered = test::countColour(image, CoverageSphere::coveredColour(), 8);
    const int uncovered = test::countColour(image, CoverageSphere::uncoveredColour(), 8);
    EXPECT_GT(covered, 2000) << name.toStdString();
    EXPECT_GT(uncovered, 2000) << name.toStdString();
    EXPECT_NEAR(double(covered) / (covered + uncovered), c.covered, 0.04) << name.toStdString();
    for (const Eigen::Vector3d& d : c.view_directions_part) {
      const QPointF at = sphere->positionOf(d);
      EXPECT_GE(colourAround(image, at, CoverageSphere::viewColour(), 2), 20)
          << name.toStdString() << ": no view dot at (" << at.x() << ", " << at.y() << ")";
    }
    EXPECT_GE(colourAround(image, sphere->positionOf(c.missing_part.at(0)),
                           CoverageSphere::suggestionColour(), 8),
              40)
        << name.toStdString() << ": no suggestion marker";
  };
  checkImage(one, QStringLiteral("coverage-one-view.png"));

  // A second view of another side: more is covered, and the text says so.
  const QString one_text = panel->summaryText();
  shown.clear();
  ASSERT_TRUE(window.addModelViews({table})) << window.logDock()->text().toStdString();
  ASSERT_TRUE(shown.wait(10000));
  ASSERT_EQ(window.views().size(), 2u);
  const core::ViewCoverage two = core::viewCoverage(window.views());
  ASSERT_EQ(two.view_directions_part.size(), 2u);
  EXPECT_GT(degreesBetween(two.view_directions_part[0], two.view_directions_part[1]), 60.0)
      << "the two views see different sides";
  EXPECT_GT(two.covered, one.covered + 0.1);
  EXPECT_EQ(panel->summaryText(), expectedSummary(two));
  EXPECT_NE(panel->summaryText(), one_text);
  checkImage(two, QStringLiteral("coverage-two-views.png"));
  // What each view leaves open: the core's sentences for each view, with its own parameters.
  for (std::size_t v = 0; v < window.views().size(); ++v) {
    const auto& taught = window.views()[v];
    const auto lines =
        core::describeAmbiguities(core::analyzeViewAmbiguities(taught, taught->params));
    ASSERT_FALSE(lines.empty());
    for (const auto& line : lines)
      EXPECT_TRUE(panel->ambiguitiesText().contains(
          QStringLiteral("View %1: %2").arg(v + 1).arg(QString::fromStdString(line))))
          << panel->ambiguitiesText().toStdString();
  }
  dock->resize(620, 900); // room for the ambiguities below the suggestions
  QTest::qWait(100);
  dock->grab().save(test::screenshotDir() + "/coverage-panel.png");

  // The texts follow the language, and come back.
  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("it")));
  const QString italian = QStringLiteral("2 viste collocate (escluse: 0): %1 % delle direzioni di "
                                         "osservazione coperte")
                              .arg(QString::number(100.0 * two.covered, 'f', 0));
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel->summaryText() == italian; }, 5000))
      << panel->summaryText().toStdString();
  EXPECT_EQ(dock->windowTitle(), QStringLiteral("Copertura delle viste"));
  EXPECT_TRUE(panel->suggestionsText().startsWith(QStringLiteral("Per coprire di più")))
      << panel->suggestionsText().toStdString();
  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("en")));
  ASSERT_TRUE(QTest::qWaitFor([&] { return panel->summaryText() == expectedSummary(two); }, 5000))
      << panel->summaryText().toStdString();
}

// Directions in words: above, below and the side, with the azimuth from +X towards +Y.
TEST(CoveragePanel, DescribesDirectionsInThePartFrame) {
  EXPECT_EQ(CoveragePanel::describeDirection(Eigen::Vector3d::UnitZ()),
            QStringLiteral("from straight above (+Z)"));
  EXPECT_EQ(CoveragePanel::describeDirection(-Eigen::Vector3d::UnitZ()),
            QStringLiteral("from straight below (−Z)"));
  EXPECT_EQ(CoveragePanel::describeDirection(Eigen::Vector3d(0, 1, 0)),
            QStringLiteral("from the side at azimuth 90° (elevation 0°)"));
  // 30° above the XY plane, towards -X: azimuth 180°.
  EXPECT_EQ(CoveragePanel::describeDirection(Eigen::Vector3d(-std::cos(std::numbers::pi / 6), 0,
                                                             std::sin(std::numbers::pi / 6))),
            QStringLiteral("from the side at azimuth 180° (elevation 30°)"));
}
