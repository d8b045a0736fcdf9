#include "ui/panels/CalibrationWizard.h"

#include "core/calib/CalibJson.h"
#include "core/calib/CalibrationRun.h"
#include "ui/FileDialogs.h"
#include "ui/jobs/JobRunner.h"

#include <QComboBox>
#include <QEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFont>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>

namespace scanpick::ui {
namespace {

QLabel* selectableLabel(const char* name, QWidget* parent) {
  auto* label = new QLabel(parent);
  label->setObjectName(QString::fromLatin1(name));
  label->setWordWrap(true);
  label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  return label;
}

template <typename W> W* named(W* widget, const char* name) {
  widget->setObjectName(QString::fromLatin1(name));
  return widget;
}

/// The unit a combo box holds ("mm"/"m"), or `fallback` for an empty entry ("as the scans").
core::LengthUnit unitOf(const QComboBox* combo, core::LengthUnit fallback) {
  const QString unit = combo->currentData().toString();
  return unit.isEmpty() ? fallback : core::parseLengthUnit(unit.toStdString());
}

} // namespace

CalibrationWizard::CalibrationWizard(QWidget* parent) : QDialog(parent) {
  setObjectName(QStringLiteral("calibrationWizard"));
  setSizeGripEnabled(true);
  resize(980, 640);
  m_pool = std::make_unique<JobPool>(1);
  m_jobs = new JobRunner(m_pool.get(), this);
  auto* layout = new QVBoxLayout(this);
  buildChoices();
  m_table = named(new QTableWidget(0, Cols, this), "calibrationPoses");
  m_table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  m_table->setSelectionBehavior(QAbstractItemView::SelectRows);
  m_table->horizontalHeader()->setStretchLastSection(true);
  layout->addWidget(m_table, 1);
  m_progress = named(new QProgressBar(this), "calibrationProgress");
  m_progress->setRange(0, 1000);
  m_progress->setVisible(false);
  layout->addWidget(m_progress);
  m_message = selectableLabel("calibrationMessage", this);
  m_result = selectableLabel("calibrationResult", this);
  // Lines of fixed-width numbers, kept whole: the label is as tall as its lines.
  m_result->setWordWrap(false);
  m_result->setFont(QFont(QStringLiteral("monospace")));
  layout->addWidget(m_message);
  layout->addWidget(m_result);
  buildButtons();
  connect(m_jobs, &JobRunner::progress, this,
          [this](double f) { m_progress->setValue(int(std::min(f, 1.0) * 1000)); });
  bindTexts();
}

CalibrationWizard::~CalibrationWizard() {
  // The job stops at its next scan; m_pool's destructor waits for it.
  m_jobs->cancel();
}

void CalibrationWizard::buildChoices() {
  auto* form = new QFormLayout;
  m_mode = named(new QComboBox(this), "calibrationMode");
  for (const auto mode : {core::calib::HandEyeMode::EyeToHand, core::calib::HandEyeMode::EyeInHand})
    m_mode->addItem(QString(), QString::fromStdString(core::calib::modeName(mode)));
  m_scan_units = named(new QComboBox(this), "calibrationScanUnits");
  m_pose_units = named(new QComboBox(this), "calibrationPoseUnits");
  m_pose_units->addItem(QString(), QString());
  for (QComboBox* combo : {m_scan_units, m_pose_units})
    for (const char* unit : {"mm", "m"})
      combo->addItem(QString(), QString::fromLatin1(unit));
  m_target = named(new QLineEdit(this), "calibrationTargetFile");
  m_target->setClearButtonEnabled(true);
  m_target_browse = named(new QPushButton(this), "calibrationTargetBrowse");
  m_poses = named(new QLineEdit(this), "calibrationPosesFile");
  m_poses->setReadOnly(true);
  m_poses_browse = named(new QPushButton(this), "calibrationPosesBrowse");
  const auto row = [this](QWidget* edit, QWidget* button) {
    auto* r = new QHBoxLayout;
    r->addWidget(edit, 1);
    r->addWidget(button);
    return r;
  };
  const char* captions[] = {"modeCaption", "scanUnitsCaption", "poseUnitsCaption", "targetCaption",
                            "posesCaption"};
  std::vector<QLabel*> labels;
  for (const char* caption : captions)
    labels.push_back(named(new QLabel(this), caption));
  form->addRow(labels[0], m_mode);
  form->addRow(labels[1], m_scan_units);
  form->addRow(labels[2], m_pose_units);
  form->addRow(labels[3], row(m_target, m_target_browse));
  form->addRow(labels[4], row(m_poses, m_poses_browse));
  static_cast<QVBoxLayout*>(layout())->addLayout(form);
  m_texts.bind(labels[0], "text", [] { return tr("Mode:"); });
  m_texts.bind(labels[1], "text", [] { return tr("Scan units:"); });
  m_texts.bind(labels[2], "text", [] { return tr("Robot positions:"); });
  m_texts.bind(labels[3], "text", [] { return tr("Target file:"); });
  m_texts.bind(labels[4], "text", [] { return tr("Poses file:"); });

  connect(m_mode, &QComboBox::currentIndexChanged, this, &CalibrationWizard::choicesChanged);
  connect(m_scan_units, &QComboBox::currentIndexChanged, this, [this] {
    if (m_pose_units->currentData().toString().isEmpty() && !m_poses->text().isEmpty())
      loadPosesFile(m_poses->text());
    choicesChanged();
  });
  connect(m_pose_units, &QComboBox::currentIndexChanged, this, [this] {
    if (!m_poses->text().isEmpty())
      loadPosesFile(m_poses->text());
    choicesChanged();
  });
  connect(m_target, &QLineEdit::textChanged, this, &CalibrationWizard::choicesChanged);
  connect(m_target_browse, &QPushButton::clicked, this, &CalibrationWizard::browseTarget);
  connect(m_poses_browse, &QPushButton::clicked, this, &CalibrationWizard::browsePoses);
}

void CalibrationWizard::buildButtons() {
  auto* buttons = new QHBoxLayout;
  m_calibrate = named(new QPushButton(this), "calibrateButton");
  m_cancel = named(new QPushButton(this), "cancelCalibrationButton");
  m_save = named(new QPushButton(this), "saveCalibrationButton");
  m_close = named(new QPushButton(this), "closeCalibrationButton");
  m_calibrate->setDefault(true);
  buttons->addWidget(m_calibrate);
  buttons->addWidget(m_cancel);
  buttons->addStretch(1);
  buttons->addWidget(m_save);
  buttons->addWidget(m_close);
  static_cast<QVBoxLayout*>(layout())->addLayout(buttons);
  connect(m_calibrate, &QPushButton::clicked, this, &CalibrationWizard::calibrate);
  connect(m_cancel, &QPushButton::clicked, this, &CalibrationWizard::cancel);
  connect(m_save, &QPushButton::clicked, this, &CalibrationWizard::askSave);
  connect(m_close, &QPushButton::clicked, this, &CalibrationWizard::reject);
}

bool CalibrationWizard::loadPosesFile(const QString& path) {
  cancel();
  m_poses->setText(path);
  m_outcome.reset();
  const core::LengthUnit scan_units = unitOf(m_scan_units, core::LengthUnit::Millimetres);
  try {
    m_entries = core::calib::readPoses(path.toStdString(), unitOf(m_pose_units, scan_units));
  } catch (const std::exception& e) {
    m_entries.clear();
    m_state = State::NoPoses;
    setMessage(Message::LoadFailed, QString::fromStdString(e.what()));
    return false;
  }
  m_state = State::Ready;
  setMessage(Message::None);
  return true;
}

void CalibrationWizard::setTargetFile(const QString& path) {
  m_target->setText(path);
}

void CalibrationWizard::setUnits(const QString& scan_units, const QString& pose_units) {
  m_scan_units->setCurrentIndex(m_scan_units->findData(scan_units));
  m_pose_units->setCurrentIndex(m_pose_units->findData(pose_units));
}

void CalibrationWizard::calibrate() {
  if (m_state == State::Running || m_state == State::NoPoses)
    return;
  core::calib::CalibrationRequest request;
  request.mode = core::calib::modeFromName(m_mode->currentData().toString().toStdString());
  request.poses_file = m_poses->text().toStdString();
  request.target_file = m_target->text().trimmed().toStdString();
  request.scan_units = unitOf(m_scan_units, core::LengthUnit::Millimetres);
  request.pose_units = unitOf(m_pose_units, request.scan_units);
  m_outcome.reset();
  m_state = State::Running;
  m_progress->setValue(0);
  setMessage(Message::None);
  m_jobs->run<CalibrationOutcome>(
      [request](const core::ProgressFn& progress) {
        return core::calib::runCalibration(request, progress);
      },
      [this](std::shared_ptr<const CalibrationOutcome> outcome) { finish(std::move(outcome)); },
      [this](const QString& error) {
        m_state = State::Failed;
        setMessage(Message::CalibrationFailed, error);
        emit calibrationFinished(false);
      });
}

void CalibrationWizard::finish(std::shared_ptr<const CalibrationOutcome> outcome) {
  m_outcome = std::move(outcome);
  if (!m_outcome->entries.empty())
    m_entries = m_outcome->entries;
  const bool success = m_outcome->result.has_value();
  m_state = success ? State::Done : State::Failed;
  if (success)
    setMessage(Message::None);
  else
    setMessage(Message::CalibrationFailed, QString::fromStdString(m_outcome->error));
  emit calibrationFinished(success);
}

void CalibrationWizard::cancel() {
  if (m_state != State::Running)
    return;
  m_jobs->cancel();
  m_state = State::Ready;
  setMessage(Message::Cancelled);
  emit calibrationFinished(false);
}

bool CalibrationWizard::saveTo(const QString& path) {
  if (!result()) {
    setMessage(Message::SaveFailed, tr("calibrate first"));
    return false;
  }
  try {
    core::calib::saveCalibration(path.toStdString(), *m_outcome->result, m_outcome->target);
  } catch (const std::exception& e) {
    setMessage(Message::SaveFailed, QString::fromStdString(e.what()));
    return false;
  }
  setMessage(Message::Saved, path);
  return true;
}

const core::calib::HandEyeResult* CalibrationWizard::result() const {
  return m_state == State::Done && m_outcome && m_outcome->result ? &*m_outcome->result : nullptr;
}

void CalibrationWizard::browsePoses() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open poses file"),
                                                    QFileInfo(m_poses->text()).absolutePath(),
                                                    tr("Poses files (*.json);;All files (*)"));
  if (!path.isEmpty())
    loadPosesFile(path);
}

void CalibrationWizard::browseTarget() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open target file"),
                                                    QFileInfo(m_target->text()).absolutePath(),
                                                    tr("Target files (*.json);;All files (*)"));
  if (!path.isEmpty())
    setTargetFile(path);
}

void CalibrationWizard::askSave() {
  const QString path =
      askSaveFileName(this, tr("Save calibration"), QFileInfo(m_poses->text()).absolutePath(),
                      tr("Calibrations (*.json)"), QStringLiteral("json"));
  if (!path.isEmpty())
    saveTo(path);
}

void CalibrationWizard::choicesChanged() {
  if (m_state == State::Running)
    cancel();
  if (m_state == State::Done || m_state == State::Failed) {
    m_outcome.reset();
    m_state = State::Ready;
    setMessage(Message::None);
  }
}

void CalibrationWizard::setMessage(Message message, const QString& detail) {
  m_message_kind = message;
  m_message_detail = detail;
  showTexts();
}

void CalibrationWizard::reject() {
  cancel();
  QDialog::reject();
}

void CalibrationWizard::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange)
    m_texts.apply();
  QDialog::changeEvent(event);
}

} // namespace scanpick::ui
