#pragma once
/// @file MainWindow.h
/// The scanpick main window: a 3D viewport in the centre and dockable panels (parameters,
/// teach tools, results, capture, log). Workflows: teach a model from a scan (crop, grip points,
/// keypoint/feature preview, save), tune parameters with live previews, recognize, capture and
/// run live. Long work runs in background jobs (JobRunner); the window never blocks.

#include "core/cloud/CloudIo.h"
#include "core/cloud/PointCloud.h"
#include "core/features/FeatureExtraction.h"
#include "core/keypoints/Keypoints.h"
#include "core/model/TaughtModel.h"
#include "core/params/ParameterTable.h"
#include "core/pipeline/Recognizer.h"
#include "ui/TranslatedTexts.h"

#include <QColor>
#include <QMainWindow>
#include <QPointer>
#include <QPolygonF>
#include <map>
#include <memory>
#include <optional>
#include <vtkSmartPointer.h>

class QAction;
class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QMenu;
class QProgressBar;
class QPushButton;
class QTimer;
class QUndoStack;
class QVBoxLayout;
class vtkBoxWidget2;
class vtkProp;

namespace scanpick::ui {

class CoveragePanel;
class DepthView;
class DevicePanel;
class JobPool;
class JobRunner;
class LassoOverlay;
class LogDock;
class ParameterPanel;
class QtVtkViewport;
class ResultsTable;

/// The keypoint/feature preview of the working cloud (teach and tune).
struct PreviewResult {
  std::shared_ptr<const core::Keypoints> keypoints;
  core::FeatureExtraction features;
  double keypoints_ms = 0; ///< 0 when the keypoints came from the cache
  double features_ms = 0;
  quint64 cloud_version = 0;
  core::KeypointParams keypoint_params;
};

class MainWindow : public QMainWindow {
  Q_OBJECT
public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // --- files (all asynchronous ones report through signals) ---
  /// Loads a PCD/PLY scan in the background; emits scanLoaded or shows the error.
  void openScan(const QString& path);
  /// Shows `scan` as the current scan (teach source and recognition scene).
  void setScan(std::shared_ptr<const core::PointCloud> scan_mm, const QString& name);
  /// Loads a .spmodel file (synchronous, small) as the part to find, in place of the views
  /// opened or taught before; shows a dialog on failure. Returns success.
  bool openModel(const QString& path) { return openModels({path}); }
  /// Loads several .spmodel files as the views of one part (each taught from a scan of another
  /// side it can rest on), in place of those opened or taught before. Recognize and Live search
  /// them all, as `scanpick-cli recognize` with several --model does; views that know their place
  /// in the part are joined (core::joinViews). When a file does not load, or the views are of
  /// different parts, a dialog says why and nothing changes. Returns success.
  bool openModels(const QStringList& paths);
  /// Adds views of the same part to those opened or taught (e.g. the other sides' saved views to
  /// one just taught); the same checks as openModels. Returns success.
  bool addModelViews(const QStringList& paths);
  /// Saves the model taught or opened first (the first view) as `file`, ".spmodel" added when it
  /// does not end so; returns false (and says why) on failure.
  bool saveModel(const QString& file);
  /// Saves the current scan (PCD or PLY by extension); returns false (and says why) on failure.
  bool saveScan(const QString& path);

  // --- teach ---
  /// Shows or hides the interactive crop box (placed around the working cloud when shown).
  void setCropBoxVisible(bool visible);
  /// Moves the crop box (scan frame).
  void setCropBox(const core::OrientedBox& box);
  [[nodiscard]] core::OrientedBox cropBox() const;
  /// Crops the working cloud to the box (undoable). Returns false when nothing would remain.
  bool applyCrop();
  /// Shows or hides the lasso tool: drag on the viewport to draw a polygon; on release the points
  /// whose projection lies inside are kept (see applyLasso).
  void setLassoActive(bool active);
  /// Keeps the working-cloud points whose screen projection (current camera) falls inside
  /// `polygon_px` (viewport widget coordinates, logical pixels). Runs in the background and is
  /// undoable; emits partChanged. A polygon with fewer than 3 corners or keeping nothing is
  /// refused with a message.
  void applyLasso(const QPolygonF& polygon_px);
  /// Finds the floor (dominant planes, params.floor) in the working cloud in the background and
  /// shows the points that would be removed in orange (kFloorPreviewColour); emits
  /// floorPreviewReady. Nothing is removed yet.
  void previewFloor();
  /// Removes the floor from the working cloud (undoable): uses the preview when it is for the
  /// current working cloud, otherwise finds the floor first (background job).
  void removeFloorFromPart();
  /// Points the last floor preview would remove (0 without a preview).
  [[nodiscard]] std::size_t floorPreviewCount() const;
  /// The sensor the current scan comes from: the preset whose grid matches an organized scan,
  /// otherwise the one chosen in the Teach panel.
  [[nodiscard]] core::SensorModel currentSensor() const;
  /// The sensor preset whose grid (width × height) matches an organized `cloud`, if any.
  static std::optional<core::SensorModel> sensorOfGrid(const core::PointCloud& cloud);
  /// Adds a grip point (scan frame, mm) with an automatic name, approached against the surface
  /// normal there (core::grasp::surfaceApproach; undoable).
  void addGripPoint(const Eigen::Vector3d& position_mm);
  /// Moves grip point `index` to `position_mm` (scan frame), approached against the surface
  /// normal at its new place (undoable). Nothing for a bad index.
  void moveGripPoint(int index, const Eigen::Vector3d& position_mm);
  /// Sets the approach of grip point `index` (scan frame, any length; undoable) and drops a
  /// closing axis that is no longer across it. Returns false, changing nothing, for a bad index
  /// or a zero or non-finite direction.
  bool setGripApproach(int index, const Eigen::Vector3d& approach);
  /// Removes grip point `index` (undoable). Nothing for a bad index.
  void removeGripPoint(int index);
  /// Renames grip point `index` (undoable). Nothing for a bad index or the same name.
  void renameGripPoint(int index, const QString& name);
  /// Replaces the grip points and selects row `selected` of their list (used by the undo
  /// commands; not undoable itself).
  void setGripPoints(std::vector<core::GripPoint> grips, int selected = -1);
  /// Teaches the model from the working cloud in the background; emits modelTaught. With the
  /// Parameters panel's default choice (ParameterPanel::derivesAtTeach) the parameters are
  /// derived from the part and the scan in the same job (values set by hand since the last teach
  /// or preset win), the model keeps the reasons, the panel shows the derived values with them
  /// and the Teach panel the measured spacing, noise and diameter; otherwise the panel's values
  /// are used as they are.
  void teach();

  // --- recognize ---
  /// Recognizes the taught model in the current scan; emits recognitionFinished.
  void recognize();
  void cancelRecognition();
  /// Writes the last results as JSON to `file`, ".json" added when it does not end so. Returns
  /// false (and says why) on failure.
  bool exportResults(const QString& file);
  /// Starts or stops capture → recognize cycles on the open camera.
  void setLiveRunning(bool running);

  // --- help ---
  /// The user guide (docs/user-guide.md): installed beside the binary, or in the source tree.
  static QString userGuidePath();
  /// Opens the user guide with the desktop's viewer for Markdown files (Help → User guide, F1);
  /// says so in a dialog when it cannot.
  void openUserGuide();
  /// Shows the About box (modeless): version, what scanpick does, Qt and VTK versions.
  void showAbout();

  /// Renders the viewport into an image / a PNG file.
  [[nodiscard]] QImage screenshot();
  bool saveScreenshot(const QString& path);

  // --- for tests and scripting ---
  [[nodiscard]] QtVtkViewport* viewport() const { return m_view; }
  [[nodiscard]] ParameterPanel* parameterPanel() const { return m_params; }
  [[nodiscard]] ResultsTable* resultsTable() const { return m_results; }
  [[nodiscard]] LogDock* logDock() const { return m_log; }
  [[nodiscard]] DevicePanel* devicePanel() const { return m_devices; }
  /// The depth image view (View → Depth image).
  [[nodiscard]] DepthView* depthView() const { return m_depth_view; }
  /// The view coverage of the part's views (View → View coverage).
  [[nodiscard]] CoveragePanel* coveragePanel() const { return m_coverage; }
  [[nodiscard]] JobRunner* depthJobs() const { return m_depth_jobs; }
  [[nodiscard]] JobRunner* jobs() const { return m_jobs; }
  [[nodiscard]] bool liveRunning() const { return m_live; }
  [[nodiscard]] JobRunner* previewJobs() const { return m_preview_jobs; }
  [[nodiscard]] JobRunner* recognizeJobs() const { return m_recognize_jobs; }
  [[nodiscard]] JobRunner* prepareJobs() const { return m_prepare_jobs; }
  /// How many model preparations the recognizer holds (see prepareModelInBackground).
  [[nodiscard]] std::size_t preparedModels() const { return m_recognizer->preparedModels(); }
  [[nodiscard]] QUndoStack* undoStack() const { return m_undo; }
  [[nodiscard]] std::shared_ptr<const core::PointCloud> scan() const { return m_scan; }
  [[nodiscard]] std::shared_ptr<const core::PointCloud> part() const { return m_part; }
  /// The first view, as loaded or taught (null before any).
  [[nodiscard]] std::shared_ptr<const core::TaughtModel> model() const {
    return m_loaded_views.empty() ? nullptr : m_loaded_views.front();
  }
  /// The part's views as Recognize searches them (joined; the first one is model()'s).
  [[nodiscard]] const std::vector<std::shared_ptr<const core::TaughtModel>>& views() const {
    return m_views;
  }
  [[nodiscard]] std::shared_ptr<const PreviewResult> preview() const { return m_preview; }
  [[nodiscard]] const core::RecognitionResult* lastResult() const { return m_result.get(); }
  [[nodiscard]] const std::vector<core::GripPoint>& gripPoints() const { return m_grips; }
  /// Runs the keypoint/feature preview now (normally debounced), cancelling a running one.
  void refreshPreview() { runPreview(); }
  /// Debounce delay of the live preview, ms (150 by default).
  void setPreviewDelay(int ms);
  /// Replaces the working cloud (used by the crop commands; undoable through them).
  void setPart(std::shared_ptr<const core::PointCloud> part_mm);

  /// Colour of the points a floor removal would take away, in the preview.
  static QColor floorPreviewColour() { return {255, 110, 0}; }

signals:
  void scanLoaded();
  /// The working cloud changed (crop, lasso, floor removal, undo/redo, new scan).
  void partChanged();
  void floorPreviewReady(std::size_t removed_points);
  /// One live capture → recognize cycle ended and is shown.
  void liveCycleFinished(double cycle_ms, int detections);
  void previewUpdated();
  void modelTaught();
  void recognitionFinished(bool ok);
  /// The depth image view shows a new image (of the current scan and result).
  void depthViewUpdated();

protected:
  void changeEvent(QEvent* event) override;
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

private:
  // MainWindow.cpp: shell
  void buildActions();
  void buildDocks();
  /// Adds every panel's and toolbar's show/hide entry to the View menu.
  void addPanelsToViewMenu();
  void restoreSettings();
  void addRecentFile(const QString& path);
  void rebuildRecentMenu();
  /// Opens scans (in turn) and models (together, as the views of one part).
  void openFiles(const QStringList& paths);
  void showError(const QString& title, const QString& message);
  void setLayer(const QString& name, vtkSmartPointer<vtkProp> prop);
  void clearLayers(const QStringList& names);
  /// Makes `code` ("en", "it") the language, at once and at the next start.
  void setLanguage(const QString& code);
  /// Sets every text again in the language now installed (QEvent::LanguageChange).
  void retranslateUi();
  /// The status bar's message before anything happened.
  static QString welcomeText();
  [[nodiscard]] double ratio() const;
  // MainWindowTeach.cpp
  void buildTeachDock();
  /// The View coverage panel, a tab beside the depth image.
  void buildCoverageDock();
  void schedulePreview(core::Stage first_stage);
  void runPreview();
  void showPart();
  void showPreview();
  void showGrips();
  void showGripApproach();      // the selected grip point's approach in its field
  void showCalibrationWizard(); // one dialog at a time, made on demand, deleted on close
  void refreshGripList();
  void onViewportClick(int x, int y);
  void showFloorPreview();
  /// Shows what the last derived teach measured (spacing, noise, diameter) in the Teach panel,
  /// the status bar and the log; hides the Teach panel's line for `derived` empty.
  void showTeachMeasures(const core::AutoParams* derived, std::size_t features);
  /// Pushes an undoable replacement of the working cloud by `after`.
  void replacePart(std::shared_ptr<const core::PointCloud> after, const QString& text);
  // MainWindowTools.cpp
  void buildToolButtons(QVBoxLayout* layout);
  /// Makes `views` (as loaded, first = the one the panel tunes; `paths` alike, empty for one not
  /// saved) the part to find and prepares them. With `take_params` the panel takes the first
  /// view's parameters; a single view's own matching parameters become the panel's values.
  void setViews(std::vector<std::shared_ptr<const core::TaughtModel>> views, QStringList paths,
                bool take_params);
  /// Loads `paths` as the part's views, or with `add` as more of them (openModels,
  /// addModelViews); on failure a dialog says why and nothing changes.
  bool takeViews(const QStringList& paths, bool add);
  // MainWindowRecognize.cpp
  /// Shows `result`, found with `views` (their files in `paths`), in the table and the viewport.
  void setResult(std::shared_ptr<const core::RecognitionResult> result,
                 std::vector<std::shared_ptr<const core::TaughtModel>> views, QStringList paths);
  void showResult(int selected);
  /// Prepares the model for matching in the background (Recognizer::prepare), so that the first
  /// recognition, or live cycle, does not pay for it.
  void prepareModelInBackground();
  void onResultSelected(int row);
  void runLiveCycle();
  /// Points the camera as the sensor looks (scans are in the camera frame) and fits the view to
  /// `frame` (scan frame, mm), or to everything shown when it is empty.
  void lookFromSensor(const Eigen::AlignedBox3f& frame = {});
  /// Shows or hides the keypoint and feature layers as the View menu's toggles say.
  void applyOverlayVisibility();
  /// Brings the depth image view up to date with the scan and the result: in the background,
  /// and only while the view is visible (otherwise when it is shown).
  void updateDepthView();

  QtVtkViewport* m_view = nullptr;
  ParameterPanel* m_params = nullptr;
  LogDock* m_log = nullptr;
  ResultsTable* m_results = nullptr;
  DevicePanel* m_devices = nullptr;
  DepthView* m_depth_view = nullptr;
  CoveragePanel* m_coverage = nullptr;
  // What the depth view shows or is drawing: of this scan, with this result.
  std::shared_ptr<const core::PointCloud> m_depth_scan;
  std::shared_ptr<const core::RecognitionResult> m_depth_result;
  int m_selected_detection = -1;
  TranslatedTexts m_texts; // every text of the window that follows the language
  QString m_welcome_shown; // the welcome message as shown, to tell whether it still is
  // The threads every job below runs on (bounded, isolated from the GUI thread); destroyed after
  // the destructor cancelled the jobs, waiting for them to end.
  std::unique_ptr<JobPool> m_pool;
  JobRunner* m_jobs = nullptr;           // loading, floor removal, teach
  JobRunner* m_preview_jobs = nullptr;   // keypoint/feature preview
  JobRunner* m_recognize_jobs = nullptr; // recognition (single and live)
  JobRunner* m_prepare_jobs = nullptr;   // preparing a new model for matching
  JobRunner* m_depth_jobs = nullptr;     // the depth image
  QTimer* m_preview_timer = nullptr;
  QUndoStack* m_undo = nullptr;
  QMenu* m_recent_menu = nullptr;
  QMenu* m_view_menu = nullptr;
  QAction* m_panels_separator = nullptr; // the View menu's panel entries go before it
  QAction* m_show_keypoints_action = nullptr;
  QAction* m_show_features_action = nullptr;
  QLabel* m_status_counts = nullptr;
  QLabel* m_status_timings = nullptr;
  QProgressBar* m_progress = nullptr;
  QPushButton* m_cancel = nullptr;
  QListWidget* m_grip_list = nullptr;
  QLineEdit* m_grip_approach = nullptr; // the selected grip point's approach, "x, y, z"
  QAction* m_crop_action = nullptr;
  QAction* m_grip_action = nullptr;
  QAction* m_grip_move_action = nullptr; // the next click moves the selected grip point
  QAction* m_live_action = nullptr;
  QAction* m_lasso_action = nullptr;
  QAction* m_floor_preview_action = nullptr;
  QAction* m_floor_remove_action = nullptr;
  bool m_apply_floor_pending = false; // Remove floor asked before a preview existed
  QComboBox* m_sensor_combo = nullptr;
  QLineEdit* m_part_name = nullptr;   // teach: the part's name (empty: the scan's)
  QLineEdit* m_part_pose = nullptr;   // teach: its pose in the scan, optional
  QLabel* m_teach_measures = nullptr; // teach: what the derived parameters were measured from
  LassoOverlay* m_lasso = nullptr;
  vtkSmartPointer<vtkBoxWidget2> m_box_widget;
  std::map<QString, vtkSmartPointer<vtkProp>> m_layers;

  std::shared_ptr<const core::PointCloud> m_scan;
  QString m_scan_path;
  std::shared_ptr<const core::PointCloud> m_part; // working cloud of the teach workflow
  quint64 m_part_version = 0;
  std::vector<core::GripPoint> m_grips; // scan frame
  // The part's views: as loaded or taught (model() first), their files (empty for a view not
  // saved), and as searched.
  std::vector<std::shared_ptr<const core::TaughtModel>> m_loaded_views;
  QStringList m_view_paths;
  std::vector<std::shared_ptr<const core::TaughtModel>> m_views;
  std::shared_ptr<core::Recognizer> m_recognizer;
  std::shared_ptr<const PreviewResult> m_preview;
  std::shared_ptr<const core::RecognitionResult> m_result;
  // The views and files the last result was found with (Detection::model_index refers to them).
  std::vector<std::shared_ptr<const core::TaughtModel>> m_result_views;
  QStringList m_result_view_paths;
  struct FloorPreview {
    std::shared_ptr<const core::PointCloud> part;      // the working cloud it was computed for
    std::shared_ptr<const core::PointCloud> remaining; // the working cloud without the floor
    std::shared_ptr<const core::PointCloud> removed;   // the floor points, for display
  };
  std::shared_ptr<const FloorPreview> m_floor_preview;
  // What the result view drew: the scan its grey scene layer shows, the scan the camera was
  // framed on, and whether detections were shown since the scan was opened.
  std::shared_ptr<const core::PointCloud> m_scene_shown;
  std::shared_ptr<const core::PointCloud> m_framed_scan;
  bool m_detections_shown = false;
  bool m_live = false;
  int m_live_cycles = 0; // cycles shown since Live started
};

} // namespace scanpick::ui
