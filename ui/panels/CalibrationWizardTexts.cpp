// CalibrationWizard's texts: every label, row and message is made from the state here, in the
// language of the moment, so that a language switch redraws them all (m_texts).
#include "core/calib/CalibJson.h"
#include "core/calib/CalibrationRun.h"
#include "ui/panels/CalibrationWizard.h"

#include <QComboBox>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>
#include <initializer_list>

namespace scanpick::ui {
namespace {

QString number(double value, int decimals) {
  return QString::number(value, 'f', decimals);
}

/// `T` (mm) as position and unit quaternion (w first, w ≥ 0), as the CLI prints it.
QString poseText(const QString& name, const Eigen::Isometry3d& T) {
  Eigen::Quaterniond q(T.linear());
  if (q.w() < 0)
    q.coeffs() = -q.coeffs();
  const Eigen::Vector3d t = T.translation();
  return CalibrationWizard::tr("%1: position %2, %3, %4 mm, quaternion (w x y z) %5 %6 %7 %8")
      .arg(name, number(t.x(), 3), number(t.y(), 3), number(t.z(), 3), number(q.w(), 6),
           number(q.x(), 6), number(q.y(), 6), number(q.z(), 6));
}

QString modeTitle(core::calib::HandEyeMode mode) {
  return mode == core::calib::HandEyeMode::EyeToHand ? CalibrationWizard::tr("Eye-to-hand")
                                                     : CalibrationWizard::tr("Eye-in-hand");
}

/// A cell of `table` with `text` (and `tip`), created when missing.
void setCell(QTableWidget* table, int row, int column, const QString& text,
             const QString& tip = {}) {
  QTableWidgetItem* item = table->item(row, column);
  if (!item) {
    item = new QTableWidgetItem;
    if (column != CalibrationWizard::ScanCol && column != CalibrationWizard::StatusCol)
      item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    table->setItem(row, column, item);
  }
  item->setText(text);
  item->setToolTip(tip);
}

} // namespace

void CalibrationWizard::bindTexts() {
  m_texts.bind(this, "windowTitle", [] { return tr("Hand-eye calibration"); });
  m_texts.bind(m_mode, [this] {
    m_mode->setItemText(0, tr("Eye-to-hand: fixed camera, target on the flange"));
    m_mode->setItemText(1, tr("Eye-in-hand: camera on the flange, fixed target"));
    m_scan_units->setItemText(0, tr("millimetres (mm)"));
    m_scan_units->setItemText(1, tr("metres (m)"));
    m_pose_units->setItemText(0, tr("as the scans"));
    m_pose_units->setItemText(1, tr("millimetres (mm)"));
    m_pose_units->setItemText(2, tr("metres (m)"));
  });
  m_texts.bind(m_mode, "toolTip", [] {
    return tr("Eye-to-hand finds the camera in the robot base (T_base_camera) and the target on "
              "the flange (T_flange_target); eye-in-hand finds the camera on the flange "
              "(T_flange_camera) and the target in the base (T_base_target).");
  });
  m_texts.bind(m_pose_units, "toolTip", [] {
    return tr("Units of the robot's flange positions in the poses file (a UR robot reports m)");
  });
  m_texts.bind(m_target, "placeholderText",
               [] { return tr("built-in target: 4 spheres on a 200 × 160 mm plate"); });
  m_texts.bind(m_poses, "placeholderText", [] { return tr("no poses file loaded"); });
  m_texts.bind(m_target_browse, "text", [] { return tr("Browse…"); });
  m_texts.bind(m_poses_browse, "text", [] { return tr("Load poses…"); });
  m_texts.bind(m_calibrate, "text", [] { return tr("&Calibrate"); });
  m_texts.bind(m_cancel, "text", [] { return tr("Cancel"); });
  m_texts.bind(m_save, "text", [] { return tr("&Save calibration…"); });
  m_texts.bind(m_close, "text", [] { return tr("Close"); });
  m_texts.bind(m_table, [this] {
    m_table->setHorizontalHeaderLabels({tr("Scan"), tr("Flange position (mm)"), tr("Spheres"),
                                        tr("Fit RMS (mm)"), tr("RMS (mm)"), tr("Max (mm)"),
                                        tr("Rotation (°)"), tr("Status")});
  });
  m_texts.bind(this, [this] { showTexts(); });
}

void CalibrationWizard::showTexts() {
  const bool running = m_state == State::Running;
  for (QWidget* w : std::initializer_list<QWidget*>{m_mode, m_scan_units, m_pose_units, m_target,
                                                    m_target_browse, m_poses_browse})
    w->setEnabled(!running);
  m_calibrate->setEnabled(!running && m_state != State::NoPoses && !m_entries.empty());
  m_cancel->setEnabled(running);
  m_save->setEnabled(result() != nullptr);
  m_progress->setVisible(running);
  const bool error = m_message_kind == Message::LoadFailed ||
                     m_message_kind == Message::CalibrationFailed ||
                     m_message_kind == Message::SaveFailed;
  m_message->setStyleSheet(error ? QStringLiteral("color: #c0392b") : QString());
  m_message->setText(messageText());
  m_result->setText(resultSummary());
  showRows();
}

QString CalibrationWizard::messageText() const {
  const int poses = int(m_entries.size());
  switch (m_message_kind) {
  case Message::LoadFailed:
    return tr("The poses file could not be read: %1").arg(m_message_detail);
  case Message::CalibrationFailed:
    return tr("Calibration failed, nothing was written: %1").arg(m_message_detail);
  case Message::Cancelled:
    return tr("Calibration cancelled.");
  case Message::Saved:
    return tr("Calibration saved to %1.").arg(m_message_detail);
  case Message::SaveFailed:
    return tr("The calibration was not saved: %1").arg(m_message_detail);
  case Message::None:
    break;
  }
  switch (m_state) {
  case State::NoPoses:
    return tr("Load a poses file: the scans of the calibration target and the robot's flange "
              "pose at each (docs/calibration.md).");
  case State::Ready:
    return tr("%n pose(s) loaded: press Calibrate.", "", poses);
  case State::Running:
    return tr("Calibrating: finding the target in %n scan(s)…", "", poses);
  case State::Done:
    return tr("Calibrated: save the calibration file.");
  case State::Failed:
    break;
  }
  return {};
}

QString CalibrationWizard::resultText() const {
  return m_result->text();
}

QString CalibrationWizard::resultSummary() const {
  const core::calib::HandEyeResult* r = result();
  if (!r)
    return {};
  int rejected = 0;
  for (const auto& residual : r->residuals)
    rejected += residual.rejected ? 1 : 0;
  QStringList lines;
  lines << tr("%1 calibration from %2 of %3 poses, residuals %4 mm / %5° RMS")
               .arg(modeTitle(r->mode))
               .arg(r->poses_used)
               .arg(r->residuals.size())
               .arg(number(r->rms_mm, 3), number(r->rms_deg, 4));
  lines << (rejected ? tr("%n pose(s) rejected (see the table)", "", rejected)
                     : tr("No pose rejected"));
  lines << poseText(QString::fromStdString(r->cameraName()), r->T_camera);
  lines << poseText(QString::fromStdString(r->targetName()), r->T_target);
  return lines.join('\n');
}

void CalibrationWizard::showRows() {
  const int rows = int(m_entries.size());
  if (m_table->rowCount() != rows)
    m_table->setRowCount(rows);
  for (int row = 0; row < rows; ++row)
    showRow(row);
  m_table->resizeColumnsToContents();
}

void CalibrationWizard::showRow(int row) {
  const core::calib::PoseEntry& entry = m_entries[std::size_t(row)];
  const QString scan = QString::fromStdString(entry.scan.string());
  setCell(m_table, row, ScanCol, QString::fromStdString(entry.scan.filename().string()), scan);
  const Eigen::Vector3d t = entry.T_base_flange.translation();
  setCell(m_table, row, FlangeCol,
          QStringLiteral("%1, %2, %3").arg(number(t.x(), 1), number(t.y(), 1), number(t.z(), 1)));
  QString spheres, fit, rms, max, rot, status, tip;
  const CalibrationOutcome* o = m_state == State::Running ? nullptr : m_outcome.get();
  if (o && row < int(o->scans.size())) {
    const core::calib::ScanReport& s = o->scans[std::size_t(row)];
    spheres = tr("%1 of %2").arg(s.spheres_found).arg(o->target.sphere_centres_mm.size());
    fit = number(s.fit_rms_mm, 3);
    tip = QString::fromStdString(s.units_warning);
  }
  if (o && o->failed_scan == row) {
    status = tr("failed");
    tip = QString::fromStdString(o->error);
  }
  if (o && o->result)
    for (const auto& r : o->result->residuals) {
      if (r.index != row)
        continue;
      rms = number(r.rms_mm, 3);
      max = number(r.max_mm, 3);
      rot = number(r.rot_deg, 4);
      status = r.rejected ? tr("rejected: %1").arg(QString::fromStdString(r.reason)) : tr("used");
      if (r.rejected)
        tip = QString::fromStdString(r.reason);
    }
  setCell(m_table, row, SpheresCol, spheres);
  setCell(m_table, row, FitCol, fit);
  setCell(m_table, row, RmsCol, rms);
  setCell(m_table, row, MaxCol, max);
  setCell(m_table, row, RotCol, rot);
  setCell(m_table, row, StatusCol, status, tip);
  m_table->setVerticalHeaderItem(row, new QTableWidgetItem(QString::number(row + 1)));
}

} // namespace scanpick::ui
