#pragma once
/// @file CalibrationWizard.h
/// Tools → Hand-eye calibration: the GUI counterpart of `scanpick-cli calibrate`
/// (docs/calibration.md). The operator chooses the mode, the units and the target, loads a poses
/// file (one table row per robot pose and its scan) and presses Calibrate: the calibration runs in
/// the background (core::calib::runCalibration, as the CLI runs it), can be cancelled, and fills
/// each row with the spheres found, the target fit and the pose's residual (or why it was
/// rejected), then shows the camera and target poses. Save writes the calibration file atomically.
/// Errors are shown in the dialog and nothing is written. All texts follow the language.

#include "core/calib/HandEye.h"
#include "ui/TranslatedTexts.h"

#include <QDialog>
#include <memory>
#include <vector>

class QComboBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTableWidget;

namespace scanpick::core::calib {
struct PoseEntry;
struct CalibrationOutcome;
} // namespace scanpick::core::calib

namespace scanpick::ui {

class JobPool;
class JobRunner;
using core::calib::CalibrationOutcome;

class CalibrationWizard : public QDialog {
  Q_OBJECT
public:
  /// What the dialog shows.
  enum class State {
    NoPoses, ///< no poses file loaded (or it could not be read)
    Ready,   ///< poses loaded, not calibrated with the current choices
    Running, ///< calibrating in the background
    Done,    ///< calibrated: result() is set and can be saved
    Failed,  ///< the last calibration failed (messageText() says why)
  };
  /// The table's columns.
  enum Column { ScanCol, FlangeCol, SpheresCol, FitCol, RmsCol, MaxCol, RotCol, StatusCol, Cols };

  explicit CalibrationWizard(QWidget* parent = nullptr);
  ~CalibrationWizard() override;

  /// Reads `path` as the poses file (the CLI's --poses) and lists its poses; false, with the
  /// reason in messageText(), when it cannot be read.
  bool loadPosesFile(const QString& path);
  /// The target file (the CLI's --target); empty for the built-in target.
  void setTargetFile(const QString& path);
  /// Units of the scans ("mm" or "m") and of the robot positions ("mm", "m", or empty for the
  /// scans' units).
  void setUnits(const QString& scan_units, const QString& pose_units = {});

  /// Starts the calibration in the background (no-op without poses or while one runs).
  void calibrate();
  /// Stops a running calibration; its result is dropped.
  void cancel();
  /// Writes the calibration to `path` as given (core::calib::saveCalibration, atomic); false, with
  /// the reason in messageText(), when there is no result or the file cannot be written.
  bool saveTo(const QString& path);

  [[nodiscard]] State state() const { return m_state; }
  /// The calibration shown, null unless state() is Done.
  [[nodiscard]] const core::calib::HandEyeResult* result() const;
  [[nodiscard]] QTableWidget* table() const { return m_table; }
  /// The message line (errors, cancel, saved) and the result text, as shown.
  [[nodiscard]] QString messageText() const;
  [[nodiscard]] QString resultText() const;

signals:
  /// A calibration ended: with a result (`success`), an error or a cancel.
  void calibrationFinished(bool success);

protected:
  void changeEvent(QEvent* event) override;
  void reject() override;

private:
  /// What the message line says (rendered in the current language by showTexts).
  enum class Message { None, LoadFailed, CalibrationFailed, Cancelled, Saved, SaveFailed };

  void buildChoices();
  void buildButtons();
  void bindTexts();
  /// Asks for a poses or target file.
  void browsePoses();
  void browseTarget();
  void askSave();
  /// The choices changed: a result shown no longer matches them.
  void choicesChanged();
  void setMessage(Message message, const QString& detail = {});
  void finish(std::shared_ptr<const CalibrationOutcome> outcome);
  /// Sets every text from the state, in the current language.
  void showTexts();
  void showRows();
  void showRow(int row);
  [[nodiscard]] QString resultSummary() const;

  QComboBox* m_mode = nullptr;
  QComboBox* m_scan_units = nullptr;
  QComboBox* m_pose_units = nullptr;
  QLineEdit* m_target = nullptr;
  QLineEdit* m_poses = nullptr;
  QPushButton* m_target_browse = nullptr;
  QPushButton* m_poses_browse = nullptr;
  QTableWidget* m_table = nullptr;
  QProgressBar* m_progress = nullptr;
  QLabel* m_message = nullptr;
  QLabel* m_result = nullptr;
  QPushButton* m_calibrate = nullptr;
  QPushButton* m_cancel = nullptr;
  QPushButton* m_save = nullptr;
  QPushButton* m_close = nullptr;

  State m_state = State::NoPoses;
  Message m_message_kind = Message::None;
  QString m_message_detail;
  std::vector<core::calib::PoseEntry> m_entries;
  std::shared_ptr<const CalibrationOutcome> m_outcome;
  /// The dialog's own job thread: the destructor cancels the job and this pool waits for it, so
  /// the job never outlives the dialog.
  std::unique_ptr<JobPool> m_pool;
  JobRunner* m_jobs = nullptr;
  TranslatedTexts m_texts;
};

} // namespace scanpick::ui
