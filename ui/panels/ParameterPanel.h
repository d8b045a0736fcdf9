#pragma once
/// @file ParameterPanel.h
/// The parameter editor, built from the core's metadata table (core/params/ParameterTable.h):
/// one editor per parameter with its label, unit, range and step, the description as tooltip,
/// grouped by pipeline stage; presets (core/params/ParamsJson.h) can be loaded and saved, each
/// described (its file's description: the list's tooltips, and a label once loaded). The mouse
/// wheel changes an editor only once it has the focus; otherwise it scrolls the panel.

#include "core/params/ParameterTable.h"

#include <QWidget>
#include <map>
#include <string>

class QComboBox;
class QLabel;
class QSpinBox;

namespace scanpick::ui {

class ParameterPanel : public QWidget {
  Q_OBJECT
public:
  explicit ParameterPanel(QWidget* parent = nullptr);

  [[nodiscard]] const core::RecognitionParams& params() const { return m_params; }
  /// Shows `params` in the editors without emitting paramsChanged.
  void setParams(const core::RecognitionParams& params);
  /// Sets one parameter by key as if the operator had edited it (emits paramsChanged).
  /// Returns false for an unknown key.
  bool setValue(const std::string& key, double value);
  /// The editor of `key` (QDoubleSpinBox, QSpinBox, QCheckBox or QComboBox), or nullptr.
  [[nodiscard]] QWidget* editor(const std::string& key) const;

  /// Loads a preset file into the editors (emits paramsChanged). Throws core::Error.
  void loadPresetFile(const QString& path);
  /// Saves the current parameters as a preset. Throws core::Error.
  void savePresetFile(const QString& path, const QString& name) const;
  /// Folder with the bundled presets (resources/presets).
  static QString presetsDirectory();

signals:
  /// The operator changed a value; `first_stage` is the earliest stage to re-run.
  void paramsChanged(const scanpick::core::RecognitionParams& params,
                     scanpick::core::Stage first_stage);
  /// A preset was loaded from `path`.
  void presetLoaded(const QString& path);

private:
  /// loadPresetFile, a message box instead of an exception; nothing for an empty path.
  void loadPresetOrWarn(const QString& path);
  QWidget* makeEditor(const core::ParamInfo& info);
  void editorChanged(const core::ParamInfo& info, double value);
  void refreshEditors();
  void fillPresetList();

  core::RecognitionParams m_params;
  std::map<std::string, QWidget*> m_editors;
  QComboBox* m_presets = nullptr;
  QLabel* m_preset_description = nullptr; // the loaded preset's description
  QSpinBox* m_seed = nullptr;
  bool m_updating = false;
};

} // namespace scanpick::ui
