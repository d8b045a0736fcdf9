#include "ui/MainWindow.h"

#include "core/cloud/CloudIo.h"
#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/model/ModelFile.h"
#include "ui/FileDialogs.h"
#include "ui/Language.h"
#include "ui/Settings.h"
#include "ui/jobs/JobRunner.h"
#include "ui/panels/CoveragePanel.h"
#include "ui/panels/DepthView.h"
#include "ui/panels/DevicePanel.h"
#include "ui/panels/LogDock.h"
#include "ui/panels/ParameterPanel.h"
#include "ui/panels/ResultsTable.h"
#include "ui/viewport/Presenters.h"
#include "ui/viewport/QtVtkViewport.h"

#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDesktopServices>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QHeaderView>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QUndoStack>
#include <QUrl>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <vtkBoxWidget2.h>
#include <vtkCamera.h>
#include <vtkProp.h>
#include <vtkRenderer.h>
#include <vtkVersion.h>

namespace scanpick::ui {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setObjectName(QStringLiteral("MainWindow"));
  m_texts.bind(this, "windowTitle", [] { return tr("scanpick"); });
  setAcceptDrops(true);
  setDockNestingEnabled(true);
  m_view = new QtVtkViewport(this);
  setCentralWidget(m_view);
  m_pool = std::make_unique<JobPool>();
  m_jobs = new JobRunner(m_pool.get(), this);
  m_preview_jobs = new JobRunner(m_pool.get(), this);
  m_recognize_jobs = new JobRunner(m_pool.get(), this);
  m_prepare_jobs = new JobRunner(m_pool.get(), this);
  m_depth_jobs = new JobRunner(m_pool.get(), this);
  m_undo = new QUndoStack(this);
  m_recognizer = std::make_shared<core::Recognizer>();
  m_preview_timer = new QTimer(this);
  m_preview_timer->setSingleShot(true);
  m_preview_timer->setInterval(150);
  connect(m_preview_timer, &QTimer::timeout, this, &MainWindow::runPreview);

  m_status_counts = new QLabel(this);
  m_status_timings = new QLabel(this);
  m_status_counts->setObjectName(QStringLiteral("statusCounts"));
  m_status_timings->setObjectName(QStringLiteral("statusTimings"));
  m_progress = new QProgressBar(this);
  m_progress->setRange(0, 1000);
  m_progress->setMaximumWidth(180);
  m_progress->setVisible(false);
  m_cancel = new QPushButton(this);
  m_texts.bind(m_cancel, "text", [] { return tr("Cancel"); });
  m_cancel->setObjectName(QStringLiteral("cancelButton"));
  m_cancel->setVisible(false);
  statusBar()->addPermanentWidget(m_status_counts);
  statusBar()->addPermanentWidget(m_status_timings);
  statusBar()->addPermanentWidget(m_progress);
  statusBar()->addPermanentWidget(m_cancel);
  m_progress->setObjectName(QStringLiteral("jobProgress"));
  // One progress bar for the long jobs (loading, teaching, recognizing); previews stay quiet. It
  // starts as a moving busy indicator and shows the percentage the job reports (loading reports
  // the bytes read and the decoding); it is hidden when the job ends.
  for (JobRunner* runner : {m_jobs, m_recognize_jobs}) {
    connect(runner, &JobRunner::progress, this, [this](double f) {
      if (f <= 0)
        return;
      m_progress->setRange(0, 1000);
      m_progress->setValue(static_cast<int>(std::min(f, 1.0) * 1000));
    });
    connect(runner, &JobRunner::busyChanged, this, [this] {
      const bool busy = m_jobs->busy() || m_recognize_jobs->busy();
      m_progress->setVisible(busy);
      m_cancel->setVisible(busy);
      if (busy && m_progress->value() <= 0)
        m_progress->setRange(0, 0);
      if (!busy)
        m_progress->reset();
    });
  }
  connect(m_cancel, &QPushButton::clicked, this, [this] {
    m_jobs->cancel();
    cancelRecognition();
    statusBar()->showMessage(tr("Cancelled"), 3000);
  });

  buildDocks();
  buildActions();
  buildTeachDock();
  buildCoverageDock();
  addPanelsToViewMenu();
  restoreSettings();
  m_welcome_shown = welcomeText();
  statusBar()->showMessage(m_welcome_shown);
}

QString MainWindow::welcomeText() {
  return tr("Open a scan (Ctrl+O) or drop a PCD/PLY file here");
}

void MainWindow::changeEvent(QEvent* event) {
  if (event->type() == QEvent::LanguageChange)
    retranslateUi();
  QMainWindow::changeEvent(event);
}

void MainWindow::retranslateUi() {
  // The welcome message stays until something else is shown; it follows the language too.
  const bool welcome = statusBar()->currentMessage() == m_welcome_shown;
  m_texts.apply();
  m_welcome_shown = welcomeText();
  if (welcome)
    statusBar()->showMessage(m_welcome_shown);
}

MainWindow::~MainWindow() {
  m_live = false;
  m_preview_jobs->cancel();
  m_recognize_jobs->cancel();
  m_prepare_jobs->cancel();
  m_depth_jobs->cancel();
  m_coverage->cancel();
  m_jobs->cancel();
  if (m_box_widget)
    m_box_widget->Off();
  // The undo stack, a child, is destroyed after this destructor has run, and clearing it emits
  // signals whose handlers read this window's members.
  m_undo->disconnect();
}

double MainWindow::ratio() const {
  return m_view->devicePixelRatioF();
}

void MainWindow::buildDocks() {
  m_params = new ParameterPanel(this);
  auto* params_dock = new QDockWidget(this);
  m_texts.bind(params_dock, "windowTitle", [] { return tr("Parameters"); });
  params_dock->setObjectName(QStringLiteral("ParametersDock"));
  params_dock->setWidget(m_params);
  addDockWidget(Qt::RightDockWidgetArea, params_dock);
  connect(m_params, &ParameterPanel::paramsChanged, this,
          [this](const core::RecognitionParams&, core::Stage stage) { schedulePreview(stage); });
  connect(m_params, &ParameterPanel::presetLoaded, this,
          [](const QString& path) { QSettings().setValue(settings::kLastPreset, path); });

  m_results = new ResultsTable(this);
  auto* results_dock = new QDockWidget(this);
  m_texts.bind(results_dock, "windowTitle", [] { return tr("Results"); });
  results_dock->setObjectName(QStringLiteral("ResultsDock"));
  results_dock->setWidget(m_results);
  addDockWidget(Qt::BottomDockWidgetArea, results_dock);
  connect(m_results, &ResultsTable::detectionSelected, this, &MainWindow::onResultSelected);

  m_devices = new DevicePanel(this);
  auto* devices_dock = new QDockWidget(this);
  m_texts.bind(devices_dock, "windowTitle", [] { return tr("Capture"); });
  devices_dock->setObjectName(QStringLiteral("CaptureDock"));
  auto* devices_scroll = new QScrollArea(devices_dock);
  devices_scroll->setWidgetResizable(true);
  devices_scroll->setFrameShape(QFrame::NoFrame);
  devices_scroll->setWidget(m_devices);
  devices_dock->setWidget(devices_scroll);
  addDockWidget(Qt::LeftDockWidgetArea, devices_dock);
  connect(m_devices, &DevicePanel::frameCaptured, this,
          [this](std::shared_ptr<const core::PointCloud> cloud, const QString& name) {
            if (!m_live)
              setScan(std::move(cloud), name);
          });
  connect(m_devices, &DevicePanel::deviceError, this,
          [this](const QString& message) { showError(tr("Camera"), message); });

  // The depth image shares the left side with Capture and Teach, as a tab.
  m_depth_view = new DepthView(this);
  auto* depth_dock = new QDockWidget(this);
  depth_dock->setObjectName(QStringLiteral("DepthDock"));
  m_texts.bind(depth_dock, "windowTitle", [] { return tr("Depth image"); });
  depth_dock->setWidget(m_depth_view);
  addDockWidget(Qt::LeftDockWidgetArea, depth_dock);
  tabifyDockWidget(devices_dock, depth_dock);
  connect(depth_dock, &QDockWidget::visibilityChanged, this, [this](bool visible) {
    if (visible)
      updateDepthView();
  });

  m_log = new LogDock(this);
  addDockWidget(Qt::BottomDockWidgetArea, m_log);
  tabifyDockWidget(results_dock, m_log);
  results_dock->raise();
  // Never smaller than the header, five rows (a typical bin's detections) and a scroll bar.
  m_results->setMinimumHeight(m_results->horizontalHeader()->sizeHint().height() +
                              5 * m_results->verticalHeader()->defaultSectionSize() +
                              m_results->horizontalScrollBar()->sizeHint().height() +
                              2 * m_results->frameWidth());
}

void MainWindow::buildActions() {
  // Every text is bound (m_texts), so that it follows a language switch (retranslateUi).
  const auto menu = [this](std::function<QString()> title) {
    QMenu* m = menuBar()->addMenu(QString());
    m_texts.bind(m->menuAction(), "text", std::move(title));
    return m;
  };
  const auto named = [this](QAction* a, std::function<QString()> text) {
    m_texts.bind(a, "text", std::move(text));
    return a;
  };
  // An entry of `m` named `text()` that calls `slot` of `receiver` (a member function, or a
  // lambda with `receiver` as context).
  const auto add = [named](QMenu* m, std::function<QString()> text, auto* receiver, auto slot) {
    return named(m->addAction(QString(), receiver, slot), std::move(text));
  };
  QMenu* file = menu([] { return tr("&File"); });
  QAction* open = add(
      file, [] { return tr("&Open scan or model…"); }, this,
      [this] {
        // Several models chosen together are the views of one part.
        const QStringList paths = QFileDialog::getOpenFileNames(
            this, tr("Open"), QSettings().value(settings::kLastDirectory).toString(),
            tr("Scans and models (*.pcd *.ply *.spmodel);;All files (*)"));
        openFiles(paths);
      });
  open->setShortcut(QKeySequence::Open);
  QAction* add_view = add(
      file, [] { return tr("&Add model view…"); }, this,
      [this] {
        const QStringList paths = QFileDialog::getOpenFileNames(
            this, tr("Add model view"), QSettings().value(settings::kLastDirectory).toString(),
            tr("Models (*.spmodel)"));
        if (!paths.isEmpty())
          addModelViews(paths);
      });
  m_texts.bind(add_view, "toolTip", [] {
    return tr("Add views of the same part, taught from scans of its other sides: "
              "Recognize searches them all");
  });
  m_recent_menu = file->addMenu(QString());
  m_texts.bind(m_recent_menu->menuAction(), "text", [] { return tr("Open &recent"); });
  rebuildRecentMenu();
  file->addSeparator();
  QAction* save_model = add(
      file, [] { return tr("&Save model…"); }, this,
      [this] {
        if (!model())
          return showError(tr("Save model"), tr("Teach or open a model first."));
        const QString path = askSaveFileName(this, tr("Save model"), m_view_paths.value(0),
                                             tr("Models (*.spmodel)"), QStringLiteral("spmodel"));
        if (!path.isEmpty())
          saveModel(path);
      });
  save_model->setShortcut(QKeySequence::Save);
  add(
      file, [] { return tr("Save &scan…"); }, this,
      [this] {
        if (!m_scan)
          return showError(tr("Save scan"), tr("Open or capture a scan first."));
        const QString path = askSaveFileName(this, tr("Save scan"), QString(),
                                             tr("Scans (*.pcd *.ply)"), QStringLiteral("pcd"));
        if (!path.isEmpty())
          saveScan(path);
      });
  add(
      file, [] { return tr("&Export results…"); }, this,
      [this] {
        const QString path = askSaveFileName(this, tr("Export results"), QString(),
                                             tr("Results (*.json)"), QStringLiteral("json"));
        if (!path.isEmpty())
          exportResults(path);
      });
  QAction* shot = add(
      file, [] { return tr("Save screens&hot…"); }, this,
      [this] {
        const QString path = askSaveFileName(this, tr("Save screenshot"), QString(),
                                             tr("Images (*.png)"), QStringLiteral("png"));
        if (!path.isEmpty())
          saveScreenshot(path);
      });
  shot->setShortcut(Qt::Key_F12);
  file->addSeparator();
  add(
      file, [] { return tr("&Quit"); }, this, &QWidget::close)
      ->setShortcut(QKeySequence::Quit);

  QMenu* edit = menu([] { return tr("&Edit"); });
  // Undo and redo name the step they undo ("Undo Crop"), in the language of the moment.
  auto* undo = new QAction(this);
  auto* redo = new QAction(this);
  undo->setObjectName(QStringLiteral("undoAction"));
  redo->setObjectName(QStringLiteral("redoAction"));
  connect(undo, &QAction::triggered, m_undo, &QUndoStack::undo);
  connect(redo, &QAction::triggered, m_undo, &QUndoStack::redo);
  undo->setEnabled(false);
  redo->setEnabled(false);
  connect(m_undo, &QUndoStack::canUndoChanged, undo, &QAction::setEnabled);
  connect(m_undo, &QUndoStack::canRedoChanged, redo, &QAction::setEnabled);
  const auto undo_text = [this] {
    const QString step = m_undo->undoText();
    return step.isEmpty() ? tr("&Undo") : tr("&Undo %1").arg(step);
  };
  const auto redo_text = [this] {
    const QString step = m_undo->redoText();
    return step.isEmpty() ? tr("&Redo") : tr("&Redo %1").arg(step);
  };
  named(undo, undo_text);
  named(redo, redo_text);
  connect(m_undo, &QUndoStack::undoTextChanged, undo,
          [undo, undo_text] { undo->setText(undo_text()); });
  connect(m_undo, &QUndoStack::redoTextChanged, redo,
          [redo, redo_text] { redo->setText(redo_text()); });
  undo->setShortcut(QKeySequence::Undo);
  redo->setShortcut(QKeySequence::Redo);
  edit->addAction(undo);
  edit->addAction(redo);

  QMenu* teach_menu = menu([] { return tr("&Teach"); });
  m_crop_action = named(teach_menu->addAction(QString()), [] { return tr("Crop &box"); });
  m_crop_action->setCheckable(true);
  m_crop_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_B));
  connect(m_crop_action, &QAction::toggled, this, &MainWindow::setCropBoxVisible);
  add(
      teach_menu, [] { return tr("&Apply crop"); }, this, [this] { applyCrop(); })
      ->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Return));
  m_lasso_action = named(teach_menu->addAction(QString()), [] { return tr("&Lasso crop"); });
  m_lasso_action->setCheckable(true);
  m_lasso_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_L));
  m_texts.bind(m_lasso_action, "toolTip", [] {
    return tr("Draw around the part with the left button: the points inside "
              "are kept (undo with Ctrl+Z)");
  });
  connect(m_lasso_action, &QAction::toggled, this, &MainWindow::setLassoActive);
  m_floor_preview_action = add(
      teach_menu, [] { return tr("&Preview floor"); }, this, &MainWindow::previewFloor);
  m_floor_preview_action->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_F));
  m_texts.bind(m_floor_preview_action, "toolTip", [] {
    return tr("Show the floor points (orange) that Remove floor would take away");
  });
  m_floor_remove_action = add(
      teach_menu, [] { return tr("Remove &floor"); }, this, &MainWindow::removeFloorFromPart);
  m_floor_remove_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_F));
  m_grip_action = named(teach_menu->addAction(QString()), [] { return tr("Place &grip points"); });
  m_grip_action->setCheckable(true);
  m_grip_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_G));
  QAction* teach_action = add(
      teach_menu, [] { return tr("&Teach model"); }, this, &MainWindow::teach);
  teach_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_T));

  QMenu* run = menu([] { return tr("&Recognize"); });
  QAction* recognize_action = add(
      run, [] { return tr("&Recognize"); }, this, &MainWindow::recognize);
  recognize_action->setShortcut(Qt::Key_F5);
  add(
      run, [] { return tr("&Cancel"); }, this, &MainWindow::cancelRecognition)
      ->setShortcut(Qt::Key_Escape);
  m_live_action = named(run->addAction(QString()), [] { return tr("&Live"); });
  m_live_action->setCheckable(true);
  m_live_action->setShortcut(Qt::Key_F6);
  connect(m_live_action, &QAction::toggled, this, &MainWindow::setLiveRunning);

  // Tools: the hand-eye calibration (docs/calibration.md), one dialog at a time, made on demand.
  QMenu* tools_menu = menu([] { return tr("T&ools"); });
  add(
      tools_menu, [] { return tr("&Hand-eye calibration…"); }, this,
      &MainWindow::showCalibrationWizard)
      ->setObjectName(QStringLiteral("handEyeCalibrationAction"));

  QMenu* view = menu([] { return tr("&View"); });
  m_view_menu = view;
  add(
      view, [] { return tr("&Reset camera"); }, m_view, &QtVtkViewport::resetCamera)
      ->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_0));
  // Overlays: on while there are no detections, then off (setResult) so that they do not hide
  // them; the operator turns them on again here.
  m_show_keypoints_action = named(view->addAction(QString()), [] { return tr("Show &keypoints"); });
  m_show_keypoints_action->setObjectName(QStringLiteral("showKeypointsAction"));
  m_show_keypoints_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_K));
  m_show_features_action = named(view->addAction(QString()), [] { return tr("Show f&eatures"); });
  m_show_features_action->setObjectName(QStringLiteral("showFeaturesAction"));
  m_show_features_action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_E));
  for (QAction* a : {m_show_keypoints_action, m_show_features_action}) {
    a->setCheckable(true);
    a->setChecked(true);
    connect(a, &QAction::toggled, this, &MainWindow::applyOverlayVisibility);
  }
  view->addSeparator();
  // The panels' entries go here once every panel exists (addPanelsToViewMenu).
  m_panels_separator = view->addSeparator();
  view->addSeparator();
  // The switch applies at once (ui/Language.h); each language is named in its own tongue.
  QMenu* language = view->addMenu(QString());
  language->setObjectName(QStringLiteral("languageMenu"));
  m_texts.bind(language->menuAction(), "text", [] { return tr("&Language"); });
  auto* group = new QActionGroup(this);
  const QString current = currentLanguage();
  for (const auto& [code, name] : {std::pair{QStringLiteral("en"), QStringLiteral("English")},
                                   std::pair{QStringLiteral("it"), QStringLiteral("Italiano")}}) {
    QAction* a = language->addAction(name, this, [this, code = code] { setLanguage(code); });
    a->setObjectName(QStringLiteral("language_") + code);
    a->setCheckable(true);
    a->setChecked(code == current);
    group->addAction(a);
  }

  QMenu* help = menu([] { return tr("&Help"); });
  add(
      help, [] { return tr("&User guide"); }, this, &MainWindow::openUserGuide)
      ->setShortcut(QKeySequence::HelpContents);
  add(
      help, [] { return tr("&About scanpick"); }, this, &MainWindow::showAbout);

  QToolBar* tools = addToolBar(QString());
  m_texts.bind(tools, "windowTitle", [] { return tr("Main"); });
  tools->setObjectName(QStringLiteral("MainToolBar"));
  tools->addAction(open);
  tools->addAction(m_crop_action);
  tools->addAction(m_lasso_action);
  tools->addAction(m_grip_action);
  tools->addAction(undo);
  tools->addAction(redo);
  tools->addSeparator();
  tools->addAction(teach_action);
  tools->addAction(recognize_action);
  tools->addAction(m_live_action);
}

void MainWindow::addPanelsToViewMenu() {
  // Every panel and toolbar, the Teach panel included, can be closed and opened again here.
  for (QDockWidget* dock : findChildren<QDockWidget*>())
    m_view_menu->insertAction(m_panels_separator, dock->toggleViewAction());
  for (QToolBar* bar : findChildren<QToolBar*>())
    m_view_menu->insertAction(m_panels_separator, bar->toggleViewAction());
}

QString MainWindow::userGuidePath() {
  // Next to an installed binary first, then the source tree the build came from.
  const QString installed =
      QCoreApplication::applicationDirPath() + "/../share/doc/scanpick/user-guide.md";
  if (QFileInfo::exists(installed))
    return QFileInfo(installed).canonicalFilePath();
  return QStringLiteral(SCANPICK_DOCS_DIR "/user-guide.md");
}

void MainWindow::openUserGuide() {
  const QString path = userGuidePath();
  if (!QFileInfo::exists(path) || !QDesktopServices::openUrl(QUrl::fromLocalFile(path)))
    showError(tr("User guide"),
              tr("Could not open the user guide (%1): open it with any text viewer.").arg(path));
}

void MainWindow::showAbout() {
  auto* box = new QMessageBox(
      QMessageBox::Information, tr("About scanpick"),
      tr("<h3>scanpick %1</h3><p>3D object recognition for bin picking, taught from a scan.</p>"
         "<p>Built with Qt %2 and VTK %3.</p><p>User guide: %4</p>")
          .arg(QStringLiteral(SCANPICK_VERSION), QString::fromLatin1(qVersion()),
               QString::fromLatin1(vtkVersion::GetVTKVersion()), userGuidePath().toHtmlEscaped()),
      QMessageBox::Ok, this);
  box->setObjectName(QStringLiteral("aboutDialog"));
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

void MainWindow::restoreSettings() {
  QSettings s;
  restoreGeometry(s.value(settings::kGeometry).toByteArray());
  restoreState(s.value(settings::kWindowState).toByteArray());
  const QString preset = s.value(settings::kLastPreset).toString();
  if (!preset.isEmpty() && QFileInfo::exists(preset)) {
    try {
      m_params->loadPresetFile(preset);
    } catch (const std::exception& e) {
      core::logger()->warn("could not restore the last preset: {}", e.what());
    }
  }
}

void MainWindow::closeEvent(QCloseEvent* event) {
  setLiveRunning(false);
  QSettings s;
  s.setValue(settings::kGeometry, saveGeometry());
  s.setValue(settings::kWindowState, saveState());
  event->accept();
}

void MainWindow::addRecentFile(const QString& path) {
  QSettings s;
  QStringList files = s.value(settings::kRecentFiles).toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  files.removeAll(absolute);
  files.prepend(absolute);
  while (files.size() > settings::kMaxRecentFiles)
    files.removeLast();
  s.setValue(settings::kRecentFiles, files);
  s.setValue(settings::kLastDirectory, QFileInfo(path).absolutePath());
  rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
  m_recent_menu->clear();
  const QStringList files = QSettings().value(settings::kRecentFiles).toStringList();
  for (const QString& path : files)
    m_recent_menu->addAction(QFileInfo(path).fileName(), this, [this, path] { openFiles({path}); })
        ->setToolTip(path);
  m_recent_menu->setEnabled(!files.isEmpty());
}

void MainWindow::openFiles(const QStringList& paths) {
  QStringList models;
  for (const QString& path : paths) {
    if (path.endsWith(QLatin1String(".spmodel"), Qt::CaseInsensitive))
      models << path;
    else
      openScan(path);
  }
  if (!models.isEmpty())
    openModels(models);
}

void MainWindow::openScan(const QString& path) {
  statusBar()->showMessage(tr("Loading %1…").arg(path));
  const std::string file = path.toStdString();
  m_jobs->run<core::LoadedCloud>(
      [file](const core::ProgressFn& progress) {
        // Files in metres are common (PCL samples, ROS): with no units given, the extent tells.
        return core::loadCloud(file, std::nullopt, progress);
      },
      [this, path](std::shared_ptr<const core::LoadedCloud> loaded) {
        m_scan_path = path;
        addRecentFile(path);
        setScan(std::make_shared<const core::PointCloud>(loaded->cloud),
                QFileInfo(path).fileName());
        emit scanLoaded();
      },
      [this, path](const QString& error) {
        showError(tr("Open scan"), error);
        statusBar()->showMessage(tr("Could not open %1").arg(path), 5000);
      });
}

void MainWindow::setScan(std::shared_ptr<const core::PointCloud> scan_mm, const QString& name) {
  m_scan = std::move(scan_mm);
  if (m_scan_path.isEmpty() || QFileInfo(m_scan_path).fileName() != name)
    m_scan_path = name;
  m_undo->clear();
  m_grips.clear();
  m_result.reset();
  m_results->setDetections({}, {});
  refreshGripList();
  clearLayers({QStringLiteral("detections"), QStringLiteral("labels"), QStringLiteral("grips"),
               QStringLiteral("scene")});
  m_scene_shown.reset();
  m_framed_scan.reset();
  // No detections: the keypoint and feature previews are what there is to see.
  m_detections_shown = false;
  m_show_keypoints_action->setChecked(true);
  m_show_features_action->setChecked(true);
  setPart(m_scan);
  lookFromSensor();
  m_selected_detection = -1;
  updateDepthView();
  m_texts.bind(this, "windowTitle", [name] { return tr("scanpick — %1").arg(name); });
  core::logger()->info("scan {}: {} valid points", name.toStdString(), m_scan->validCount());
  statusBar()->showMessage(tr("%1: %2 points").arg(name).arg(m_scan->validCount()), 5000);
}

void MainWindow::lookFromSensor(const Eigen::AlignedBox3f& frame) {
  // Scans are in the camera frame: z forward, y down.
  vtkCamera* camera = m_view->renderer()->GetActiveCamera();
  camera->SetPosition(0, 0, 0);
  camera->SetFocalPoint(0, 0, 1);
  camera->SetViewUp(0, -1, 0);
  if (frame.isEmpty()) {
    m_view->resetCamera();
    return;
  }
  double bounds[6] = {frame.min().x(), frame.max().x(), frame.min().y(),
                      frame.max().y(), frame.min().z(), frame.max().z()};
  m_view->renderer()->ResetCamera(bounds);
  m_view->renderer()->ResetCameraClippingRange();
  m_view->requestRender();
}

bool MainWindow::openModels(const QStringList& paths) {
  return takeViews(paths, false);
}

bool MainWindow::addModelViews(const QStringList& paths) {
  return takeViews(paths, model() != nullptr);
}

bool MainWindow::takeViews(const QStringList& paths, bool add) {
  if (paths.isEmpty())
    return false;
  try {
    auto views = add ? m_loaded_views : std::vector<std::shared_ptr<const core::TaughtModel>>{};
    for (const QString& path : paths)
      views.push_back(
          std::make_shared<const core::TaughtModel>(core::loadModel(path.toStdString())));
    core::requireOnePart(views);
    setViews(std::move(views), add ? m_view_paths + paths : paths, true);
  } catch (const std::exception& e) {
    showError(add ? tr("Add model view") : tr("Open model"), QString::fromUtf8(e.what()));
    return false;
  }
  for (const QString& path : paths)
    addRecentFile(path);
  return true;
}

void MainWindow::setViews(std::vector<std::shared_ptr<const core::TaughtModel>> views,
                          QStringList paths, bool take_params) {
  m_loaded_views = std::move(views);
  m_view_paths = std::move(paths);
  const core::TaughtModel& first = *m_loaded_views.front();
  core::RecognitionParams params = core::viewsParams(m_loaded_views);
  if (m_loaded_views.size() == 1 && !first.view_params.empty()) {
    // A single view's own matching parameters become the panel's values, so that the panel tunes
    // them (the searched copy drops them; the file keeps them when saved again). With several
    // views each keeps its own, over the panel's.
    auto folded = std::make_shared<core::TaughtModel>(first);
    core::foldViewParams(params, folded->view_params);
    m_views = {folded};
    take_params = true;
  } else {
    m_views = core::joinViews(m_loaded_views);
  }
  if (take_params) {
    // The reasons of the values derived at teach; a view's own value has none.
    auto reasons = first.param_reasons;
    for (const auto& [key, value] : first.view_params)
      reasons.erase(key);
    if (!reasons.empty())
      core::logger()->info("model '{}': {} parameters derived from the part at teach, each with "
                           "its reason in the Parameters panel",
                           first.name, reasons.size());
    m_params->setParams(params, std::move(reasons));
  }
  // What a derived teach measured belongs to that teach (teach() shows it again).
  m_teach_measures->setVisible(false);
  prepareModelInBackground();
  m_coverage->setViews(m_views);
  const auto joined = std::count_if(m_views.begin(), m_views.end(),
                                    [](const auto& v) { return !v->joined_views.empty(); });
  for (std::size_t v = 0; v < m_views.size(); ++v)
    core::logger()->info(
        "model '{}' view {} ({}): {} features, {} grip points{}", first.name, v + 1,
        m_view_paths[int(v)].isEmpty() ? std::string("taught") : m_view_paths[int(v)].toStdString(),
        m_views[v]->features.size(), m_views[v]->grip_points.size(),
        m_views[v]->joined_views.empty() ? "" : ", joined with the others");
  statusBar()->showMessage(m_views.size() == 1
                               ? tr("Model %1 loaded").arg(QString::fromStdString(first.name))
                               : tr("Model %1: %2 views, %3 of them joined")
                                     .arg(QString::fromStdString(first.name))
                                     .arg(m_views.size())
                                     .arg(joined),
                           5000);
}

void MainWindow::prepareModelInBackground() {
  const auto recognizer = m_recognizer;
  const auto views = m_views;
  const core::RecognitionParams params = m_params->params();
  m_prepare_jobs->run<double>(
      [recognizer, views, params](const core::ProgressFn&) {
        return core::prepareViews(*recognizer, views, params);
      },
      [](std::shared_ptr<const double> ms) {
        core::logger()->info("model prepared for matching in {:.0f} ms", *ms);
      });
}

bool MainWindow::saveModel(const QString& file) {
  if (!model()) {
    showError(tr("Save model"), tr("Teach or open a model first."));
    return false;
  }
  const QString path = withSuffix(file, QStringLiteral("spmodel"));
  try {
    core::saveModel(path.toStdString(), *model());
    // The first view now has this file, also for the results found with it.
    m_view_paths[0] = path;
    if (!m_result_views.empty() && m_result_views.front() == m_views.front())
      m_result_view_paths[0] = path;
    core::logger()->info("saved model to {}", path.toStdString());
    statusBar()->showMessage(tr("Saved %1").arg(path), 5000);
    return true;
  } catch (const std::exception& e) {
    showError(tr("Save model"), QString::fromUtf8(e.what()));
    return false;
  }
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls())
    event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  QStringList paths;
  for (const QUrl& url : event->mimeData()->urls())
    if (url.isLocalFile())
      paths << url.toLocalFile();
  openFiles(paths);
}

void MainWindow::showError(const QString& title, const QString& message) {
  core::logger()->error("{}: {}", title.toStdString(), message.toStdString());
  // Modeless, so a failing background job never stacks nested event loops.
  auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->setObjectName(QStringLiteral("errorDialog"));
  box->open();
}

void MainWindow::setLayer(const QString& name, vtkSmartPointer<vtkProp> prop) {
  auto it = m_layers.find(name);
  if (it != m_layers.end()) {
    m_view->renderer()->RemoveViewProp(it->second);
    m_layers.erase(it);
  }
  if (prop) {
    m_view->renderer()->AddViewProp(prop);
    m_layers[name] = prop;
  }
  applyOverlayVisibility();
}

void MainWindow::applyOverlayVisibility() {
  for (const auto& [name, action] :
       {std::pair{QStringLiteral("keypoints"), m_show_keypoints_action},
        std::pair{QStringLiteral("features"), m_show_features_action}})
    if (const auto it = m_layers.find(name); it != m_layers.end())
      it->second->SetVisibility(action->isChecked() ? 1 : 0);
  m_view->requestRender();
}

void MainWindow::clearLayers(const QStringList& names) {
  for (const QString& name : names)
    setLayer(name, nullptr);
}

void MainWindow::setLanguage(const QString& code) {
  QSettings().setValue(settings::kLanguage, code);
  // Installing the translators sends QEvent::LanguageChange to every widget (retranslateUi).
  if (!applyLanguage(code))
    core::logger()->warn("the '{}' translation could not be loaded: English is shown",
                         code.toStdString());
  for (QAction* a : findChildren<QAction*>(QStringLiteral("language_") + currentLanguage()))
    a->setChecked(true);
  core::logger()->info("language set to '{}'", currentLanguage().toStdString());
}

QImage MainWindow::screenshot() {
  return m_view->grabFramebuffer();
}

bool MainWindow::saveScreenshot(const QString& path) {
  const QImage image = screenshot();
  if (image.isNull() || !image.save(path)) {
    showError(tr("Screenshot"),
              tr("Could not write %1: check the folder exists and is writable.").arg(path));
    return false;
  }
  core::logger()->info("screenshot saved to {}", path.toStdString());
  return true;
}

} // namespace scanpick::ui
