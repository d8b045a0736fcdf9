// Teach tools beside the crop box: the screen-space lasso, the floor-removal preview and the
// sensor the scan comes from, with the Teach panel's buttons.
#include "core/cloud/CloudIo.h"
#include "core/common/Log.h"
#include "core/preprocess/FloorRemoval.h"
#include "ui/MainWindow.h"
#include "ui/Settings.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/CalibrationWizard.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/viewport/Lasso.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QAction>
#include <QComboBox>
#include <QGridLayout>
#include <QLabel>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <QToolButton>
#include <QVBoxLayout>
#include <utility>
#include <vtkActor.h>

namespace scanpick::ui {
namespace {

const QString kSensorSetting = QStringLiteral("teach/sensor");

/// A tool button showing `action` (text, shortcut tooltip, checked state follow it).
QToolButton* actionButton(QAction* action, QWidget* parent) {
  auto* b = new QToolButton(parent);
  b->setDefaultAction(action);
  b->setToolButtonStyle(Qt::ToolButtonTextOnly);
  b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  return b;
}

} // namespace

void MainWindow::buildToolButtons(QVBoxLayout* layout) {
  QWidget* panel = layout->parentWidget();
  auto* sensor_row = new QHBoxLayout;
  auto* sensor_caption = new QLabel(panel);
  m_texts.bind(sensor_caption, "text", [] { return tr("Sensor:"); });
  sensor_row->addWidget(sensor_caption);
  m_sensor_combo = new QComboBox(panel);
  m_sensor_combo->setObjectName(QStringLiteral("sensorCombo"));
  m_texts.bind(m_sensor_combo, "toolTip", [] {
    return tr("Sensor of scans that do not tell (unorganized clouds). An organized "
              "scan whose grid matches a sensor uses that sensor.");
  });
  for (const std::string& name : core::sensorPresetNames())
    m_sensor_combo->addItem(QString::fromStdString(name));
  m_sensor_combo->setCurrentText(
      QSettings().value(kSensorSetting, QStringLiteral("phoxi-m-1032")).toString());
  connect(m_sensor_combo, &QComboBox::currentTextChanged, this,
          [](const QString& name) { QSettings().setValue(kSensorSetting, name); });
  sensor_row->addWidget(m_sensor_combo, 1);
  layout->addLayout(sensor_row);

  m_lasso = new LassoOverlay(m_view, [this](const QPolygonF& polygon) { applyLasso(polygon); });

  auto* grid = new QGridLayout;
  grid->addWidget(actionButton(m_crop_action, panel), 0, 0);
  grid->addWidget(actionButton(m_lasso_action, panel), 0, 1);
  grid->addWidget(actionButton(m_floor_preview_action, panel), 1, 0);
  grid->addWidget(actionButton(m_floor_remove_action, panel), 1, 1);
  grid->addWidget(actionButton(m_grip_action, panel), 2, 0, 1, 2);
  layout->addLayout(grid);
  auto* apply = new QPushButton(panel);
  m_texts.bind(apply, "text", [] { return tr("Apply crop box"); });
  connect(apply, &QPushButton::clicked, this, [this] { applyCrop(); });
  layout->addWidget(apply);
}

std::optional<core::SensorModel> MainWindow::sensorOfGrid(const core::PointCloud& cloud) {
  if (cloud.isOrganized())
    for (const std::string& name : core::sensorPresetNames()) {
      core::SensorModel s = core::sensorPreset(name);
      if (s.width == static_cast<int>(cloud.width) && s.height == static_cast<int>(cloud.height))
        return s;
    }
  return std::nullopt;
}

core::SensorModel MainWindow::currentSensor() const {
  if (m_scan)
    if (auto s = sensorOfGrid(*m_scan))
      return *s;
  return core::sensorPreset(m_sensor_combo->currentText().toStdString());
}

void MainWindow::setLassoActive(bool active) {
  if (active && !m_part) {
    statusBar()->showMessage(tr("Open a scan first"), 5000);
    active = false;
  }
  if (m_lasso_action->isChecked() != active) {
    m_lasso_action->setChecked(active); // re-enters through toggled
    return;
  }
  if (active) {
    setCropBoxVisible(false);
    m_grip_action->setChecked(false);
    statusBar()->showMessage(tr("Lasso: drag around the part; the points inside are kept"));
  }
  m_lasso->setActive(active);
}

void MainWindow::applyLasso(const QPolygonF& polygon_px) {
  if (!m_part)
    return;
  if (polygon_px.size() < 3 || polygon_px.boundingRect().width() < 2 ||
      polygon_px.boundingRect().height() < 2) {
    statusBar()->showMessage(tr("Lasso too small: drag around the part"), 5000);
    return;
  }
  const auto part = m_part;
  // The camera is read now, on the GUI thread; the selection runs in the background.
  const ScreenProjection projection =
      ScreenProjection::fromRenderer(m_view->renderer(), m_view->width(), m_view->height());
  statusBar()->showMessage(tr("Lasso crop…"));
  m_jobs->run<core::PointCloud>(
      [part, projection, polygon_px](const core::ProgressFn&) {
        return selectInLasso(*part, projection, polygon_px);
      },
      [this, part](std::shared_ptr<const core::PointCloud> kept) {
        if (part != m_part)
          return; // the working cloud changed meanwhile; this lasso was drawn on another one
        if (kept->size() == 0) {
          showError(tr("Lasso crop"), tr("The lasso holds no point: draw around the part."));
          return;
        }
        core::logger()->info("lasso crop: {} of {} points kept", kept->size(), part->validCount());
        replacePart(kept, tr("Lasso crop"));
        statusBar()->showMessage(tr("Lasso kept %1 points (Ctrl+Z undoes)").arg(kept->size()),
                                 5000);
      },
      [this](const QString& e) { showError(tr("Lasso crop"), e); });
}

std::size_t MainWindow::floorPreviewCount() const {
  return m_floor_preview && m_floor_preview->part == m_part ? m_floor_preview->removed->size() : 0;
}

void MainWindow::showFloorPreview() {
  if (!m_floor_preview || m_floor_preview->part != m_part) {
    setLayer(QStringLiteral("floor"), nullptr);
    return;
  }
  setLayer(QStringLiteral("floor"),
           makeCloudActor(*m_floor_preview->removed, floorPreviewColour(),
                          QSettings().value(settings::kPointSize, 2.0).toDouble() + 1, ratio()));
}

void MainWindow::previewFloor() {
  if (!m_part)
    return showError(tr("Floor"), tr("Open a scan first."));
  const auto part = m_part;
  const core::RecognitionParams params = m_params->params();
  statusBar()->showMessage(tr("Looking for the floor…"));
  m_apply_floor_pending = false;
  m_jobs->run<FloorPreview>(
      [part, params](const core::ProgressFn& progress) {
        core::FloorParams floor = params.floor;
        floor.enabled = true;
        core::FloorRemovalResult r = core::removeFloor(*part, floor, params.seed, progress);
        // removeFloor drops every point within distance_mm of a found plane: the same test
        // gives the points it took away, for display.
        std::vector<Eigen::Vector3f> removed;
        const float distance = static_cast<float>(floor.distance_mm);
        for (const Eigen::Vector3f& p : part->points_mm) {
          if (!core::isValid(p))
            continue;
          for (const Eigen::Vector4f& plane : r.planes)
            if (std::abs(plane.head<3>().dot(p) + plane[3]) <= distance) {
              removed.push_back(p);
              break;
            }
        }
        FloorPreview preview;
        preview.part = part;
        preview.remaining = std::make_shared<const core::PointCloud>(std::move(r.remaining));
        preview.removed = std::make_shared<const core::PointCloud>(
            core::PointCloud::fromPoints(std::move(removed)));
        return preview;
      },
      [this, part](std::shared_ptr<const FloorPreview> preview) {
        if (part != m_part) {
          m_apply_floor_pending = false; // asked for another working cloud
          return;
        }
        m_floor_preview = preview;
        showFloorPreview();
        const std::size_t n = preview->removed->size();
        core::logger()->info("floor preview: {} of {} points would be removed", n,
                             part->validCount());
        statusBar()->showMessage(
            n == 0 ? tr("No plane large enough to remove")
                   : tr("%1 floor points shown in orange: Remove floor takes them away").arg(n),
            8000);
        emit floorPreviewReady(n);
        if (std::exchange(m_apply_floor_pending, false))
          removeFloorFromPart();
      },
      [this](const QString& e) {
        m_apply_floor_pending = false;
        showError(tr("Floor"), e);
      });
}

void MainWindow::removeFloorFromPart() {
  if (!m_part)
    return;
  if (!m_floor_preview || m_floor_preview->part != m_part) {
    // No preview for this working cloud yet: find the floor, then apply it.
    previewFloor();
    m_apply_floor_pending = true;
    return;
  }
  if (floorPreviewCount() == 0)
    return; // the preview found no floor; previewFloor said so
  const auto remaining = m_floor_preview->remaining;
  const std::size_t n = m_floor_preview->removed->size();
  replacePart(remaining, tr("Remove floor"));
  core::logger()->info("floor removal: {} points removed", n);
  statusBar()->showMessage(tr("Removed %1 floor points (Ctrl+Z undoes)").arg(n), 5000);
}

bool MainWindow::saveScan(const QString& path) {
  if (!m_scan) {
    showError(tr("Save scan"), tr("Open or capture a scan first."));
    return false;
  }
  try {
    core::saveCloud(path.toStdString(), *m_scan);
    core::logger()->info("saved scan to {}", path.toStdString());
    statusBar()->showMessage(tr("Saved %1").arg(path), 5000);
    return true;
  } catch (const std::exception& e) {
    showError(tr("Save scan"), QString::fromUtf8(e.what()));
    return false;
  }
}

void MainWindow::showCalibrationWizard() {
  for (auto* shown : findChildren<CalibrationWizard*>())
    if (shown->isVisible()) {
      shown->raise();
      shown->activateWindow();
      return;
    }
  auto* wizard = new CalibrationWizard(this);
  wizard->setAttribute(Qt::WA_DeleteOnClose);
  wizard->show();
}

} // namespace scanpick::ui
