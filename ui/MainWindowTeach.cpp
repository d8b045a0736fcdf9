// Teach and tune: crop box, undoable crops and floor removal, grip points, the debounced
// keypoint/feature preview and teaching the model.
#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/grasp/GraspPoint.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"
#include "ui/MainWindow.h"
#include "ui/Settings.h"
#include "ui/TeachJob.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/CoveragePanel.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkInteractor.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QAction>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMouseEvent>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QShortcut>
#include <QStatusBar>
#include <QTimer>
#include <QToolButton>
#include <QUndoCommand>
#include <QUndoStack>
#include <QVBoxLayout>
#include <vtkActor.h>
#include <vtkBoxRepresentation.h>
#include <vtkBoxWidget2.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkMatrix4x4.h>
#include <vtkPointPicker.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkTransform.h>

namespace scanpick::ui {
namespace {

/// Replaces the working cloud; undo puts the previous one back.
class ReplacePartCommand : public QUndoCommand {
public:
  ReplacePartCommand(MainWindow* window, std::shared_ptr<const core::PointCloud> before,
                     std::shared_ptr<const core::PointCloud> after, const QString& text)
      : QUndoCommand(text), m_window(window), m_before(std::move(before)),
        m_after(std::move(after)) {}
  void undo() override { m_window->setPart(m_before); }
  void redo() override { m_window->setPart(m_after); }

private:
  MainWindow* m_window;
  std::shared_ptr<const core::PointCloud> m_before, m_after;
};

/// Replaces the grip points (added, moved, renamed or removed); undo puts the previous ones back.
class ReplaceGripsCommand : public QUndoCommand {
public:
  ReplaceGripsCommand(MainWindow* window, std::vector<core::GripPoint> before,
                      std::vector<core::GripPoint> after, int selected, const QString& text)
      : QUndoCommand(text), m_window(window), m_before(std::move(before)),
        m_after(std::move(after)), m_selected(selected) {}
  void undo() override { m_window->setGripPoints(m_before, m_selected); }
  void redo() override { m_window->setGripPoints(m_after, m_selected); }

private:
  MainWindow* m_window;
  std::vector<core::GripPoint> m_before, m_after;
  int m_selected; // the row the change is about, selected after it and after its undo
};

/// Forwards single clicks (press and release within a few pixels) on the viewport.
class ClickFilter : public QObject {
public:
  ClickFilter(QObject* parent, std::function<void(QPoint)> on_click)
      : QObject(parent), m_on_click(std::move(on_click)) {}
  bool eventFilter(QObject*, QEvent* event) override {
    if (event->type() == QEvent::MouseButtonPress) {
      m_press = static_cast<QMouseEvent*>(event)->position().toPoint();
    } else if (event->type() == QEvent::MouseButtonRelease) {
      const auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() == Qt::LeftButton &&
          (e->position().toPoint() - m_press).manhattanLength() < 4)
        m_on_click(e->position().toPoint());
    }
    return false;
  }

private:
  std::function<void(QPoint)> m_on_click;
  QPoint m_press;
};

double pointSize() {
  return QSettings().value(settings::kPointSize, 2.0).toDouble();
}

/// The approach a grip point placed at `position_mm` on `part` gets: against the surface normal
/// there; none (the model's +z at recognition) where the part has no surface to fit.
std::optional<Eigen::Vector3d> approachAt(const core::PointCloud& part,
                                          const Eigen::Vector3d& position_mm) {
  try {
    return core::grasp::surfaceApproach(part, position_mm);
  } catch (const core::Error& e) {
    core::logger()->warn("grip point: no approach from the surface: {}", e.what());
    return std::nullopt;
  }
}

} // namespace

void MainWindow::buildTeachDock() {
  auto* panel = new QWidget(this);
  auto* layout = new QVBoxLayout(panel);
  buildToolButtons(layout);
  // The part's name (views of one part share it) and, optionally, its pose in the scan (so that
  // views taught from scans of its other sides are joined).
  auto* part_form = new QFormLayout();
  const auto field = [&](const char* object_name, std::function<QString()> label,
                         std::function<QString()> placeholder, std::function<QString()> tip) {
    auto* edit = new QLineEdit(panel);
    edit->setObjectName(QString::fromLatin1(object_name));
    m_texts.bind(edit, "placeholderText", std::move(placeholder));
    m_texts.bind(edit, "toolTip", std::move(tip));
    auto* caption = new QLabel(panel);
    caption->setBuddy(edit);
    m_texts.bind(caption, "text", std::move(label));
    part_form->addRow(caption, edit);
    return edit;
  };
  m_part_name = field(
      "partNameEdit", [] { return tr("Part name:"); }, [] { return tr("the scan's file name"); },
      [] {
        return tr("Give every view of one part the same name: only views of one part are "
                  "searched together");
      });
  m_part_pose = field(
      "partPoseEdit", [] { return tr("Part pose:"); },
      [] { return tr("x, y, z (mm), qw, qx, qy, qz (optional)"); },
      [] {
        return tr("Where the part lies in this scan (from a fixture, or the robot that placed "
                  "it): views that know it are joined, each knowing the others");
      });
  layout->addLayout(part_form);
  // After a derived teach: what the parameters were derived from.
  m_teach_measures = new QLabel(panel);
  m_teach_measures->setObjectName(QStringLiteral("teachMeasures"));
  m_teach_measures->setWordWrap(true);
  m_teach_measures->setVisible(false);
  layout->addWidget(m_teach_measures);
  auto* grips_caption = new QLabel(panel);
  m_texts.bind(grips_caption, "text", [] { return tr("Grip points (double-click to rename):"); });
  layout->addWidget(grips_caption);
  m_grip_list = new QListWidget(panel);
  m_grip_list->setObjectName(QStringLiteral("gripList"));
  m_texts.bind(m_grip_list, "toolTip",
               [] { return tr("Del removes the selected grip point; Ctrl+Z undoes"); });
  layout->addWidget(m_grip_list, 1);
  auto* approach_form = new QFormLayout;
  m_grip_approach = new QLineEdit(panel);
  m_grip_approach->setObjectName(QStringLiteral("gripApproach"));
  m_texts.bind(m_grip_approach, "toolTip", [] {
    return tr(
        "Direction the gripper moves in to reach the selected grip point (scan frame: x, y, "
        "z, any length; Enter applies); placing or moving a point sets it against the surface "
        "normal");
  });
  auto* approach_label = new QLabel(panel);
  m_texts.bind(approach_label, "text", [] { return tr("Approach:"); });
  approach_form->addRow(approach_label, m_grip_approach);
  layout->addLayout(approach_form);
  connect(m_grip_list, &QListWidget::currentRowChanged, this, [this] { showGripApproach(); });
  connect(m_grip_approach, &QLineEdit::returnPressed, this, [this] {
    const QStringList parts = m_grip_approach->text().split(QLatin1Char(','));
    Eigen::Vector3d v;
    bool ok = parts.size() == 3;
    for (int k = 0; ok && k < 3; ++k)
      v[k] = parts[k].trimmed().toDouble(&ok);
    if (!ok || !setGripApproach(m_grip_list->currentRow(), v)) {
      statusBar()->showMessage(
          tr("The approach is three numbers x, y, z, not all zero (e.g. 0, 0, 1)"), 5000);
      showGripApproach();
    }
  });
  auto* grip_buttons = new QHBoxLayout;
  m_grip_move_action = new QAction(this);
  m_texts.bind(m_grip_move_action, "text", [] { return tr("Move grip point"); });
  m_grip_move_action->setObjectName(QStringLiteral("moveGripAction"));
  m_grip_move_action->setCheckable(true);
  m_texts.bind(m_grip_move_action, "toolTip", [] {
    return tr("Select a grip point in the list, then click on the part where it should be");
  });
  connect(m_grip_move_action, &QAction::toggled, this, [this](bool on) {
    if (on && m_grip_list->currentRow() < 0) {
      statusBar()->showMessage(tr("Select the grip point to move in the list first"), 5000);
      m_grip_move_action->setChecked(false);
      return;
    }
    if (on) {
      m_grip_action->setChecked(false);
      statusBar()->showMessage(tr("Click on the part where the grip point should be"));
    }
  });
  auto* move = new QToolButton(panel);
  move->setObjectName(QStringLiteral("moveGripButton"));
  move->setDefaultAction(m_grip_move_action);
  move->setToolButtonStyle(Qt::ToolButtonTextOnly);
  grip_buttons->addWidget(move);
  auto* remove = new QPushButton(panel);
  m_texts.bind(remove, "text", [] { return tr("Remove grip point"); });
  remove->setObjectName(QStringLiteral("removeGripButton"));
  grip_buttons->addWidget(remove);
  layout->addLayout(grip_buttons);
  const auto remove_selected = [this] { removeGripPoint(m_grip_list->currentRow()); };
  connect(remove, &QPushButton::clicked, this, remove_selected);
  auto* del =
      new QShortcut(QKeySequence::Delete, m_grip_list, nullptr, nullptr, Qt::WidgetShortcut);
  connect(del, &QShortcut::activated, this, remove_selected);
  connect(m_grip_list, &QListWidget::itemChanged, this,
          [this](QListWidgetItem* item) { renameGripPoint(m_grip_list->row(item), item->text()); });
  auto* dock = new QDockWidget(this);
  m_texts.bind(dock, "windowTitle", [] { return tr("Teach"); });
  dock->setObjectName(QStringLiteral("TeachDock"));
  // Scrolls rather than making the window taller than a 700-pixel screen.
  auto* scroll = new QScrollArea(dock);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setWidget(panel);
  dock->setWidget(scroll);
  addDockWidget(Qt::LeftDockWidgetArea, dock);
  // Teach and Capture share the left side as tabs, Teach in front.
  if (auto* capture = findChild<QDockWidget*>(QStringLiteral("CaptureDock"))) {
    tabifyDockWidget(capture, dock);
    dock->raise();
  }
  m_view->installEventFilter(new ClickFilter(this, [this](QPoint p) {
    if (m_grip_action->isChecked() || m_grip_move_action->isChecked())
      onViewportClick(p.x(), p.y());
  }));
}

void MainWindow::buildCoverageDock() {
  // Which sides the views cover tells which to teach next; a tab beside the depth image.
  m_coverage = new CoveragePanel(m_pool.get(), this);
  auto* dock = new QDockWidget(this);
  dock->setObjectName(QStringLiteral("CoverageDock"));
  m_texts.bind(dock, "windowTitle", [] { return tr("View coverage"); });
  dock->setWidget(m_coverage);
  addDockWidget(Qt::LeftDockWidgetArea, dock);
  if (auto* depth = findChild<QDockWidget*>(QStringLiteral("DepthDock")))
    tabifyDockWidget(depth, dock);
  // The Teach panel stays in front.
  if (auto* teach = findChild<QDockWidget*>(QStringLiteral("TeachDock")))
    teach->raise();
}

void MainWindow::setPreviewDelay(int ms) {
  m_preview_timer->setInterval(ms);
}

void MainWindow::setPart(std::shared_ptr<const core::PointCloud> part_mm) {
  m_part = std::move(part_mm);
  ++m_part_version;
  showPart();
  showFloorPreview(); // hides a preview made for another working cloud
  schedulePreview(core::Stage::Keypoints);
  emit partChanged();
}

void MainWindow::showPart() {
  // The working cloud replaces the recognition's grey scene.
  setLayer(QStringLiteral("scene"), nullptr);
  m_scene_shown.reset();
  if (!m_part) {
    clearLayers({QStringLiteral("part"), QStringLiteral("scan")});
    return;
  }
  setLayer(QStringLiteral("part"),
           makeCloudActor(*m_part, Qt::white, pointSize(), ratio(), CloudShading::Depth));
  // The rest of the scan stays visible, dim, so the operator sees what the crop left out.
  if (m_scan && m_part != m_scan)
    setLayer(QStringLiteral("scan"), makeCloudActor(*m_scan, QColor(90, 90, 100), 1.0, ratio()));
  else
    setLayer(QStringLiteral("scan"), nullptr);
}

void MainWindow::setCropBoxVisible(bool visible) {
  if (!m_box_widget) {
    m_box_widget = vtkSmartPointer<vtkBoxWidget2>::New();
    vtkNew<vtkBoxRepresentation> rep;
    rep->SetPlaceFactor(1.0);
    m_box_widget->SetRepresentation(rep);
    m_box_widget->SetInteractor(m_view->interactor());
  }
  if (visible && m_lasso_action->isChecked())
    m_lasso_action->setChecked(false);
  if (visible && m_part) {
    const Eigen::AlignedBox3f box = core::boundingBox(*m_part);
    core::OrientedBox oriented;
    oriented.T_scan_box.translation() = box.center();
    oriented.half_extents_mm = box.sizes() / 2 * 1.02f + Eigen::Vector3f::Constant(0.5f);
    setCropBox(oriented);
  }
  m_box_widget->SetEnabled(visible && m_part ? 1 : 0);
  if (m_crop_action->isChecked() != (visible && m_part))
    m_crop_action->setChecked(visible && m_part);
  m_view->requestRender();
}

void MainWindow::setCropBox(const core::OrientedBox& box) {
  if (!m_box_widget)
    setCropBoxVisible(false);
  auto* rep = vtkBoxRepresentation::SafeDownCast(m_box_widget->GetRepresentation());
  // Placed as the unit cube, then moved: the transform fully describes the box.
  double unit[6] = {-0.5, 0.5, -0.5, 0.5, -0.5, 0.5};
  rep->PlaceWidget(unit);
  vtkNew<vtkTransform> t;
  const Eigen::Matrix4d m = box.T_scan_box.matrix().cast<double>();
  vtkNew<vtkMatrix4x4> matrix;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      matrix->SetElement(r, c, m(r, c));
  t->SetMatrix(matrix);
  t->Scale(2.0 * box.half_extents_mm.x(), 2.0 * box.half_extents_mm.y(),
           2.0 * box.half_extents_mm.z());
  rep->SetTransform(t);
  m_view->requestRender();
}

core::OrientedBox MainWindow::cropBox() const {
  core::OrientedBox box;
  if (!m_box_widget)
    return box;
  auto* rep = vtkBoxRepresentation::SafeDownCast(m_box_widget->GetRepresentation());
  vtkNew<vtkPolyData> poly;
  rep->GetPolyData(poly);
  // Corners 0..7 of vtkBoxRepresentation: 0 (min), 1 (+x), 3 (+y), 4 (+z).
  const auto corner = [&](int i) {
    double p[3];
    poly->GetPoints()->GetPoint(i, p);
    return Eigen::Vector3f(static_cast<float>(p[0]), static_cast<float>(p[1]),
                           static_cast<float>(p[2]));
  };
  const Eigen::Vector3f o = corner(0), ex = corner(1) - o, ey = corner(3) - o, ez = corner(4) - o;
  Eigen::Matrix3f R;
  R.col(0) = ex.normalized();
  R.col(1) = ey.normalized();
  R.col(2) = ez.normalized();
  box.T_scan_box.linear() = R;
  box.T_scan_box.translation() = o + (ex + ey + ez) / 2;
  box.half_extents_mm = Eigen::Vector3f(ex.norm(), ey.norm(), ez.norm()) / 2;
  return box;
}

bool MainWindow::applyCrop() {
  if (!m_part || !m_box_widget || !m_box_widget->GetEnabled()) {
    statusBar()->showMessage(tr("Show the crop box first (Ctrl+B)"), 5000);
    return false;
  }
  auto cropped =
      std::make_shared<const core::PointCloud>(core::cropToOrientedBox(*m_part, cropBox()));
  if (!cropped->hasValidPoint()) {
    showError(tr("Crop"), tr("The crop box holds no point: move or enlarge it."));
    return false;
  }
  core::logger()->info("crop: {} of {} points kept", cropped->validCount(), m_part->validCount());
  replacePart(cropped, tr("Crop"));
  setCropBoxVisible(false);
  return true;
}

void MainWindow::replacePart(std::shared_ptr<const core::PointCloud> after, const QString& text) {
  m_undo->push(new ReplacePartCommand(this, m_part, std::move(after), text));
}

void MainWindow::onViewportClick(int x, int y) {
  const auto it = m_layers.find(QStringLiteral("part"));
  if (it == m_layers.end())
    return;
  vtkNew<vtkPointPicker> picker;
  picker->SetTolerance(0.005);
  picker->PickFromListOn();
  picker->AddPickList(it->second);
  const double r = ratio();
  const int* size = m_view->renderWindow()->GetSize();
  if (!picker->Pick(x * r, size[1] - y * r - 1, 0, m_view->renderer()) || picker->GetPointId() < 0)
    return;
  double p[3];
  picker->GetPickPosition(p);
  if (m_grip_move_action->isChecked()) {
    m_grip_move_action->setChecked(false);
    moveGripPoint(m_grip_list->currentRow(), Eigen::Vector3d(p[0], p[1], p[2]));
  } else {
    addGripPoint(Eigen::Vector3d(p[0], p[1], p[2]));
  }
}

void MainWindow::addGripPoint(const Eigen::Vector3d& position_mm) {
  core::GripPoint grip;
  grip.name = tr("grip %1").arg(m_grips.size() + 1).toStdString();
  grip.position_mm = position_mm;
  grip.approach = approachAt(*m_part, position_mm);
  core::logger()->info("grip point '{}' at ({:.1f}, {:.1f}, {:.1f}) mm", grip.name, position_mm.x(),
                       position_mm.y(), position_mm.z());
  auto after = m_grips;
  after.push_back(grip);
  m_undo->push(new ReplaceGripsCommand(this, m_grips, std::move(after),
                                       static_cast<int>(m_grips.size()), tr("Add grip point")));
}

void MainWindow::moveGripPoint(int index, const Eigen::Vector3d& position_mm) {
  if (index < 0 || index >= static_cast<int>(m_grips.size()))
    return;
  auto after = m_grips;
  after[std::size_t(index)].position_mm = position_mm;
  after[std::size_t(index)].approach = approachAt(*m_part, position_mm);
  after[std::size_t(index)].closing_axis.reset();
  core::logger()->info("grip point '{}' moved to ({:.1f}, {:.1f}, {:.1f}) mm",
                       after[std::size_t(index)].name, position_mm.x(), position_mm.y(),
                       position_mm.z());
  m_undo->push(
      new ReplaceGripsCommand(this, m_grips, std::move(after), index, tr("Move grip point")));
}

bool MainWindow::setGripApproach(int index, const Eigen::Vector3d& approach) {
  if (index < 0 || index >= static_cast<int>(m_grips.size()) || !approach.allFinite() ||
      approach.norm() < 1e-9)
    return false;
  auto after = m_grips;
  core::GripPoint& grip = after[std::size_t(index)];
  grip.approach = approach.normalized();
  if (grip.closing_axis && std::abs(grip.closing_axis->dot(*grip.approach)) > 0.99)
    grip.closing_axis.reset();
  if (after == m_grips)
    return true;
  m_undo->push(
      new ReplaceGripsCommand(this, m_grips, std::move(after), index, tr("Set grip approach")));
  return true;
}

void MainWindow::showGripApproach() {
  const int row = m_grip_list->currentRow();
  const bool selected = row >= 0 && row < static_cast<int>(m_grips.size());
  m_grip_approach->setEnabled(selected);
  const auto& approach = selected ? m_grips[std::size_t(row)].approach : std::nullopt;
  m_grip_approach->setText(approach ? QStringLiteral("%1, %2, %3")
                                          .arg(approach->x(), 0, 'f', 3)
                                          .arg(approach->y(), 0, 'f', 3)
                                          .arg(approach->z(), 0, 'f', 3)
                                    : QString());
}

void MainWindow::removeGripPoint(int index) {
  if (index < 0 || index >= static_cast<int>(m_grips.size()))
    return;
  auto after = m_grips;
  after.erase(after.begin() + index);
  m_undo->push(
      new ReplaceGripsCommand(this, m_grips, std::move(after), index, tr("Remove grip point")));
}

void MainWindow::renameGripPoint(int index, const QString& name) {
  if (index < 0 || index >= static_cast<int>(m_grips.size()) ||
      name.toStdString() == m_grips[std::size_t(index)].name)
    return;
  auto after = m_grips;
  after[std::size_t(index)].name = name.toStdString();
  m_undo->push(
      new ReplaceGripsCommand(this, m_grips, std::move(after), index, tr("Rename grip point")));
}

void MainWindow::setGripPoints(std::vector<core::GripPoint> grips, int selected) {
  m_grips = std::move(grips);
  refreshGripList();
  m_grip_list->setCurrentRow(std::min(selected, static_cast<int>(m_grips.size()) - 1));
  showGripApproach();
  showGrips();
}

void MainWindow::refreshGripList() {
  const QSignalBlocker block(m_grip_list);
  m_grip_list->clear();
  for (const core::GripPoint& g : m_grips) {
    auto* item = new QListWidgetItem(QString::fromStdString(g.name), m_grip_list);
    item->setFlags(item->flags() | Qt::ItemIsEditable);
    item->setToolTip(QStringLiteral("(%1, %2, %3) mm")
                         .arg(g.position_mm.x(), 0, 'f', 1)
                         .arg(g.position_mm.y(), 0, 'f', 1)
                         .arg(g.position_mm.z(), 0, 'f', 1));
  }
}

void MainWindow::showGrips() {
  const double length =
      m_part ? std::max(5.0, core::boundingBox(*m_part).sizes().norm() * 0.06) : 10.0;
  setLayer(QStringLiteral("grips"),
           m_grips.empty() ? nullptr : makeGripAxesActor(m_grips, length, ratio()));
}

void MainWindow::schedulePreview(core::Stage first_stage) {
  // Matching and refinement do not change the keypoint/feature preview.
  if (first_stage > core::Stage::Features || !m_part)
    return;
  m_preview_timer->start();
}

void MainWindow::runPreview() {
  if (!m_part)
    return;
  const auto part = m_part;
  const quint64 version = m_part_version;
  const core::RecognitionParams params = m_params->params();
  // Keypoints are reused when only feature parameters changed.
  std::shared_ptr<const core::Keypoints> cached;
  if (m_preview && m_preview->cloud_version == version &&
      m_preview->keypoint_params == params.keypoints)
    cached = m_preview->keypoints;
  m_preview_jobs->run<PreviewResult>(
      [part, version, params, cached](const core::ProgressFn& progress) {
        PreviewResult r;
        r.cloud_version = version;
        r.keypoint_params = params.keypoints;
        QElapsedTimer timer;
        timer.start();
        if (cached) {
          r.keypoints = cached;
        } else {
          const core::PointCloud cloud =
              params.downsample.voxel_mm > 0
                  ? core::voxelDownsample(*part, params.downsample.voxel_mm)
                  : *part;
          r.keypoints = std::make_shared<const core::Keypoints>(
              core::extractKeypoints(cloud, params.keypoints, core::subProgress(progress, 0, 0.6)));
          r.keypoints_ms = static_cast<double>(timer.nsecsElapsed()) / 1e6;
        }
        timer.restart();
        r.features = core::extractFeatures(r.keypoints->points_mm, params.features, params.seed,
                                           core::subProgress(progress, 0.6, 1.0));
        r.features_ms = static_cast<double>(timer.nsecsElapsed()) / 1e6;
        return r;
      },
      [this](std::shared_ptr<const PreviewResult> r) {
        m_preview = std::move(r);
        showPreview();
        emit previewUpdated();
      },
      [this](const QString& error) {
        // Tuning often passes through invalid combinations: say so without a dialog.
        core::logger()->warn("preview: {}", error.toStdString());
        statusBar()->showMessage(tr("Preview: %1").arg(error), 8000);
        clearLayers({QStringLiteral("keypoints"), QStringLiteral("features")});
      });
}

void MainWindow::showPreview() {
  if (!m_preview)
    return;
  int lines = 0, circles = 0;
  for (const core::Feature& f : m_preview->features.features)
    (f.type == core::FeatureType::Line ? lines : circles)++;
  setLayer(QStringLiteral("keypoints"),
           makePointsActor(m_preview->keypoints->points_mm, QColor(255, 220, 0), pointSize() + 2,
                           ratio()));
  setLayer(QStringLiteral("features"),
           makeFeaturesActor(m_preview->features.features, QColor(0, 230, 255),
                             QColor(255, 60, 220), 3.0, ratio()));
  // Once the scan has a recognition, the status bar keeps its stage timings.
  if (m_result)
    return;
  // The status bar's texts follow a language switch (m_texts).
  m_texts.bind(
      m_status_counts, "text",
      [keypoints = m_preview->keypoints->points_mm.size(), lines, circles] {
        return tr("keypoints %1 · lines %2 · circles %3").arg(keypoints).arg(lines).arg(circles);
      });
  m_texts.bind(m_status_timings, "text",
               [keypoints_ms = m_preview->keypoints_ms, features_ms = m_preview->features_ms] {
                 return keypoints_ms > 0
                            ? tr("keypoints %1 ms · features %2 ms")
                                  .arg(keypoints_ms, 0, 'f', 0)
                                  .arg(features_ms, 0, 'f', 0)
                            : tr("keypoints cached · features %1 ms").arg(features_ms, 0, 'f', 0);
               });
}

void MainWindow::teach() {
  if (!m_part) {
    showError(tr("Teach"), tr("Open a scan and crop the part first."));
    return;
  }
  core::TeachOptions options;
  const QString name = m_part_name->text().trimmed();
  options.name = !name.isEmpty()         ? name.toStdString()
                 : m_scan_path.isEmpty() ? "part"
                                         : QFileInfo(m_scan_path).completeBaseName().toStdString();
  if (const QString pose = m_part_pose->text().trimmed(); !pose.isEmpty()) {
    try {
      options.T_scan_part = core::partPose(pose.toStdString());
    } catch (const core::Error& e) {
      showError(tr("Teach"), QString::fromUtf8(e.what()));
      return;
    }
  }
  // The working cloud is already cropped; its own bounds (padded) keep every point.
  Eigen::AlignedBox3f bounds = core::boundingBox(*m_part);
  bounds.min() -= Eigen::Vector3f::Constant(1.0f);
  bounds.max() += Eigen::Vector3f::Constant(1.0f);
  options.crop_box_mm = bounds;
  options.grips_scan = m_grips;
  options.sensor = currentSensor();
  const auto part = m_part;
  const core::RecognitionParams params = m_params->params();
  const std::set<std::string> hand_edits = m_params->handEdits();
  const bool derive = m_params->derivesAtTeach();
  statusBar()->showMessage(derive ? tr("Deriving the parameters from the part and teaching…")
                                  : tr("Teaching…"));
  m_jobs->run<TeachOutcome>(
      [part, options, params, hand_edits, derive](const core::ProgressFn& progress) {
        return teachPart(*part, options, params, hand_edits, derive, progress);
      },
      [this](std::shared_ptr<const TeachOutcome> outcome) {
        const auto& model = outcome->model;
        // The panel takes the taught values (and their reasons): recognition uses them.
        setViews({model}, {QString()}, true);
        core::logger()->info("taught '{}': {} points, {} keypoints, {} features, {} grip points",
                             model->name, model->cloud_mm.size(), model->keypoints_mm.size(),
                             model->features.size(), model->grip_points.size());
        // The taught features, drawn where they lie in the teach scan.
        setLayer(QStringLiteral("features"),
                 makeFeaturesActor(model->features, QColor(0, 230, 255), QColor(255, 60, 220), 3.0,
                                   ratio(), model->T_teach_model));
        showTeachMeasures(outcome->derived ? &*outcome->derived : nullptr, model->features.size());
        // The preview's keypoints were found with the values before the derivation.
        if (outcome->derived)
          schedulePreview(core::Stage::Keypoints);
        emit modelTaught();
      },
      [this](const QString& e) { showError(tr("Teach"), e); });
}

void MainWindow::showTeachMeasures(const core::AutoParams* derived, std::size_t features) {
  m_teach_measures->setVisible(derived != nullptr);
  if (!derived) {
    statusBar()->showMessage(tr("Model taught: %1 features. Save it with Ctrl+S.").arg(features),
                             8000);
    return;
  }
  m_texts.bind(
      m_teach_measures, "text",
      [spacing = derived->scan.spacing_mm, noise = derived->scan.noise_mm,
       diameter = derived->part.diameter_mm] {
        const auto mm = [](double v) { return QString::number(v, 'f', v < 10 ? 2 : 1); };
        const QString measures = tr("point spacing %1 mm, depth noise %2 mm, part diameter %3 mm")
                                     .arg(mm(spacing), mm(noise), mm(diameter));
        return tr("Parameters derived from the part: %1 (the values marked “derived” in the "
                  "Parameters panel).")
            .arg(measures);
      });
  core::logger()->info("parameters derived from the part: point spacing {:.3f} mm, depth noise "
                       "{:.3f} mm, part diameter {:.1f} mm, {} values",
                       derived->scan.spacing_mm, derived->scan.noise_mm, derived->part.diameter_mm,
                       derived->values.size());
  statusBar()->showMessage(
      tr("Model taught: %1 features, with parameters derived from the part. Save it with Ctrl+S.")
          .arg(features),
      8000);
}

} // namespace scanpick::ui
