// The language switches while the window is open (View → Language): menus, docks, the
// Parameters panel (labels, descriptions, units, choices and stage titles from the core's
// parameter table), the Teach panel, the results table and the status bar turn Italian, and back
// to English, in the same window, with no restart.
#include "ui/Language.h"

#include "core/params/ParameterTable.h"
#include "core/params/ParamsJson.h"
#include "tests/gui/GuiTestSupport.h"
#include "ui/MainWindow.h"
#include "ui/Settings.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"

#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QSettings>
#include <QStatusBar>
#include <QTest>
#include <QTranslator>
#include <gtest/gtest.h>

using namespace scanpick;
using ui::MainWindow;

namespace {

/// The texts a language switch must change, read from the widgets.
struct Texts {
  QStringList menus;
  QString params_dock, depth_dock, teach_dock;
  QString depth_toggle; // the Depth image panel's entry in the View menu
  QString distance_label, distance_tooltip, distance_suffix;
  QString preprocess_group;
  QString method_choice; // keypoints.method's first choice
  QString part_name_label, part_name_placeholder;
  QString results_header;
  QString status;
  QString undo;
};

QLabel* labelFor(QWidget* root, QWidget* buddy) {
  for (QLabel* label : root->findChildren<QLabel*>())
    if (label->buddy() == buddy)
      return label;
  return nullptr;
}

Texts read(MainWindow& window) {
  Texts t;
  for (QAction* a : window.menuBar()->actions())
    t.menus << a->text();
  t.params_dock = window.findChild<QDockWidget*>(QStringLiteral("ParametersDock"))->windowTitle();
  auto* depth = window.findChild<QDockWidget*>(QStringLiteral("DepthDock"));
  t.depth_dock = depth->windowTitle();
  t.depth_toggle = depth->toggleViewAction()->text();
  t.teach_dock = window.findChild<QDockWidget*>(QStringLiteral("TeachDock"))->windowTitle();
  ui::ParameterPanel* panel = window.parameterPanel();
  auto* distance = qobject_cast<QDoubleSpinBox*>(panel->editor("floor.distance_mm"));
  if (QLabel* label = labelFor(panel, distance))
    t.distance_label = label->text();
  t.distance_tooltip = distance->toolTip();
  t.distance_suffix = distance->suffix();
  for (QGroupBox* group : panel->findChildren<QGroupBox*>())
    if (group->isAncestorOf(distance))
      t.preprocess_group = group->title();
  t.method_choice = qobject_cast<QComboBox*>(panel->editor("keypoints.method"))->itemText(0);
  auto* part_name = window.findChild<QLineEdit*>(QStringLiteral("partNameEdit"));
  if (QLabel* label = labelFor(&window, part_name))
    t.part_name_label = label->text();
  t.part_name_placeholder = part_name->placeholderText();
  t.results_header = window.resultsTable()->horizontalHeaderItem(0)->text();
  t.status = window.statusBar()->currentMessage();
  t.undo = window.findChild<QAction*>(QStringLiteral("undoAction"))->text();
  return t;
}

QAction* languageAction(MainWindow& window, const QString& code) {
  return window.findChild<QAction*>(QStringLiteral("language_") + code);
}

} // namespace

TEST(LiveLanguage, SwitchesToItalianAndBackWithoutRestart) {
  MainWindow window;
  window.resize(1200, 800);
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  const Texts english = read(window);
  ASSERT_TRUE(english.menus.contains(QStringLiteral("&Edit")))
      << english.menus.join(' ').toStdString();
  EXPECT_EQ(english.distance_label, QStringLiteral("Floor distance"));
  EXPECT_EQ(english.preprocess_group, QStringLiteral("Scene preprocessing"));
  EXPECT_EQ(english.depth_dock, QStringLiteral("Depth image"));
  EXPECT_EQ(english.undo, QStringLiteral("&Undo"));

  QAction* italian = languageAction(window, QStringLiteral("it"));
  ASSERT_NE(italian, nullptr) << "no Italian entry in View → Language";
  italian->trigger();
  // Qt delivers QEvent::LanguageChange through the event loop.
  ASSERT_TRUE(QTest::qWaitFor([&] { return read(window).menus.contains("&Modifica"); }, 5000))
      << read(window).menus.join(' ').toStdString();
  EXPECT_EQ(QSettings().value(ui::settings::kLanguage).toString(), QStringLiteral("it"))
      << "the choice is kept for the next start";
  EXPECT_EQ(ui::currentLanguage(), QStringLiteral("it"));
  const Texts it = read(window);
  EXPECT_TRUE(it.menus.contains(QStringLiteral("&Insegna"))) << it.menus.join(' ').toStdString();
  EXPECT_TRUE(it.menus.contains(QStringLiteral("&Vista"))) << it.menus.join(' ').toStdString();
  EXPECT_EQ(it.params_dock, QStringLiteral("Parametri"));
  EXPECT_EQ(it.depth_dock, QStringLiteral("Immagine di profondità"));
  EXPECT_EQ(it.depth_toggle, QStringLiteral("Immagine di profondità"));
  EXPECT_EQ(it.teach_dock, QStringLiteral("Insegna"));
  EXPECT_EQ(it.distance_label, QStringLiteral("Distanza dal pavimento"));
  EXPECT_TRUE(it.distance_tooltip.startsWith(QStringLiteral("I punti più vicini")))
      << it.distance_tooltip.toStdString();
  EXPECT_EQ(it.distance_suffix, QStringLiteral(" mm"));
  EXPECT_EQ(it.preprocess_group, QStringLiteral("Pre-elaborazione della scena"));
  EXPECT_EQ(it.method_choice, QStringLiteral("vicinato"));
  EXPECT_EQ(it.part_name_label, QStringLiteral("Nome del pezzo:"));
  EXPECT_NE(it.part_name_placeholder, english.part_name_placeholder);
  EXPECT_EQ(it.results_header, QStringLiteral("Punteggio"));
  EXPECT_EQ(it.status,
            QStringLiteral("Apri una scansione (Ctrl+O) o trascina qui un file PCD/PLY"));
  EXPECT_EQ(it.undo, QStringLiteral("&Annulla"));
  EXPECT_TRUE(italian->isChecked());

  // Every label and description of the parameter table is in Italian, as each editor shows it.
  for (const core::ParamInfo& info : core::parameterTable()) {
    const QString label = ui::ParameterPanel::translatedParamText(info.label);
    const QString description = ui::ParameterPanel::translatedParamText(info.description);
    EXPECT_NE(label.toStdString(), info.label) << info.key << ": label not translated";
    EXPECT_NE(description.toStdString(), info.description)
        << info.key << ": description not translated";
    if (QWidget* editor = window.parameterPanel()->editor(info.key)) {
      EXPECT_TRUE(editor->toolTip().startsWith(description)) << info.key;
    }
  }

  QAction* english_action = languageAction(window, QStringLiteral("en"));
  ASSERT_NE(english_action, nullptr);
  english_action->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return read(window).menus.contains("&Edit"); }, 5000));
  const Texts back = read(window);
  EXPECT_EQ(back.menus, english.menus);
  EXPECT_EQ(back.params_dock, english.params_dock);
  EXPECT_EQ(back.depth_dock, english.depth_dock);
  EXPECT_EQ(back.depth_toggle, english.depth_toggle);
  EXPECT_EQ(back.teach_dock, english.teach_dock);
  EXPECT_EQ(back.distance_label, english.distance_label);
  EXPECT_EQ(back.distance_tooltip, english.distance_tooltip);
  EXPECT_EQ(back.preprocess_group, english.preprocess_group);
  EXPECT_EQ(back.method_choice, english.method_choice);
  EXPECT_EQ(back.part_name_label, english.part_name_label);
  EXPECT_EQ(back.part_name_placeholder, english.part_name_placeholder);
  EXPECT_EQ(back.results_header, english.results_header);
  EXPECT_EQ(back.status, english.status);
  EXPECT_EQ(back.undo, english.undo);
  EXPECT_EQ(QSettings().value(ui::settings::kLanguage).toString(), QStringLiteral("en"));
}

// Texts made from data (the results table's rows and their notes) follow the switch too.
TEST(LiveLanguage, ResultsTableRowsFollowTheLanguage) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  std::vector<core::Detection> two(2);
  window.resultsTable()->setDetections(two, {});
  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("it")));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        return window.resultsTable()->horizontalHeaderItem(0)->text() ==
               QStringLiteral("Punteggio");
      },
      5000));
  EXPECT_EQ(window.resultsTable()->rowCount(), 2) << "the rows stay";
  EXPECT_EQ(window.resultsTable()->verticalHeaderItem(1)->toolTip(),
            QStringLiteral("Rilevamento 2: disegnato in questo colore, etichettato 2 nella vista"));
  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("en")));
  ASSERT_TRUE(QTest::qWaitFor(
      [&] {
        return window.resultsTable()->horizontalHeaderItem(0)->text() == QStringLiteral("Score");
      },
      5000));
  EXPECT_EQ(window.resultsTable()->verticalHeaderItem(1)->toolTip(),
            QStringLiteral("Detection 2: drawn in this colour, labelled 2 in the view"));
}

// Every bundled preset says what it is for in Italian too: the preset list's tooltips and the
// loaded preset's description follow the switch, and go back.
TEST(LiveLanguage, PresetDescriptionsFollowTheLanguage) {
  MainWindow window;
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ui::ParameterPanel* panel = window.parameterPanel();
  auto* combo = panel->findChild<QComboBox*>(QStringLiteral("presetCombo"));
  auto* label = panel->findChild<QLabel*>(QStringLiteral("presetDescription"));
  ASSERT_NE(combo, nullptr);
  ASSERT_NE(label, nullptr);
  panel->loadPresetFile(QStringLiteral(SCANPICK_SOURCE_DIR "/resources/presets/phoxi-bin.json"));
  const QString english_label = label->text();
  ASSERT_TRUE(english_label.contains(QStringLiteral("PhoXi M bin picking")))
      << english_label.toStdString();
  QStringList english_tips;
  for (int i = 0; i < combo->count(); ++i)
    english_tips << combo->itemData(i, Qt::ToolTipRole).toString();

  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("it")));
  ASSERT_TRUE(QTest::qWaitFor([&] { return label->text() != english_label; }, 5000))
      << "the loaded preset's description stays English";
  EXPECT_TRUE(label->text().contains(QStringLiteral("Bin picking con PhoXi M")))
      << label->text().toStdString();
  int bundled = 0;
  for (int i = 1; i < combo->count(); ++i) {
    const QString file = combo->itemData(i).toString();
    const std::string english = core::loadPreset(file.toStdString()).description;
    const QString tip = combo->itemData(i, Qt::ToolTipRole).toString();
    EXPECT_FALSE(tip.isEmpty()) << file.toStdString();
    EXPECT_NE(tip.toStdString(), english) << file.toStdString() << ": description not translated";
    ++bundled;
  }
  EXPECT_GE(bundled, 10) << "the bundled presets are listed";

  ASSERT_TRUE(ui::applyLanguage(QStringLiteral("en")));
  ASSERT_TRUE(QTest::qWaitFor([&] { return label->text() == english_label; }, 5000))
      << label->text().toStdString();
  for (int i = 0; i < combo->count(); ++i)
    EXPECT_EQ(combo->itemData(i, Qt::ToolTipRole).toString(), english_tips[i]) << i;
}
