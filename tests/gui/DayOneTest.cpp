// What an operator meets on the first day, each in a real window: files saved without their
// extension get it, the wheel leaves unfocused parameters alone, every panel can be reopened from
// the View menu, the Help menu opens the user guide and the About box, presets say what they are
// for, grip points move and go away with undo, the window is usable at 1024 × 700, and loading
// shows that it is working.
#include "core/cloud/CloudIo.h"
#include "core/model/ModelFile.h"
#include "core/params/ParameterTable.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "tests/unit/pipeline/IdealScene.h"
#include "ui/MainWindow.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QAbstractScrollArea>
#include <QCheckBox>
#include <QComboBox>
#include <QDesktopServices>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTableWidgetItem>
#include <QTest>
#include <QTextBrowser>
#include <QTimer>
#include <QToolButton>
#include <QUndoStack>
#include <QWheelEvent>
#include <QtTest/qtestspontaneevent.h>
#include <algorithm>
#include <gtest/gtest.h>
#include <vtkPropAssembly.h>
#include <vtkPropCollection.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>

using namespace scanpick;
using ui::MainWindow;

namespace {

Eigen::Isometry3d at700() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 700);
  return T;
}

std::shared_ptr<const core::PointCloud> onePart() {
  return std::make_shared<const core::PointCloud>(
      test::idealScene(test::idealPartPoints(), {at700()}, 0.0, 1));
}

/// The thesis's ideal part taught through the core and saved; returns the file.
QString savedIdealModel(const QString& name) {
  core::TeachOptions options;
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  const QString path = test::screenshotDir() + "/" + name;
  core::saveModel(path.toStdString(), core::teach(*onePart(), options, test::idealParams(0.001)));
  return path;
}

QMenu* menuTitled(MainWindow& window, const QString& title) {
  for (QAction* a : window.menuBar()->actions())
    if (a->menu() && a->text() == title)
      return a->menu();
  return nullptr;
}

QAction* actionTitled(QMenu* menu, const QString& title) {
  for (QAction* a : menu->actions())
    if (a->text() == title)
      return a;
  return nullptr;
}

/// A wheel turn (one notch up) over the middle of `widget`, delivered as a real mouse's is: a
/// spontaneous event, which goes through the event filters and then, when ignored, to the
/// parents (Qt never passes a synthesized wheel event on to the parents).
void wheelOver(QWidget* widget, int notches = 1) {
  const QPointF local(widget->width() / 2.0, widget->height() / 2.0);
  QWheelEvent event(local, widget->mapToGlobal(local), QPoint(), QPoint(0, 120 * notches),
                    Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
  QSpontaneKeyEvent::setSpontaneous(&event);
  QApplication::instance()->notify(widget, &event);
}

struct DayOne : ::testing::Test {
  MainWindow window;
  void SetUp() override {
    window.setPreviewDelay(20);
    window.resize(1200, 800);
    window.show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
    // Shortcuts (Del, Esc) reach the active window only.
    window.activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
  }
  /// The ideal part opened as scan and model, recognized once.
  void recognizeIdealPart() {
    ASSERT_TRUE(window.openModel(savedIdealModel(QStringLiteral("day-one.spmodel"))));
    window.parameterPanel()->setParams(test::idealParams(0.001));
    window.setScan(onePart(), QStringLiteral("part"));
    QSignalSpy finished(&window, &MainWindow::recognitionFinished);
    window.recognize();
    ASSERT_TRUE(finished.wait(60000)) << window.logDock()->text().toStdString();
    ASSERT_TRUE(finished.first().at(0).toBool()) << window.logDock()->text().toStdString();
  }
};

} // namespace

TEST_F(DayOne, SavedModelsAndResultsGetTheirExtension) {
  recognizeIdealPart();
  const QString dir = test::screenshotDir();
  QFile::remove(dir + "/bare-model.spmodel");
  QFile::remove(dir + "/bare-results.json");
  ASSERT_TRUE(window.saveModel(dir + "/bare-model"));
  EXPECT_TRUE(QFile::exists(dir + "/bare-model.spmodel"));
  EXPECT_FALSE(QFile::exists(dir + "/bare-model"));
  // File → Open takes it back as a model.
  EXPECT_TRUE(window.openModel(dir + "/bare-model.spmodel"));
  ASSERT_TRUE(window.exportResults(dir + "/bare-results"));
  EXPECT_TRUE(QFile::exists(dir + "/bare-results.json"));
  // A name that already ends right is kept.
  ASSERT_TRUE(window.saveModel(dir + "/bare-model.spmodel"));
  EXPECT_FALSE(QFile::exists(dir + "/bare-model.spmodel.spmodel"));

  // Through the File menu's dialog, typed without the extension.
  QFile::remove(dir + "/typed.spmodel");
  QTimer::singleShot(0, &window, [dir] {
    auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
    ASSERT_NE(dialog, nullptr) << "no save dialog";
    dialog->selectFile(dir + "/typed");
    QMetaObject::invokeMethod(dialog, "accept");
  });
  QAction* save =
      actionTitled(menuTitled(window, QStringLiteral("&File")), QStringLiteral("&Save model…"));
  ASSERT_NE(save, nullptr);
  save->trigger();
  EXPECT_TRUE(QFile::exists(dir + "/typed.spmodel"));
}

TEST_F(DayOne, TheFewTunedParametersComeFirstTheOthersOnDemand) {
  ui::ParameterPanel* panel = window.parameterPanel();
  auto* advanced = panel->findChild<QCheckBox*>(QStringLiteral("showAdvanced"));
  ASSERT_NE(advanced, nullptr);
  EXPECT_FALSE(advanced->isChecked());
  const auto shown = [&] {
    std::vector<std::string> keys;
    for (const core::ParamInfo& info : core::parameterTable())
      if (panel->editor(info.key)->isVisibleTo(panel))
        keys.push_back(info.key);
    return keys;
  };
  const std::vector<std::string> tuned(std::begin(core::kTunedParameters),
                                       std::end(core::kTunedParameters));
  std::vector<std::string> first = shown();
  std::sort(first.begin(), first.end());
  std::vector<std::string> expected = tuned;
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(first, expected) << "only the tuned parameters at first";
  // Stages with no tuned parameter show no empty group.
  for (auto* group : panel->findChildren<QGroupBox*>()) {
    if (!group->isVisibleTo(panel))
      continue;
    EXPECT_TRUE(std::any_of(tuned.begin(), tuned.end(), [&](const std::string& key) {
      return group->isAncestorOf(panel->editor(key));
    })) << group->title().toStdString();
  }
  advanced->click();
  EXPECT_EQ(shown().size(), core::parameterTable().size()) << "every parameter on demand";
  EXPECT_TRUE(panel->findChild<QSpinBox*>(QStringLiteral("seed"))->isVisibleTo(panel));
  advanced->click();
  EXPECT_EQ(shown().size(), tuned.size());
}

TEST_F(DayOne, TheWheelChangesOnlyAFocusedParameter) {
  window.resize(1024, 700);
  window.parameterPanel()->findChild<QCheckBox*>(QStringLiteral("showAdvanced"))->click();
  QTest::qWait(50); // the rows shown are laid out
  auto* spin = qobject_cast<QDoubleSpinBox*>(
      window.parameterPanel()->editor("features.circle_threshold_mm"));
  ASSERT_NE(spin, nullptr);
  auto* scroll = window.parameterPanel()->findChild<QScrollArea*>();
  ASSERT_NE(scroll, nullptr);
  scroll->ensureWidgetVisible(spin);
  QTest::qWait(50);
  const double before = spin->value();
  const int scrolled_before = scroll->verticalScrollBar()->value();
  ASSERT_GT(scrolled_before, 0) << "the panel should scroll at this size";
  ASSERT_FALSE(spin->hasFocus());
  QSignalSpy changed(window.parameterPanel(), &ui::ParameterPanel::paramsChanged);
  wheelOver(spin);
  EXPECT_EQ(spin->value(), before) << "the wheel changed a parameter the operator never clicked";
  EXPECT_EQ(changed.count(), 0);
  EXPECT_LT(scroll->verticalScrollBar()->value(), scrolled_before)
      << "the wheel should scroll the panel instead";

  // Clicked into, the field takes the wheel.
  spin->setFocus(Qt::MouseFocusReason);
  ASSERT_TRUE(QTest::qWaitFor([&] { return spin->hasFocus(); }, 2000));
  wheelOver(spin);
  EXPECT_GT(spin->value(), before);
  EXPECT_EQ(spin->focusPolicy(), Qt::StrongFocus);
}

TEST_F(DayOne, EveryPanelCanBeReopenedFromTheViewMenu) {
  QMenu* view = menuTitled(window, QStringLiteral("&View"));
  ASSERT_NE(view, nullptr);
  const QList<QDockWidget*> docks = window.findChildren<QDockWidget*>();
  ASSERT_GE(docks.size(), 5) << "parameters, results, capture, log and teach";
  for (QDockWidget* dock : docks) {
    EXPECT_TRUE(view->actions().contains(dock->toggleViewAction()))
        << dock->objectName().toStdString() << " is not in the View menu";
    dock->close();
    ASSERT_FALSE(dock->isVisible());
    dock->toggleViewAction()->trigger();
    EXPECT_TRUE(dock->isVisible()) << dock->objectName().toStdString();
  }
  auto* teach = window.findChild<QDockWidget*>(QStringLiteral("TeachDock"));
  ASSERT_NE(teach, nullptr);
  EXPECT_TRUE(view->actions().contains(teach->toggleViewAction()));
}

TEST_F(DayOne, HelpMenuOpensTheUserGuideAndTheAboutBox) {
  QMenu* help = menuTitled(window, QStringLiteral("&Help"));
  ASSERT_NE(help, nullptr) << "no Help menu";
  QAction* guide = actionTitled(help, QStringLiteral("&User guide"));
  QAction* about = actionTitled(help, QStringLiteral("&About scanpick"));
  ASSERT_NE(guide, nullptr);
  ASSERT_NE(about, nullptr);

  // The desktop's viewer is stood in for by a text browser that shows what it was asked to open.
  QTextBrowser viewer;
  QDesktopServices::setUrlHandler(QStringLiteral("file"), &viewer, "setSource");
  guide->trigger();
  QDesktopServices::unsetUrlHandler(QStringLiteral("file"));
  EXPECT_TRUE(viewer.source().toLocalFile().endsWith(QStringLiteral("docs/user-guide.md")))
      << viewer.source().toString().toStdString();
  EXPECT_TRUE(QFile::exists(viewer.source().toLocalFile()));
  EXPECT_TRUE(viewer.toPlainText().contains(QStringLiteral("scanpick")))
      << "the user guide is empty";
  EXPECT_EQ(window.findChild<QMessageBox*>(QStringLiteral("errorDialog")), nullptr);

  about->trigger();
  auto* box = window.findChild<QMessageBox*>(QStringLiteral("aboutDialog"));
  ASSERT_NE(box, nullptr);
  EXPECT_TRUE(QTest::qWaitForWindowExposed(box));
  EXPECT_TRUE(box->text().contains(QStringLiteral(SCANPICK_VERSION_FOR_TESTS)))
      << box->text().toStdString();
  box->close();
}

TEST_F(DayOne, PresetsSayWhatTheyAreFor) {
  auto* combo = window.parameterPanel()->findChild<QComboBox*>(QStringLiteral("presetCombo"));
  ASSERT_NE(combo, nullptr);
  int described = 0;
  for (int i = 0; i < combo->count(); ++i) {
    const QString file = combo->itemData(i).toString();
    if (file.isEmpty())
      continue;
    const std::string description = core::loadPreset(file.toStdString()).description;
    EXPECT_EQ(combo->itemData(i, Qt::ToolTipRole).toString().toStdString(), description)
        << file.toStdString();
    described += description.empty() ? 0 : 1;
  }
  EXPECT_GE(described, 10) << "the bundled presets have descriptions";

  auto* label = window.parameterPanel()->findChild<QLabel*>(QStringLiteral("presetDescription"));
  ASSERT_NE(label, nullptr);
  EXPECT_FALSE(label->isVisible()) << "no preset loaded yet";
  const QString phoxi = QStringLiteral(SCANPICK_SOURCE_DIR "/resources/presets/phoxi-bin.json");
  window.parameterPanel()->loadPresetFile(phoxi);
  EXPECT_TRUE(label->isVisible());
  EXPECT_TRUE(label->text().contains(QStringLiteral("PhoXi M bin picking")))
      << label->text().toStdString();
}

TEST_F(DayOne, GripPointsMoveAndGoAwayWithUndo) {
  window.setScan(onePart(), QStringLiteral("part"));
  window.viewport()->resetCamera();
  QTest::qWait(100);
  window.addGripPoint(Eigen::Vector3d(0, 0, 700));
  window.addGripPoint(Eigen::Vector3d(20, 0, 700));
  ASSERT_EQ(window.gripPoints().size(), 2u);
  QUndoStack* undo = window.undoStack();

  // Moved by clicking on the part: select the grip in the list, Move, click a point of the part.
  auto* list = window.findChild<QListWidget*>(QStringLiteral("gripList"));
  auto* move = window.findChild<QToolButton*>(QStringLiteral("moveGripButton"));
  auto* remove = window.findChild<QPushButton*>(QStringLiteral("removeGripButton"));
  ASSERT_NE(list, nullptr);
  ASSERT_NE(move, nullptr);
  ASSERT_NE(remove, nullptr);
  const Eigen::Vector3f target = window.part()->points_mm.front();
  vtkRenderer* renderer = window.viewport()->renderer();
  renderer->SetWorldPoint(target.x(), target.y(), target.z(), 1.0);
  renderer->WorldToDisplay();
  double display[3];
  renderer->GetDisplayPoint(display);
  const double ratio = window.viewport()->devicePixelRatioF();
  const QPoint click(static_cast<int>(display[0] / ratio),
                     window.viewport()->height() - static_cast<int>(display[1] / ratio) - 1);
  list->setCurrentRow(0);
  QTest::mouseClick(move, Qt::LeftButton);
  ASSERT_TRUE(move->isChecked());
  QTest::mouseClick(window.viewport(), Qt::LeftButton, {}, click);
  EXPECT_FALSE(move->isChecked()) << "one click moves one grip point";
  ASSERT_EQ(window.gripPoints().size(), 2u);
  EXPECT_LT((window.gripPoints()[0].position_mm - target.cast<double>()).norm(), 5.0)
      << "the grip point is not where the part was clicked";
  EXPECT_EQ(window.gripPoints()[1].position_mm, Eigen::Vector3d(20, 0, 700));
  undo->undo();
  EXPECT_EQ(window.gripPoints()[0].position_mm, Eigen::Vector3d(0, 0, 700)) << "undo of the move";
  undo->redo();
  EXPECT_LT((window.gripPoints()[0].position_mm - target.cast<double>()).norm(), 5.0);

  // Removed with the button and with Del; each undone.
  list->setCurrentRow(1);
  QTest::mouseClick(remove, Qt::LeftButton);
  ASSERT_EQ(window.gripPoints().size(), 1u);
  undo->undo();
  ASSERT_EQ(window.gripPoints().size(), 2u);
  EXPECT_EQ(window.gripPoints()[1].position_mm, Eigen::Vector3d(20, 0, 700));
  list->setFocus();
  list->setCurrentRow(0);
  QTest::keyClick(list, Qt::Key_Delete);
  ASSERT_EQ(window.gripPoints().size(), 1u);
  EXPECT_EQ(window.gripPoints()[0].position_mm, Eigen::Vector3d(20, 0, 700));
  undo->undo();
  EXPECT_EQ(window.gripPoints().size(), 2u);
  EXPECT_EQ(list->count(), 2) << "the list follows the undo";
}

TEST_F(DayOne, AGripPointIsApproachedAgainstTheSurfaceAndTheApproachIsEditedWithUndo) {
  window.setScan(onePart(), QStringLiteral("part"));
  window.addGripPoint(Eigen::Vector3d(0, 0, 700));
  ASSERT_EQ(window.gripPoints().size(), 1u);
  // The ideal part lies in the plane z = 700 facing the camera: approached along +z, into it.
  ASSERT_TRUE(window.gripPoints()[0].approach);
  EXPECT_TRUE(window.gripPoints()[0].approach->isApprox(Eigen::Vector3d::UnitZ(), 1e-6))
      << window.gripPoints()[0].approach->transpose();
  auto* field = window.findChild<QLineEdit*>(QStringLiteral("gripApproach"));
  ASSERT_NE(field, nullptr);
  EXPECT_TRUE(field->isEnabled());
  EXPECT_EQ(field->text(), QStringLiteral("0.000, 0.000, 1.000"));

  // Typed in the field: made unit, undoable, and the field follows the undo.
  field->setFocus();
  field->selectAll();
  QTest::keyClicks(field, QStringLiteral("0, 3, 4"));
  QTest::keyClick(field, Qt::Key_Return);
  ASSERT_TRUE(window.gripPoints()[0].approach);
  EXPECT_TRUE(window.gripPoints()[0].approach->isApprox(Eigen::Vector3d(0, 0.6, 0.8)));
  EXPECT_EQ(field->text(), QStringLiteral("0.000, 0.600, 0.800"));
  window.undoStack()->undo();
  EXPECT_TRUE(window.gripPoints()[0].approach->isApprox(Eigen::Vector3d::UnitZ(), 1e-6));
  EXPECT_EQ(field->text(), QStringLiteral("0.000, 0.000, 1.000"));

  // Text that is no direction changes nothing and puts the approach back in the field.
  const int commands = window.undoStack()->count();
  for (const QString& bad :
       {QStringLiteral("1, 2"), QStringLiteral("0, 0, 0"), QStringLiteral("a, b, c")}) {
    field->selectAll();
    QTest::keyClicks(field, bad);
    QTest::keyClick(field, Qt::Key_Return);
    EXPECT_EQ(window.undoStack()->count(), commands) << bad.toStdString();
    EXPECT_EQ(field->text(), QStringLiteral("0.000, 0.000, 1.000")) << bad.toStdString();
  }
}

TEST_F(DayOne, UsableAt1024x700WithFiveResultRowsVisible) {
  EXPECT_LE(window.minimumSizeHint().width(), 1024);
  EXPECT_LE(window.minimumSizeHint().height(), 700);
  window.resize(1024, 700);
  ASSERT_TRUE(QTest::qWaitFor([&] { return window.size() == QSize(1024, 700); }, 2000))
      << "the window stays " << window.width() << " × " << window.height();
  std::vector<core::Detection> five(5);
  for (int i = 0; i < 5; ++i)
    five[std::size_t(i)].score = 0.9 - 0.1 * i;
  ui::ResultsTable* table = window.resultsTable();
  table->setDetections(five, {});
  QTest::qWait(50);
  const QRect visible = table->viewport()->rect();
  for (int row = 0; row < 5; ++row) {
    const QRect cell = table->visualRect(table->model()->index(row, 0));
    EXPECT_TRUE(visible.contains(cell)) << "result row " << row + 1 << " is not fully visible";
  }
  EXPECT_GT(window.viewport()->height(), 250) << "the 3D view shrank to nothing";
}

TEST_F(DayOne, LoadingShowsProgressThatMoves) {
  // A file big enough to take a moment: an organized grid of 3000 × 1500 cells (about 54 MB as
  // binary PCD), so that reading and decoding it span several progress updates (Qt passes at
  // most one every 40 ms on). One cell in a hundred holds a point, the rest NaN, so that what
  // follows the load (drawing, the keypoint preview) stays small.
  const QString path = test::screenshotDir() + "/day-one-load.pcd";
  {
    core::PointCloud big;
    big.width = 3000;
    big.height = 1500;
    big.points_mm.resize(std::size_t(big.width) * big.height);
    for (std::uint32_t r = 0; r < big.height; ++r)
      for (std::uint32_t c = 0; c < big.width; ++c)
        big.points_mm[std::size_t(r) * big.width + c] =
            r % 10 == 0 && c % 10 == 0
                ? Eigen::Vector3f(0.5f * float(c), 0.5f * float(r), 700.0f + 0.01f * float(c))
                : core::invalidPoint();
    core::saveCloud(path.toStdString(), big);
  }
  auto* bar = window.findChild<QProgressBar*>(QStringLiteral("jobProgress"));
  ASSERT_NE(bar, nullptr);
  QList<int> values; // what the bar showed, in order
  QObject watching;  // the connection ends with it, before `values`
  QObject::connect(bar, &QProgressBar::valueChanged, &watching, [&values, bar](int v) {
    if (bar->maximum() > 0 && v >= 0)
      values << v;
  });
  QSignalSpy loaded(&window, &MainWindow::scanLoaded);
  window.openScan(path);
  ASSERT_TRUE(window.jobs()->busy());
  EXPECT_TRUE(bar->isVisible());
  ASSERT_TRUE(loaded.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_EQ(window.scan()->size(), std::size_t(3000) * 1500);
  QStringList shown;
  for (int v : values)
    shown << QString::number(v);
  // It moved: at least one value strictly between 0 and 100 %, never backwards, and 100 % last.
  ASSERT_FALSE(values.isEmpty()) << "the bar never showed a value";
  EXPECT_TRUE(std::any_of(values.begin(), values.end(), [bar](int v) {
    return v > 0 && v < bar->maximum();
  })) << shown.join(' ').toStdString();
  EXPECT_TRUE(std::is_sorted(values.begin(), values.end())) << shown.join(' ').toStdString();
  EXPECT_EQ(values.last(), bar->maximum()) << shown.join(' ').toStdString();
  // Hidden once the job has ended.
  EXPECT_TRUE(QTest::qWaitFor([&] { return !bar->isVisible(); }, 5000));
  QFile::remove(path);
}

// After a recognition the detections are what the view shows: the whole-scene keypoints and
// features are layers turned off (the View menu turns them on again), each detection carries its
// results-table ID in its colour, and the status bar keeps the recognition's stage timings.
TEST_F(DayOne, ResultShowsNumberedDetectionsAndStageTimings) {
  QSignalSpy previews(&window, &MainWindow::previewUpdated);
  ASSERT_TRUE(window.openModel(savedIdealModel(QStringLiteral("day-one-result.spmodel"))));
  window.parameterPanel()->setParams(test::idealParams(0.001));
  window.setScan(onePart(), QStringLiteral("part"));
  ASSERT_TRUE(previews.wait(30000));
  auto* keypoints = window.findChild<QAction*>(QStringLiteral("showKeypointsAction"));
  auto* features = window.findChild<QAction*>(QStringLiteral("showFeaturesAction"));
  ASSERT_NE(keypoints, nullptr);
  ASSERT_NE(features, nullptr);
  EXPECT_TRUE(keypoints->isChecked()) << "no detections yet: the preview is what there is to see";
  const QColor keypoint_yellow(255, 220, 0);
  window.viewport()->requestRender();
  QTest::qWait(100);
  EXPECT_GT(test::countColour(window.screenshot(), keypoint_yellow), 50);

  QSignalSpy finished(&window, &MainWindow::recognitionFinished);
  window.recognize();
  ASSERT_TRUE(finished.wait(60000)) << window.logDock()->text().toStdString();
  ASSERT_TRUE(finished.first().at(0).toBool());
  ASSERT_NE(window.lastResult(), nullptr);
  ASSERT_EQ(window.lastResult()->detections.size(), 1u);
  EXPECT_FALSE(keypoints->isChecked());
  EXPECT_FALSE(features->isChecked());
  // A preview that arrives after the recognition changes neither the toggles nor the status bar.
  window.refreshPreview();
  ASSERT_TRUE(previews.wait(30000));
  EXPECT_FALSE(keypoints->isChecked());
  auto* timings = window.findChild<QLabel*>(QStringLiteral("statusTimings"));
  ASSERT_NE(timings, nullptr);
  EXPECT_TRUE(timings->text().contains(QStringLiteral("matching")) &&
              timings->text().contains(QStringLiteral("total")))
      << timings->text().toStdString();
  window.viewport()->requestRender();
  QTest::qWait(100);
  const QImage result = window.screenshot();
  result.save(test::screenshotDir() + "/day-one-result.png");
  EXPECT_LT(test::countColour(result, keypoint_yellow, 20), 20) << "keypoints cover the result";
  EXPECT_GT(test::countColour(result, ui::detectionColour(0), 30), 20);

  // The detection's ID, as in the table's row header, labels it in the view.
  ui::ResultsTable* table = window.resultsTable();
  ASSERT_NE(table->verticalHeaderItem(0), nullptr);
  EXPECT_EQ(table->verticalHeaderItem(0)->text(), QStringLiteral("1"));
  EXPECT_FALSE(table->verticalHeaderItem(0)->icon().isNull()) << "no colour swatch";
  QStringList labels;
  vtkPropCollection* props = window.viewport()->renderer()->GetViewProps();
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
    if (auto* assembly = vtkPropAssembly::SafeDownCast(prop)) {
      vtkPropCollection* parts = assembly->GetParts();
      parts->InitTraversal();
      while (vtkProp* part = parts->GetNextProp())
        if (auto* text = vtkTextActor::SafeDownCast(part))
          labels << QString::fromUtf8(text->GetInput());
    }
  EXPECT_EQ(labels, QStringList{QStringLiteral("1")});

  // Turned on again from the View menu, the keypoints are drawn over the result.
  keypoints->trigger();
  window.viewport()->requestRender();
  QTest::qWait(100);
  EXPECT_GT(test::countColour(window.screenshot(), keypoint_yellow), 50);
}
