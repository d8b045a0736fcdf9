#pragma once
/// @file CoveragePanel.h
/// View → View coverage: which directions the part can be seen from its taught views cover
/// (core::viewCoverage), as a sphere (CoverageSphere) and in words: how many views are placed in
/// the part and how many are left out, the share of the directions covered, and up to three
/// directions to teach next; and, per view, what a scan of it may leave open (the rotations its
/// surface cannot pin, core::describeAmbiguities, with the view's own parameters). MainWindow
/// hands it the part's views whenever they change; both are measured in the background. All
/// texts but the core's sentences follow the language.

#include "core/ambiguity/ViewAmbiguities.h"
#include "core/model/ViewCoverage.h"
#include "ui/TranslatedTexts.h"

#include <QWidget>
#include <memory>
#include <vector>

class QLabel;
class QScrollArea;

namespace scanpick::ui {

class CoverageSphere;
class JobPool;
class JobRunner;

class CoveragePanel : public QWidget {
  Q_OBJECT
public:
  /// What the panel shows.
  enum class State {
    NoModel,   ///< no view opened or taught
    Measuring, ///< the coverage is being measured
    Shown,     ///< coverage() is shown
    Failed,    ///< the measure failed (error())
  };

  /// Measures on `pool` (must outlive the panel's jobs; see JobRunner).
  explicit CoveragePanel(JobPool* pool, QWidget* parent = nullptr);

  /// Measures the coverage of `views` (the views of one part) in the background and shows it;
  /// with none, says that there is no model. Emits coverageShown when the panel is up to date.
  void setViews(std::vector<std::shared_ptr<const core::TaughtModel>> views);
  /// Cancels a running measure.
  void cancel();

  [[nodiscard]] State state() const { return m_state; }
  /// The coverage shown (null unless state() is Shown).
  [[nodiscard]] const core::ViewCoverage* coverage() const { return m_coverage.get(); }
  [[nodiscard]] CoverageSphere* sphere() const { return m_sphere; }
  /// The summary line and the suggestions as shown, in the current language.
  [[nodiscard]] QString summaryText() const;
  [[nodiscard]] QString suggestionsText() const;
  /// What each view leaves open, as shown (empty unless state() is Shown).
  [[nodiscard]] QString ambiguitiesText() const;

  /// `d_part` (unit, part frame, from the part towards the camera) in words: from above, from
  /// below or from the side, with its azimuth (degrees in the XY plane from +X towards +Y) and
  /// elevation (degrees from the XY plane towards +Z).
  static QString describeDirection(const Eigen::Vector3d& d_part);

signals:
  /// The panel shows the coverage of the views last given (or that there is none).
  void coverageShown();

protected:
  void changeEvent(QEvent* event) override;

private:
  /// Sets the labels from the state, in the current language.
  void showTexts();
  /// Sets the ambiguities' label from m_ambiguities.
  void showAmbiguities();

  core::ViewCoverageOptions m_options;
  State m_state = State::NoModel;
  std::shared_ptr<const core::ViewCoverage> m_coverage;
  std::vector<core::ViewAmbiguities> m_ambiguities; ///< per view, with m_coverage
  QString m_error;
  JobRunner* m_jobs = nullptr;
  CoverageSphere* m_sphere = nullptr;
  QLabel* m_summary = nullptr;
  QLabel* m_legend = nullptr;
  QLabel* m_suggestions = nullptr;
  QLabel* m_ambiguity_text = nullptr;
  QScrollArea* m_ambiguity_scroll = nullptr; ///< holds m_ambiguity_text
  TranslatedTexts m_texts;
};

} // namespace scanpick::ui
