// Recognize and live: background recognition with progress and cancel, the detections drawn in
// distinct colours over the grey scene, the results table, export, and capture → recognize loops.
#include "core/common/Log.h"
#include "core/output/DepthOverlay.h"
#include "core/output/ResultsJson.h"
#include "ui/FileDialogs.h"
#include "ui/MainWindow.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/DepthView.h"
#include "ui/panels/DevicePanel.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QAction>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QLabel>
#include <QStatusBar>
#include <QTimer>
#include <QUndoStack>
#include <vtkActor.h>
#include <vtkAssembly.h>
#include <vtkPropAssembly.h>
#include <vtkProperty.h>

#ifdef SCANPICK_UI_WITH_DEVICES
#include "devices/Camera.h"
#endif

namespace scanpick::ui {
namespace {

/// One live cycle: the captured scene and what was found in it.
struct LiveCycle {
  std::shared_ptr<const core::PointCloud> scene;
  core::RecognitionResult result;
  double cycle_ms = 0;
};

QString timingsText(const core::StageTimings& t) {
  return MainWindow::tr("preprocess %1 · clustering %2 · keypoints %3 · features %4 · matching %5 "
                        "· refine %6 · total %7 ms")
      .arg(t.preprocess_ms, 0, 'f', 0)
      .arg(t.clustering_ms, 0, 'f', 0)
      .arg(t.keypoints_ms, 0, 'f', 0)
      .arg(t.features_ms, 0, 'f', 0)
      .arg(t.matching_ms, 0, 'f', 0)
      .arg(t.refine_ms, 0, 'f', 0)
      .arg(t.total_ms, 0, 'f', 0);
}

} // namespace

void MainWindow::recognize() {
  if (!model())
    return showError(tr("Recognize"), tr("Teach a model or open one (.spmodel) first."));
  if (!m_scan)
    return showError(tr("Recognize"), tr("Open or capture a scene first."));
  const auto scene = m_scan;
  const auto recognizer = m_recognizer;
  const auto views = m_views;
  const QStringList paths = m_view_paths;
  const core::RecognitionParams params = m_params->params();
  // The scene's own sensor when its grid tells, otherwise the one the model was taught with.
  const core::SensorModel sensor = sensorOfGrid(*scene).value_or(model()->sensor);
  statusBar()->showMessage(tr("Recognizing…"));
  const quint64 gen = m_recognize_jobs->run<core::RecognitionResult>(
      [scene, recognizer, views, params, sensor](const core::ProgressFn& progress) {
        return core::recognizeViews(*recognizer, views, *scene, sensor, params, progress);
      },
      [this, views, paths](std::shared_ptr<const core::RecognitionResult> result) {
        setResult(std::move(result), views, paths);
        // The status bar's texts follow a language switch (m_texts).
        const int found = static_cast<int>(m_result->detections.size());
        m_texts.bind(m_status_counts, "text",
                     [found] { return tr("%n detection(s)", nullptr, found); });
        m_texts.bind(m_status_timings, "text",
                     [timings = m_result->timings] { return timingsText(timings); });
        core::logger()->info("recognized {} instance(s) in {:.0f} ms", m_result->detections.size(),
                             m_result->timings.total_ms);
        statusBar()->showMessage(
            tr("Found %n instance(s)", nullptr, static_cast<int>(m_result->detections.size())),
            8000);
      },
      [this](const QString& e) { showError(tr("Recognize"), e); });
  // One signal for every ending (done, error, cancelled), so callers and tests can wait on it.
  auto* connection = new QMetaObject::Connection;
  *connection = connect(m_recognize_jobs, &JobRunner::jobFinished, this,
                        [this, gen, connection](quint64 finished, bool accepted) {
                          if (finished != gen)
                            return;
                          disconnect(*connection);
                          delete connection;
                          emit recognitionFinished(accepted);
                        });
}

void MainWindow::cancelRecognition() {
  if (m_recognize_jobs->busy()) {
    m_recognize_jobs->cancel();
    core::logger()->info("recognition cancelled");
    statusBar()->showMessage(tr("Recognition cancelled"), 5000);
  }
  if (m_live)
    m_live_action->setChecked(false);
}

void MainWindow::setResult(std::shared_ptr<const core::RecognitionResult> result,
                           std::vector<std::shared_ptr<const core::TaughtModel>> views,
                           QStringList paths) {
  m_result = std::move(result);
  m_result_views = std::move(views);
  m_result_view_paths = std::move(paths);
  QStringList names;
  if (m_result_views.size() > 1)
    for (const QString& path : m_result_view_paths)
      names << (path.isEmpty() ? tr("taught") : QFileInfo(path).completeBaseName());
  m_results->setDetections(m_result->detections, names);
  if (!m_result->detections.empty() && !m_detections_shown) {
    // The whole-scene keypoints and features would cover the detections: off until asked for.
    m_detections_shown = true;
    m_show_keypoints_action->setChecked(false);
    m_show_features_action->setChecked(false);
  }
  showResult(-1);
  m_selected_detection = -1;
  updateDepthView();
  // Live keeps the camera where the operator put it after the first cycle.
  if (m_framed_scan != m_scan && !(m_live && m_live_cycles > 0)) {
    // The camera frames the bin: the scene without its floor (the parts and the bin's walls).
    m_framed_scan = m_scan;
    const auto& preprocessed = m_result->scene ? m_result->scene->preprocessed : nullptr;
    lookFromSensor(preprocessed && preprocessed->hasValidPoint() ? core::boundingBox(*preprocessed)
                                                                 : Eigen::AlignedBox3f());
  }
}

void MainWindow::showResult(int selected) {
  if (!m_result || !m_scan)
    return;
  clearLayers({QStringLiteral("scan"), QStringLiteral("part"), QStringLiteral("grips")});
  // The scene in greys by depth, so that the detections' colours stand out; drawn once per scan
  // (selecting a row redraws the detections only).
  if (m_scene_shown != m_scan) {
    setLayer(QStringLiteral("scene"),
             makeCloudActor(*m_scan, Qt::white, 1.5, ratio(), CloudShading::DepthGrey));
    m_scene_shown = m_scan;
  }
  auto assembly = vtkSmartPointer<vtkAssembly>::New();
  auto labels = vtkSmartPointer<vtkPropAssembly>::New();
  for (int i = 0; i < static_cast<int>(m_result->detections.size()); ++i) {
    const core::Detection& d = m_result->detections[i];
    const bool highlight = selected < 0 || selected == i;
    const QColor colour = detectionColour(i);
    // The view that found it, moved to where it was found.
    const core::TaughtModel* view =
        d.model_index >= 0 && d.model_index < static_cast<int>(m_result_views.size())
            ? m_result_views[std::size_t(d.model_index)].get()
            : nullptr;
    const double diameter_mm = view ? view->diameter_mm : 50.0;
    if (view) {
      // A few thousand points show the part's shape; a bin's worth of full views would cost
      // the GUI thread a frame of its own.
      auto cloud = makeCloudActor(view->cloud_mm, colour, highlight ? 3.0 : 2.0, ratio(),
                                  CloudShading::Flat, d.T_scene_model, 6000);
      cloud->GetProperty()->SetOpacity(highlight ? 1.0 : 0.25);
      assembly->AddPart(cloud);
    }
    // Grip points: long axes (z, blue, is the approach) and a white ball where the gripper goes.
    auto axes = makeGripAxesActor(d.grip_points_scene, std::max(8.0, diameter_mm * 0.3), ratio(),
                                  d.T_scene_model.linear());
    axes->GetProperty()->SetOpacity(highlight ? 1.0 : 0.3);
    assembly->AddPart(axes);
    auto markers = makeGripMarkersActor(d.grip_points_scene, Qt::white, 11.0, ratio());
    markers->GetProperty()->SetOpacity(highlight ? 1.0 : 0.3);
    assembly->AddPart(markers);
    // The results table's ID, in the detection's colour, over its centre (the model origin).
    labels->AddPart(makeLabelActor(QString::number(i + 1), d.T_scene_model.translation(), colour,
                                   highlight ? 16 : 12, ratio()));
  }
  setLayer(QStringLiteral("detections"), assembly);
  setLayer(QStringLiteral("labels"), labels);
  applyOverlayVisibility();
}

void MainWindow::onResultSelected(int row) {
  showResult(row);
  m_selected_detection = row;
  m_depth_view->setSelected(row);
  if (m_result && row >= 0 && row < static_cast<int>(m_result->detections.size()))
    statusBar()->showMessage(
        tr("Detection %1: score %2").arg(row + 1).arg(m_result->detections[row].score, 0, 'f', 3),
        5000);
}

void MainWindow::updateDepthView() {
  using State = DepthView::State;
  if (!m_scan) {
    m_depth_jobs->cancel();
    m_depth_scan.reset();
    m_depth_result.reset();
    return m_depth_view->setState(State::NoScan);
  }
  if (!m_scan->isOrganized()) {
    m_depth_jobs->cancel();
    m_depth_scan = m_scan;
    m_depth_result.reset();
    return m_depth_view->setState(State::Unorganized);
  }
  // Drawn when seen: a hidden view costs nothing, also in Live.
  if (!m_depth_view->isVisible() || (m_depth_scan == m_scan && m_depth_result == m_result))
    return;
  m_depth_scan = m_scan;
  m_depth_result = m_result;
  // An image of the same grid stays until the new one is ready (Live); otherwise say it comes.
  if (m_depth_view->image().size() != QSize(int(m_scan->width), int(m_scan->height)))
    m_depth_view->setState(State::Rendering);
  const auto scan = m_scan;
  const auto result = m_result;
  const auto views = m_result_views;
  std::vector<QColor> colours;
  std::vector<core::Rgb8> rgb;
  for (int i = 0; result && i < static_cast<int>(result->detections.size()); ++i) {
    const QColor c = detectionColour(i);
    colours.push_back(c);
    rgb.push_back({static_cast<std::uint8_t>(c.red()), static_cast<std::uint8_t>(c.green()),
                   static_cast<std::uint8_t>(c.blue())});
  }
  // A scan point is one of a detection's visible points as the result picture decides it.
  const double tolerance_mm = core::depthOverlayTolerance_mm(m_params->params());
  m_depth_jobs->run<core::DepthOverlay>(
      [scan, result, views, rgb, tolerance_mm](const core::ProgressFn& progress) {
        std::vector<const core::PointCloud*> clouds;
        for (const auto& view : views)
          clouds.push_back(view ? &view->cloud_mm : nullptr);
        static const std::vector<core::Detection> kNone;
        return core::renderDepthOverlay(*scan, clouds, result ? result->detections : kNone, rgb,
                                        tolerance_mm, progress);
      },
      [this, colours](std::shared_ptr<const core::DepthOverlay> overlay) {
        m_depth_view->setOverlay(*overlay, colours);
        m_depth_view->setSelected(m_selected_detection);
        emit depthViewUpdated();
      },
      [this](const QString& error) {
        core::logger()->warn("depth image: {}", error.toStdString());
        m_depth_scan.reset();
        m_depth_view->setState(DepthView::State::NoScan);
      });
}

bool MainWindow::exportResults(const QString& file) {
  if (!m_result || m_result_views.empty()) {
    showError(tr("Export results"), tr("Run a recognition first (F5)."));
    return false;
  }
  const QString path = withSuffix(file, QStringLiteral("json"));
  try {
    std::vector<core::ModelSource> sources;
    for (std::size_t v = 0; v < m_result_views.size(); ++v)
      sources.push_back({m_result_views[v].get(), m_result_view_paths[int(v)].toStdString()});
    core::saveResults(path.toStdString(), *m_result, sources, m_scan_path.toStdString());
    core::logger()->info("results written to {}", path.toStdString());
    statusBar()->showMessage(tr("Saved %1").arg(path), 5000);
    return true;
  } catch (const std::exception& e) {
    showError(tr("Export results"), QString::fromUtf8(e.what()));
    return false;
  }
}

void MainWindow::setLiveRunning(bool running) {
  if (m_live_action->isChecked() != running) {
    m_live_action->setChecked(running); // re-enters through toggled
    return;
  }
  if (!running) {
    m_live = false;
    return;
  }
#ifdef SCANPICK_UI_WITH_DEVICES
  if (!model() || !m_devices->camera()) {
    m_live_action->setChecked(false);
    showError(tr("Live"), tr("Live needs a model and an open camera (Capture panel)."));
    return;
  }
  m_live = true;
  m_live_cycles = 0;
  core::logger()->info("live recognition started");
  runLiveCycle();
#else
  m_live_action->setChecked(false);
  showError(tr("Live"), tr("This build has no camera support."));
#endif
}

void MainWindow::runLiveCycle() {
#ifdef SCANPICK_UI_WITH_DEVICES
  const auto camera = m_devices->camera();
  if (!m_live || !camera || !model()) {
    m_live_action->setChecked(false);
    return;
  }
  const auto recognizer = m_recognizer;
  const auto views = m_views;
  const QStringList paths = m_view_paths;
  const core::RecognitionParams params = m_params->params();
  const core::SensorModel model_sensor = model()->sensor;
  // Each cycle schedules the next one when it ends, so cycles never overlap.
  m_recognize_jobs->run<LiveCycle>(
      [camera, recognizer, views, params, model_sensor](const core::ProgressFn& progress) {
        QElapsedTimer timer;
        timer.start();
        LiveCycle c;
        c.scene = std::make_shared<const core::PointCloud>(
            camera->capture(std::chrono::seconds(5)).cloud);
        c.result =
            core::recognizeViews(*recognizer, views, *c.scene,
                                 sensorOfGrid(*c.scene).value_or(model_sensor), params, progress);
        c.cycle_ms = static_cast<double>(timer.nsecsElapsed()) / 1e6;
        return c;
      },
      [this, views, paths](std::shared_ptr<const LiveCycle> c) {
        m_scan = c->scene;
        setResult(std::shared_ptr<const core::RecognitionResult>(c, &c->result), views, paths);
        m_live_cycles++;
        const int found = static_cast<int>(m_result->detections.size());
        m_texts.bind(m_status_counts, "text",
                     [found] { return tr("%n detection(s)", nullptr, found); });
        m_texts.bind(m_status_timings, "text",
                     [ms = c->cycle_ms] { return tr("cycle %1 ms").arg(ms, 0, 'f', 0); });
        statusBar()->showMessage(tr("Live: %n instance(s), cycle %1 ms", nullptr,
                                    static_cast<int>(m_result->detections.size()))
                                     .arg(c->cycle_ms, 0, 'f', 0));
        emit liveCycleFinished(c->cycle_ms, static_cast<int>(m_result->detections.size()));
        QTimer::singleShot(0, this, &MainWindow::runLiveCycle);
      },
      [this](const QString& e) {
        m_live_action->setChecked(false);
        showError(tr("Live"), e);
      });
#endif
}

} // namespace scanpick::ui
