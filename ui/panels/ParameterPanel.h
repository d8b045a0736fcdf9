#pragma once
/// @file ParameterPanel.h
/// The parameter editor, built from the core's metadata table (core/params/ParameterTable.h):
/// one editor per parameter with its label, unit, range and step, the description as tooltip,
/// grouped by pipeline stage; presets (core/params/ParamsJson.h) can be loaded and saved, each
/// described (its file's description: the list's tooltips, and a label once loaded). The list's
/// first entry, "Derived from the part (default)", has Teach derive the parameters from the part
/// and the scan instead (core::autoTeachParams); values derived so are marked "derived" beside
/// their editor, with the reason in its tooltip. The mouse wheel changes an editor only once it
/// has the focus; otherwise it scrolls the panel. Every text (labels, units, descriptions, the
/// stages' titles) follows a language switch: the table's English texts are translated in the
/// contexts "scanpick::core::params" and "scanpick::core" (translations/scanpick_it.ts).

#include "core/params/ParameterTable.h"

#include <QWidget>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

class QCheckBox;
class QComboBox;
class QFormLayout;
class QGroupBox;
class QLabel;
class QPushButton;
class QSpinBox;

namespace scanpick::ui {

class ParameterPanel : public QWidget {
  Q_OBJECT
public:
  explicit ParameterPanel(QWidget* parent = nullptr);

  [[nodiscard]] const core::RecognitionParams& params() const { return m_params; }
  /// Shows `params` in the editors without emitting paramsChanged, and `reasons` (key -> why it
  /// has its value, as core::TaughtModel::param_reasons) beside the values derived from the part.
  /// Forgets the hand edits (handEdits); keeps the preset list's choice.
  void setParams(const core::RecognitionParams& params,
                 std::map<std::string, std::string> reasons = {});
  /// Sets one parameter by key as if the operator had edited it (emits paramsChanged).
  /// Returns false for an unknown key.
  bool setValue(const std::string& key, double value);
  /// Why each value shown was derived from the part and the scan, by key (empty: none was). A
  /// value edited by hand loses its reason.
  [[nodiscard]] const std::map<std::string, std::string>& reasons() const { return m_reasons; }
  /// Keys of the values changed by hand (editors, setValue; "seed" for the seed) since the last
  /// setParams, preset load or chooseDerived.
  [[nodiscard]] const std::set<std::string>& handEdits() const { return m_hand_edits; }

  /// True while the preset list's first entry, "Derived from the part (default)", is chosen (at
  /// the first start, and until a preset is loaded): Teach then derives the parameters from the
  /// part and the scan over the core's defaults, the hand edits applied on them.
  [[nodiscard]] bool derivesAtTeach() const { return m_choice == 0; }
  /// Chooses that entry: the core's defaults in the editors, no reasons and no hand edits; emits
  /// presetLoaded with an empty path, then paramsChanged.
  void chooseDerived();
  /// The editor of `key` (QDoubleSpinBox, QSpinBox, QCheckBox or QComboBox), or nullptr.
  [[nodiscard]] QWidget* editor(const std::string& key) const;

  /// Loads a preset file into the editors (emits paramsChanged). Throws core::Error.
  void loadPresetFile(const QString& path);
  /// Saves the current parameters as a preset. Throws core::Error.
  void savePresetFile(const QString& path, const QString& name) const;
  /// Folder with the bundled presets (resources/presets).
  static QString presetsDirectory();

  /// A parameter table text (label, unit, description, choice) in the current language.
  static QString translatedParamText(const std::string& english);
  /// A bundled preset's description in the current language (the English text when it has no
  /// translation, e.g. a preset file from elsewhere).
  static QString translatedPresetText(const std::string& english);

signals:
  /// The operator changed a value; `first_stage` is the earliest stage to re-run.
  void paramsChanged(const scanpick::core::RecognitionParams& params,
                     scanpick::core::Stage first_stage);
  /// A preset was loaded from `path`, or (`path` empty) the derived entry was chosen.
  void presetLoaded(const QString& path);

protected:
  void changeEvent(QEvent* event) override;

private:
  /// Sets every text again in the language now installed.
  void retranslateUi();
  /// loadPresetFile, a message box instead of an exception; nothing for an empty path.
  void loadPresetOrWarn(const QString& path);
  QWidget* makeEditor(const core::ParamInfo& info);
  void editorChanged(const core::ParamInfo& info, double value);
  void refreshEditors();
  /// Shows the tuned parameters' rows (core::ParamInfo::tuned), and the others too while
  /// m_show_advanced is checked; a stage's group only while one of its rows is shown.
  void showAdvanced();
  /// Shows m_reasons: the editors' tooltips, the "derived" markers and the note above them.
  void refreshReasons();
  void fillPresetList();
  /// Keeps preset list entry `index`'s English description (kDescriptionRole) and shows it,
  /// translated, as the entry's tooltip.
  void setEntryDescription(int index, const std::string& english);
  /// Shows the loaded preset's name and description (translated) above the editors, or nothing
  /// when the parameters are derived.
  void showPresetDescription();
  /// Makes entry `index` of the preset list the one in effect (m_choice) and shows it.
  void setChoice(int index);

  core::RecognitionParams m_params;
  std::map<std::string, QWidget*> m_editors;
  std::map<std::string, QLabel*> m_markers;    // "derived", beside each editor
  std::map<std::string, QLabel*> m_labels;     // each editor's label
  std::map<std::string, QFormLayout*> m_forms; // the form holding each editor's row
  QCheckBox* m_show_advanced = nullptr;
  std::vector<std::pair<QGroupBox*, core::Stage>> m_groups;
  QGroupBox* m_misc_group = nullptr;
  QLabel* m_seed_label = nullptr;
  QPushButton* m_load = nullptr;
  QPushButton* m_save = nullptr;
  std::map<std::string, std::string> m_reasons;
  std::set<std::string> m_hand_edits;
  QComboBox* m_presets = nullptr;
  int m_choice = 0;                       // the preset list's entry in effect; 0 derives at teach
  QLabel* m_preset_description = nullptr; // the loaded preset's description
  QString m_preset_name;                  // the loaded preset's, empty when derived
  QString m_preset_description_en;        // the loaded preset's description, in English
  static constexpr int kDescriptionRole = Qt::UserRole + 1; // preset list: English description
  QLabel* m_derived_note = nullptr; // shown while values are marked "derived"
  QSpinBox* m_seed = nullptr;
  bool m_updating = false;
};

/// `derived` with the values of `keys` (handEdits; "seed" for the seed) taken from `panel`: at a
/// derived teach, values set by hand win over derived ones, as --set does on the CLI. Pure: the
/// teach job calls it on its own thread.
core::RecognitionParams withHandEdits(core::RecognitionParams derived,
                                      const core::RecognitionParams& panel,
                                      const std::set<std::string>& keys);

} // namespace scanpick::ui
