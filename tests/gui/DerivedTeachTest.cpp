// Teach configures itself: with the Parameters panel's default choice, "Derived from the part
// (default)", Teach derives the parameters from the part and the scan (core::autoTeachParams) in
// its job, the panel then holds the derived values with their reasons (tooltip and a "derived"
// marker) and the Teach panel says what was measured; a value set by hand wins at the next teach,
// as --set does on the CLI; a named preset teaches with its own values and no reasons; a model
// opened with reasons shows them again. On the demo's simulated PhoXi teach scan of the support.
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/gui/SyntheticScenes.h"
#include "ui/MainWindow.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFileInfo>
#include <QLabel>
#include <QScrollArea>
#include <QSignalSpy>
#include <QTest>
#include <gtest/gtest.h>

using namespace scanpick;
using ui::MainWindow;

namespace {

const std::string kKey = "keypoints.neighbourhood_radius_mm";

std::string dump(const core::RecognitionParams& params) {
  return core::paramsToJson(params).dump(1);
}

struct DerivedTeach : ::testing::Test {
  MainWindow window;
  ui::ParameterPanel* panel = window.parameterPanel();
  QComboBox* combo = panel->findChild<QComboBox*>(QStringLiteral("presetCombo"));
  QLabel* measures = window.findChild<QLabel*>(QStringLiteral("teachMeasures"));

  void SetUp() override {
    ASSERT_NE(combo, nullptr);
    ASSERT_NE(measures, nullptr);
    window.setPreviewDelay(20);
    window.resize(1200, 800);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  }
  /// The teach scan opened, its floor removed and the part cropped where the ground truth says.
  void openAndCrop(const test::DemoScenes& scenes) {
    QSignalSpy loaded(&window, &MainWindow::scanLoaded);
    window.openScan(QString::fromStdString(scenes.teach_scan.string()));
    ASSERT_TRUE(loaded.wait(30000)) << window.logDock()->text().toStdString();
    QSignalSpy changed(&window, &MainWindow::partChanged);
    window.removeFloorFromPart(); // finds the floor in a job, then removes it
    ASSERT_TRUE(changed.wait(30000)) << window.logDock()->text().toStdString();
    window.setCropBoxVisible(true);
    window.setCropBox(scenes.cropBox());
    ASSERT_TRUE(window.applyCrop());
  }
  /// Teach, waited for.
  void teach() {
    QSignalSpy taught(&window, &MainWindow::modelTaught);
    window.teach();
    ASSERT_TRUE(taught.wait(60000)) << window.logDock()->text().toStdString();
    ASSERT_NE(window.model(), nullptr);
  }
  /// Chooses entry `index` of the preset list as the operator does.
  void choose(int index) {
    combo->setCurrentIndex(index);
    emit combo->activated(index);
  }
  [[nodiscard]] QLabel* marker(const std::string& key) const {
    return panel->findChild<QLabel*>(QString::fromStdString(key + ".derived"));
  }
  [[nodiscard]] QString tooltip(const std::string& key) const {
    return panel->editor(key)->toolTip();
  }
};

} // namespace

TEST_F(DerivedTeach, DerivedByDefaultHandEditsWinPresetsDeriveNothing) {
  const test::DemoScenes scenes;
  EXPECT_TRUE(panel->derivesAtTeach()) << "the default at the first start";
  EXPECT_EQ(combo->currentIndex(), 0);
  EXPECT_EQ(combo->currentText(), QStringLiteral("Derived from the part (default)"));
  EXPECT_TRUE(combo->toolTip().contains(QStringLiteral("override"))) << "says how edits count";
  openAndCrop(scenes);

  // What the core derives from this working cloud, cut as the Teach action cuts it (its bounds,
  // padded by 1 mm): the job must come to the same values.
  core::TeachOptions options;
  Eigen::AlignedBox3f bounds = core::boundingBox(*window.part());
  bounds.min() -= Eigen::Vector3f::Constant(1.0f);
  bounds.max() += Eigen::Vector3f::Constant(1.0f);
  options.crop_box_mm = bounds;
  const core::AutoParams expected = core::autoTeachParams(*window.part(), options);
  ASSERT_FALSE(expected.values.empty());

  teach();
  const auto derived = window.model();
  EXPECT_EQ(dump(derived->params), dump(expected.params));
  EXPECT_EQ(derived->param_reasons.size(), expected.values.size());
  // The panel holds the derived values, so recognition uses them, each with its reason.
  EXPECT_EQ(dump(panel->params()), dump(derived->params));
  EXPECT_EQ(panel->params().keypoints.neighbourhood_radius_mm,
            derived->params.keypoints.neighbourhood_radius_mm);
  ASSERT_EQ(derived->param_reasons.count(kKey), 1u);
  const QString reason = QString::fromStdString(derived->param_reasons.at(kKey));
  EXPECT_TRUE(tooltip(kKey).contains(reason)) << tooltip(kKey).toStdString();
  ASSERT_NE(marker(kKey), nullptr);
  EXPECT_FALSE(marker(kKey)->isVisibleTo(panel)) << "a derived value is advanced: hidden at first";
  auto* advanced = panel->findChild<QCheckBox*>(QStringLiteral("showAdvanced"));
  ASSERT_NE(advanced, nullptr);
  advanced->click();
  EXPECT_TRUE(marker(kKey)->isVisibleTo(panel));
  EXPECT_EQ(panel->reasons(), derived->param_reasons);
  const auto* note = panel->findChild<QLabel*>(QStringLiteral("derivedNote"));
  ASSERT_NE(note, nullptr);
  EXPECT_TRUE(note->isVisibleTo(panel));
  // A value nobody derived has no marker: the seed's editor is the panel's own, so take one of
  // the table's keys that the derivation left alone, if any.
  for (const core::ParamInfo& info : core::parameterTable())
    if (derived->param_reasons.count(info.key) == 0) {
      EXPECT_FALSE(marker(info.key)->isVisibleTo(panel)) << info.key;
      EXPECT_FALSE(tooltip(info.key).contains(QStringLiteral("Derived from the part")));
      break;
    }
  // The keypoint preview follows the derived values.
  EXPECT_TRUE(QTest::qWaitFor(
      [&] {
        return window.preview() && window.preview()->keypoint_params == derived->params.keypoints;
      },
      30000));
  // The Teach panel says what was measured.
  EXPECT_TRUE(measures->isVisibleTo(&window));
  EXPECT_TRUE(measures->text().contains(QStringLiteral("point spacing")) &&
              measures->text().contains(QStringLiteral("depth noise")) &&
              measures->text().contains(QStringLiteral("part diameter")))
      << measures->text().toStdString();
  EXPECT_TRUE(measures->text().contains(QString::number(expected.part.diameter_mm, 'f', 1)))
      << measures->text().toStdString();
  if (auto* scroll = panel->findChild<QScrollArea*>())
    scroll->ensureWidgetVisible(panel->editor(kKey));
  QTest::qWait(50);
  window.grab().save(test::screenshotDir() + "/derived-teach.png");
  const QString saved = test::screenshotDir() + "/derived-support.spmodel";
  ASSERT_TRUE(window.saveModel(saved));

  // A value set by hand since the last teach wins over the derived one and has no reason.
  const double hand = derived->params.keypoints.neighbourhood_radius_mm + 1.0;
  ASSERT_TRUE(panel->setValue(kKey, hand));
  EXPECT_FALSE(marker(kKey)->isVisibleTo(panel)) << "an edited value is no longer derived";
  EXPECT_FALSE(tooltip(kKey).contains(reason));
  teach();
  EXPECT_EQ(window.model()->params.keypoints.neighbourhood_radius_mm, hand);
  EXPECT_EQ(window.model()->param_reasons.count(kKey), 0u);
  EXPECT_EQ(window.model()->param_reasons.size(), expected.values.size() - 1);
  EXPECT_EQ(panel->params().keypoints.neighbourhood_radius_mm, hand);
  EXPECT_FALSE(marker(kKey)->isVisibleTo(panel));
  EXPECT_TRUE(panel->handEdits().empty()) << "a teach takes the hand edits in";

  // A named preset: its values as they are, nothing derived, no reasons shown.
  const QString phoxi = QFileInfo(test::phoxiBinPreset()).canonicalFilePath();
  int preset = -1;
  for (int i = 1; i < combo->count(); ++i)
    if (QFileInfo(combo->itemData(i).toString()).canonicalFilePath() == phoxi)
      preset = i;
  ASSERT_GT(preset, 0) << "phoxi-bin is not in the preset list";
  choose(preset);
  EXPECT_FALSE(panel->derivesAtTeach());
  EXPECT_TRUE(panel->reasons().empty());
  const core::RecognitionParams preset_params =
      core::loadPreset(test::phoxiBinPreset().toStdString()).params;
  teach();
  EXPECT_EQ(dump(window.model()->params), dump(preset_params));
  EXPECT_TRUE(window.model()->param_reasons.empty());
  EXPECT_EQ(dump(panel->params()), dump(preset_params));
  EXPECT_TRUE(panel->reasons().empty());
  EXPECT_FALSE(marker(kKey)->isVisibleTo(panel));
  EXPECT_FALSE(tooltip(kKey).contains(QStringLiteral("Derived from the part")));
  EXPECT_FALSE(note->isVisibleTo(panel));
  EXPECT_FALSE(measures->isVisibleTo(&window)) << "nothing was measured for a preset";
  {
    MainWindow next; // the choice is remembered
    EXPECT_FALSE(next.parameterPanel()->derivesAtTeach());
  }

  // The derived model opened again shows its reasons.
  ASSERT_TRUE(window.openModel(saved));
  EXPECT_EQ(panel->reasons(), derived->param_reasons);
  EXPECT_TRUE(tooltip(kKey).contains(reason));
  EXPECT_TRUE(marker(kKey)->isVisibleTo(panel));

  // Back to the derived entry: the core's defaults until the next teach, and remembered.
  choose(0);
  EXPECT_TRUE(panel->derivesAtTeach());
  EXPECT_TRUE(panel->reasons().empty());
  EXPECT_EQ(dump(panel->params()), dump(core::RecognitionParams{}));
  {
    MainWindow next;
    EXPECT_TRUE(next.parameterPanel()->derivesAtTeach());
  }
}
