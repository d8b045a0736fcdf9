#include "ui/panels/ParameterPanel.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/params/ParamsJson.h"

#include <QCheckBox>
#include <QComboBox>
#include <QCoreApplication>
#include <QDir>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QVBoxLayout>
#include <cmath>
#include <set>

#ifndef SCANPICK_PRESETS_DIR
#define SCANPICK_PRESETS_DIR ""
#endif

namespace scanpick::ui {
namespace {

int decimalsFor(double step) {
  int decimals = 0;
  while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) -
                                  std::round(step * std::pow(10.0, decimals))) > 1e-9)
    ++decimals;
  return std::max(decimals, 1);
}

QString qs(const std::string& s) {
  return QString::fromStdString(s);
}

QString translated(const std::string& s) {
  return ParameterPanel::translatedParamText(s);
}

QString translatedStage(core::Stage stage) {
  return QCoreApplication::translate("scanpick::core", core::stageName(stage).c_str());
}

/// Keeps the mouse wheel from changing an editor the operator has not clicked into: over an
/// unfocused editor the wheel scrolls the panel instead (an ignored wheel event goes on to the
/// parent, the scroll area).
class WheelGuard : public QObject {
public:
  using QObject::QObject;
  bool eventFilter(QObject* watched, QEvent* event) override {
    if (event->type() == QEvent::Wheel) {
      const auto* widget = qobject_cast<QWidget*>(watched);
      if (widget && !widget->hasFocus()) {
        event->ignore();
        return true;
      }
    }
    return false;
  }
};

/// The tooltip of the preset list's first entry.
QString derivedEntryTip() {
  return ParameterPanel::tr(
      "Teach derives every parameter from the part and the scan (point spacing, depth noise, "
      "the part's size) and shows each here with its reason. Values you change by hand before "
      "teaching override the derived ones, as --set does on the command line. A preset below "
      "is used as it is, with nothing derived.");
}

} // namespace

ParameterPanel::ParameterPanel(QWidget* parent) : QWidget(parent) {
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);

  auto* preset_row = new QHBoxLayout;
  m_presets = new QComboBox(this);
  m_presets->setObjectName(QStringLiteral("presetCombo"));
  auto* load = m_load = new QPushButton(this);
  auto* save = m_save = new QPushButton(this);
  preset_row->addWidget(m_presets, 1);
  preset_row->addWidget(load);
  preset_row->addWidget(save);
  outer->addLayout(preset_row);
  // What the loaded preset is for (its file's description).
  m_preset_description = new QLabel(this);
  m_preset_description->setObjectName(QStringLiteral("presetDescription"));
  m_preset_description->setWordWrap(true);
  m_preset_description->setVisible(false);
  outer->addWidget(m_preset_description);
  // Which values teach derived from the part (marked "derived" below).
  m_derived_note = new QLabel(this);
  m_derived_note->setObjectName(QStringLiteral("derivedNote"));
  m_derived_note->setWordWrap(true);
  m_derived_note->setVisible(false);
  outer->addWidget(m_derived_note);
  // The few parameters tuned for a cell are shown; the rest (derived at teach) on demand.
  m_show_advanced = new QCheckBox(this);
  m_show_advanced->setObjectName(QStringLiteral("showAdvanced"));
  outer->addWidget(m_show_advanced);
  connect(m_show_advanced, &QCheckBox::toggled, this, [this] { showAdvanced(); });
  fillPresetList();
  connect(m_presets, &QComboBox::activated, this, [this](int index) {
    if (index == 0)
      chooseDerived();
    else
      loadPresetOrWarn(m_presets->itemData(index).toString());
  });
  connect(load, &QPushButton::clicked, this, [this] {
    loadPresetOrWarn(QFileDialog::getOpenFileName(this, tr("Load preset"), presetsDirectory(),
                                                  tr("Presets (*.json)")));
  });
  connect(save, &QPushButton::clicked, this, [this] {
    const QString path =
        QFileDialog::getSaveFileName(this, tr("Save preset"), QString(), tr("Presets (*.json)"));
    if (path.isEmpty())
      return;
    try {
      savePresetFile(path, QFileInfo(path).completeBaseName());
    } catch (const std::exception& e) {
      QMessageBox::warning(this, tr("Preset"), QString::fromUtf8(e.what()));
    }
  });

  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  auto* body = new QWidget(scroll);
  auto* body_layout = new QVBoxLayout(body);
  std::map<core::Stage, QFormLayout*> forms;
  auto* wheel_guard = new WheelGuard(this);
  for (const core::ParamInfo& info : core::parameterTable()) {
    auto& form = forms[info.stage];
    if (!form) {
      auto* group = new QGroupBox(body);
      m_groups.emplace_back(group, info.stage);
      form = new QFormLayout(group);
      form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
      body_layout->addWidget(group);
    }
    QWidget* editor = makeEditor(info);
    // A click or Tab focuses an editor; the wheel alone does not (see WheelGuard).
    editor->setFocusPolicy(Qt::StrongFocus);
    editor->installEventFilter(wheel_guard);
    editor->setObjectName(qs(info.key));
    m_editors[info.key] = editor;
    // The editor and, when teach derived its value, a small "derived" marker beside it.
    auto* row = new QWidget(body);
    auto* row_layout = new QHBoxLayout(row);
    row_layout->setContentsMargins(0, 0, 0, 0);
    row_layout->addWidget(editor, 1);
    auto* marker = new QLabel(row);
    marker->setObjectName(qs(info.key + ".derived"));
    marker->setForegroundRole(QPalette::Link);
    QFont small = marker->font();
    small.setItalic(true);
    small.setPointSizeF(small.pointSizeF() * 0.85);
    marker->setFont(small);
    // Its room is kept while hidden, so that the editors line up.
    QSizePolicy keep_room = marker->sizePolicy();
    keep_room.setRetainSizeWhenHidden(true);
    marker->setSizePolicy(keep_room);
    marker->setVisible(false);
    row_layout->addWidget(marker);
    m_markers[info.key] = marker;
    auto* label = new QLabel(row);
    label->setBuddy(editor);
    m_labels[info.key] = label;
    form->addRow(label, row);
    m_forms[info.key] = form;
  }
  auto* misc = m_misc_group = new QGroupBox(body);
  auto* misc_form = new QFormLayout(misc);
  m_seed = new QSpinBox(misc);
  m_seed->setObjectName(QStringLiteral("seed"));
  m_seed->setRange(0, std::numeric_limits<int>::max());
  m_seed->setFocusPolicy(Qt::StrongFocus);
  m_seed->installEventFilter(wheel_guard);
  m_seed_label = new QLabel(misc);
  m_seed_label->setBuddy(m_seed);
  misc_form->addRow(m_seed_label, m_seed);
  body_layout->addWidget(misc);
  body_layout->addStretch(1);
  connect(m_seed, &QSpinBox::valueChanged, this, [this](int value) {
    if (m_updating)
      return;
    const core::RecognitionParams before = m_params;
    m_params.seed = static_cast<std::uint64_t>(value);
    m_hand_edits.insert("seed");
    if (const auto stage = core::firstChangedStage(before, m_params))
      emit paramsChanged(m_params, *stage);
  });
  scroll->setWidget(body);
  outer->addWidget(scroll, 1);
  refreshEditors();
  showAdvanced();
  retranslateUi();
}

void ParameterPanel::showAdvanced() {
  const bool all = m_show_advanced->isChecked();
  std::set<core::Stage> shown;
  for (const core::ParamInfo& info : core::parameterTable()) {
    const bool visible = all || info.tuned;
    m_forms.at(info.key)->setRowVisible(m_labels.at(info.key), visible);
    if (visible)
      shown.insert(info.stage);
  }
  for (const auto& [group, stage] : m_groups)
    group->setVisible(shown.count(stage) > 0);
  m_misc_group->setVisible(all);
}

QString ParameterPanel::translatedParamText(const std::string& english) {
  return QCoreApplication::translate("scanpick::core::params", english.c_str());
}

QString ParameterPanel::translatedPresetText(const std::string& english) {
  return english.empty() ? QString()
                         : QCoreApplication::translate("scanpick::presets", english.c_str());
}

void ParameterPanel::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange)
    retranslateUi();
  QWidget::changeEvent(event);
}

void ParameterPanel::retranslateUi() {
  m_load->setText(tr("Load…"));
  m_save->setText(tr("Save…"));
  m_derived_note->setText(tr("Values marked “derived” come from the part and the scan at "
                             "teach: hover one for its reason. Values you change override "
                             "them at the next teach."));
  m_show_advanced->setText(tr("Show advanced parameters"));
  m_show_advanced->setToolTip(tr("Shown first are the parameters tuned for a cell: the floor, the "
                                 "split into objects, verification, how many detections and "
                                 "ICP. Teach derives the others from the part and the scan."));
  for (const auto& [group, stage] : m_groups)
    group->setTitle(translatedStage(stage));
  for (const core::ParamInfo& info : core::parameterTable()) {
    m_labels.at(info.key)->setText(translated(info.label));
    m_markers.at(info.key)->setText(tr("derived"));
    QWidget* editor = m_editors.at(info.key);
    const QString suffix =
        info.unit.empty() ? QString() : QStringLiteral(" ") + translated(info.unit);
    if (auto* ispin = qobject_cast<QSpinBox*>(editor))
      ispin->setSuffix(suffix);
    else if (auto* dspin = qobject_cast<QDoubleSpinBox*>(editor))
      dspin->setSuffix(suffix);
    else if (auto* combo = qobject_cast<QComboBox*>(editor))
      for (int i = 0; i < combo->count() && i < static_cast<int>(info.choices.size()); ++i)
        combo->setItemText(i, translated(info.choices[std::size_t(i)]));
  }
  m_misc_group->setTitle(tr("Random"));
  m_seed_label->setText(tr("Seed"));
  m_seed->setToolTip(tr("Seed of every random choice: the same scan, parameters and seed give "
                        "the same result."));
  m_presets->setItemText(0, tr("Derived from the part (default)"));
  m_presets->setItemData(0, derivedEntryTip(), Qt::ToolTipRole);
  for (int i = 1; i < m_presets->count(); ++i)
    m_presets->setItemData(
        i, translatedPresetText(m_presets->itemData(i, kDescriptionRole).toString().toStdString()),
        Qt::ToolTipRole);
  setChoice(m_choice); // the list's tooltip
  showPresetDescription();
  refreshReasons(); // the editors' tooltips: descriptions and reasons
}

QWidget* ParameterPanel::makeEditor(const core::ParamInfo& info) {
  switch (info.type) {
  case core::ParamType::Bool: {
    auto* box = new QCheckBox(this);
    connect(box, &QCheckBox::toggled, this,
            [this, &info](bool on) { editorChanged(info, on ? 1.0 : 0.0); });
    return box;
  }
  case core::ParamType::Enum: {
    auto* combo = new QComboBox(this);
    for (const std::string& choice : info.choices)
      combo->addItem(translated(choice));
    connect(combo, &QComboBox::currentIndexChanged, this,
            [this, &info](int index) { editorChanged(info, index); });
    return combo;
  }
  case core::ParamType::Int: {
    auto* spin = new QSpinBox(this);
    spin->setRange(static_cast<int>(info.min_value), static_cast<int>(info.max_value));
    spin->setSingleStep(std::max(1, static_cast<int>(info.step)));
    spin->setKeyboardTracking(false);
    connect(spin, &QSpinBox::valueChanged, this, [this, &info](int v) { editorChanged(info, v); });
    return spin;
  }
  case core::ParamType::Double:
  default: {
    auto* spin = new QDoubleSpinBox(this);
    spin->setDecimals(decimalsFor(info.step));
    spin->setRange(info.min_value, info.max_value);
    spin->setSingleStep(info.step);
    spin->setKeyboardTracking(false);
    connect(spin, &QDoubleSpinBox::valueChanged, this,
            [this, &info](double v) { editorChanged(info, v); });
    return spin;
  }
  }
}

void ParameterPanel::editorChanged(const core::ParamInfo& info, double value) {
  if (m_updating)
    return;
  const core::RecognitionParams before = m_params;
  info.set(m_params, value);
  m_hand_edits.insert(info.key);
  if (m_reasons.erase(info.key) > 0)
    refreshReasons();
  if (const auto stage = core::firstChangedStage(before, m_params))
    emit paramsChanged(m_params, *stage);
}

void ParameterPanel::refreshEditors() {
  m_updating = true;
  for (const core::ParamInfo& info : core::parameterTable()) {
    QWidget* w = m_editors.at(info.key);
    const double v = info.get(m_params);
    if (auto* box = qobject_cast<QCheckBox*>(w))
      box->setChecked(v >= 0.5);
    else if (auto* combo = qobject_cast<QComboBox*>(w))
      combo->setCurrentIndex(static_cast<int>(std::lround(v)));
    else if (auto* ispin = qobject_cast<QSpinBox*>(w))
      ispin->setValue(static_cast<int>(std::lround(v)));
    else if (auto* dspin = qobject_cast<QDoubleSpinBox*>(w))
      dspin->setValue(v);
  }
  m_seed->setValue(static_cast<int>(std::min<std::uint64_t>(m_params.seed, INT32_MAX)));
  m_updating = false;
}

void ParameterPanel::refreshReasons() {
  for (const core::ParamInfo& info : core::parameterTable()) {
    const auto reason = m_reasons.find(info.key);
    const bool derived = reason != m_reasons.end();
    const QString description = translated(info.description);
    m_editors.at(info.key)->setToolTip(
        derived ? description + QStringLiteral("\n\n") +
                      tr("Derived from the part: %1").arg(qs(reason->second))
                : description);
    QLabel* marker = m_markers.at(info.key);
    marker->setToolTip(derived ? qs(reason->second) : QString());
    marker->setVisible(derived);
  }
  m_derived_note->setVisible(!m_reasons.empty());
}

void ParameterPanel::setParams(const core::RecognitionParams& params,
                               std::map<std::string, std::string> reasons) {
  m_params = params;
  m_reasons = std::move(reasons);
  m_hand_edits.clear();
  refreshEditors();
  refreshReasons();
}

bool ParameterPanel::setValue(const std::string& key, double value) {
  const core::ParamInfo* info = core::findParameter(key);
  if (!info)
    return false;
  const core::RecognitionParams before = m_params;
  info->set(m_params, value);
  m_hand_edits.insert(key);
  if (m_reasons.erase(key) > 0)
    refreshReasons();
  refreshEditors();
  if (const auto stage = core::firstChangedStage(before, m_params))
    emit paramsChanged(m_params, *stage);
  return true;
}

QWidget* ParameterPanel::editor(const std::string& key) const {
  const auto it = m_editors.find(key);
  return it == m_editors.end() ? nullptr : it->second;
}

void ParameterPanel::loadPresetFile(const QString& path) {
  const core::Preset preset = core::loadPreset(path.toStdString());
  const core::RecognitionParams before = m_params;
  setParams(preset.params);
  // The list shows the preset in effect; a file from elsewhere (Load…) joins it.
  int index = -1;
  const QString canonical = QFileInfo(path).canonicalFilePath();
  for (int i = 1; i < m_presets->count() && index < 0; ++i)
    if (QFileInfo(m_presets->itemData(i).toString()).canonicalFilePath() == canonical)
      index = i;
  if (index < 0) {
    m_presets->addItem(QFileInfo(path).completeBaseName(), QFileInfo(path).absoluteFilePath());
    index = m_presets->count() - 1;
    setEntryDescription(index, preset.description);
  }
  m_preset_name = qs(preset.name);
  m_preset_description_en = qs(preset.description);
  setChoice(index);
  showPresetDescription();
  core::logger()->info("loaded preset '{}' from {}", preset.name, path.toStdString());
  emit presetLoaded(path);
  emit paramsChanged(m_params,
                     core::firstChangedStage(before, m_params).value_or(core::Stage::Preprocess));
}

void ParameterPanel::chooseDerived() {
  const core::RecognitionParams before = m_params;
  setParams(core::RecognitionParams{});
  m_preset_name.clear();
  m_preset_description_en.clear();
  setChoice(0);
  showPresetDescription();
  core::logger()->info("parameters: derived from the part and the scan at teach");
  emit presetLoaded(QString());
  emit paramsChanged(m_params,
                     core::firstChangedStage(before, m_params).value_or(core::Stage::Preprocess));
}

void ParameterPanel::setEntryDescription(int index, const std::string& english) {
  m_presets->setItemData(index, qs(english), kDescriptionRole);
  m_presets->setItemData(index, translatedPresetText(english), Qt::ToolTipRole);
}

void ParameterPanel::showPresetDescription() {
  const QString text = translatedPresetText(m_preset_description_en.toStdString());
  m_preset_description->setText(
      QStringLiteral("<b>%1</b>: %2").arg(m_preset_name.toHtmlEscaped(), text.toHtmlEscaped()));
  m_preset_description->setToolTip(text);
  m_preset_description->setVisible(!m_preset_description_en.isEmpty());
}

void ParameterPanel::setChoice(int index) {
  m_choice = index;
  m_presets->setCurrentIndex(index);
  // The list's own tooltip says what the entry in effect does.
  const QString tip = m_presets->itemData(index, Qt::ToolTipRole).toString();
  m_presets->setToolTip(tip.isEmpty() ? tr("Bundled parameter presets") : tip);
}

void ParameterPanel::loadPresetOrWarn(const QString& path) {
  if (path.isEmpty())
    return;
  try {
    loadPresetFile(path);
  } catch (const std::exception& e) {
    setChoice(m_choice); // the list goes back to what is in effect
    QMessageBox::warning(this, tr("Preset"), QString::fromUtf8(e.what()));
  }
}

void ParameterPanel::savePresetFile(const QString& path, const QString& name) const {
  core::savePreset(path.toStdString(),
                   core::Preset{name.toStdString(), "saved from scanpick", m_params});
  core::logger()->info("saved preset to {}", path.toStdString());
}

QString ParameterPanel::presetsDirectory() {
  // Next to an installed binary first, then the source tree the build came from.
  const QString installed = QCoreApplication::applicationDirPath() + "/../share/scanpick/presets";
  if (QDir(installed).exists())
    return QDir(installed).canonicalPath();
  return QStringLiteral(SCANPICK_PRESETS_DIR);
}

void ParameterPanel::fillPresetList() {
  m_presets->clear();
  m_presets->addItem(tr("Derived from the part (default)"), QString());
  m_presets->setItemData(0, derivedEntryTip(), Qt::ToolTipRole);
  const QDir dir(presetsDirectory());
  for (const QFileInfo& file :
       dir.entryInfoList({QStringLiteral("*.json")}, QDir::Files, QDir::Name)) {
    m_presets->addItem(file.completeBaseName(), file.absoluteFilePath());
    // Each entry says what it is for; a file that does not read is still listed, and says why
    // when chosen.
    try {
      setEntryDescription(m_presets->count() - 1,
                          core::loadPreset(file.absoluteFilePath().toStdString()).description);
    } catch (const std::exception& e) {
      core::logger()->warn("preset {}: {}", file.absoluteFilePath().toStdString(), e.what());
    }
  }
  setChoice(0);
}

core::RecognitionParams withHandEdits(core::RecognitionParams derived,
                                      const core::RecognitionParams& panel,
                                      const std::set<std::string>& keys) {
  for (const std::string& key : keys) {
    if (key == "seed")
      derived.seed = panel.seed;
    else if (const core::ParamInfo* info = core::findParameter(key))
      info->set(derived, info->get(panel));
  }
  return derived;
}

} // namespace scanpick::ui
