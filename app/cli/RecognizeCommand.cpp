// scanpick-cli recognize: find a taught part in one scene, or in every scene of a suite folder.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/ModelViews.h"
#include "app/cli/RecipeOptions.h"
#include "core/calib/BaseFrame.h"
#include "core/common/AtomicFile.h"
#include "core/common/JsonText.h"
#include "core/model/ModelFile.h"
#include "core/model/ViewCoverage.h"
#include "core/output/OverlayPicture.h"
#include "core/output/ResultsJson.h"
#include "core/pipeline/Recognizer.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace scanpick::cli {
namespace {
namespace fs = std::filesystem;

struct Options {
  RecipeOptions recipe;
  std::vector<std::string> models;
  std::string scene, out, picture, suite;
  std::string calibration; ///< hand-eye calibration file: poses also in the robot base frame
  std::string flange_pose; ///< eye-in-hand: the flange pose of the scan
};

/// Where the robot base frame comes from, checked before any work: the calibration, and for
/// eye-in-hand the flange pose of the (single) scene.
struct BaseFrameSource {
  std::optional<core::calib::CameraCalibration> calibration;
  std::optional<Eigen::Isometry3d> T_base_flange;
};

BaseFrameSource baseFrameSource(const Options& o) {
  BaseFrameSource out;
  if (!o.flange_pose.empty()) {
    if (o.calibration.empty())
      throw core::Error("--flange-pose needs --calibration (the eye-in-hand calibration file "
                        "written by scanpick-cli calibrate)");
    out.T_base_flange = core::calib::parseFlangePose(o.flange_pose, "--flange-pose");
  }
  if (o.calibration.empty())
    return out;
  out.calibration = core::calib::loadCameraCalibration(o.calibration);
  if (out.calibration->needsFlangePose() && !o.suite.empty())
    throw core::Error("'" + o.calibration +
                      "' is an eye-in-hand calibration: each scan needs the flange pose it was "
                      "taken at; recognize the scans one at a time with --scene and --flange-pose");
  (void)core::calib::baseFromCamera(*out.calibration, out.T_base_flange); // refuses a mismatch
  return out;
}

/// resultsToJson(...) with, when a calibration is given, each detection's pose and grip points in
/// the robot base frame ("pose_base", "position_base_mm") and the calibration used.
nlohmann::json resultsDocument(const core::RecognitionResult& result, const ModelViews& loaded,
                               const std::string& scene_path, const BaseFrameSource& base) {
  nlohmann::json doc = core::resultsToJson(result, loaded.sources, scene_path);
  if (!base.calibration)
    return doc;
  const Eigen::Isometry3d T_base_camera =
      core::calib::baseFromCamera(*base.calibration, base.T_base_flange);
  nlohmann::json calibration = {{"file", base.calibration->file},
                                {"mode", core::calib::modeName(base.calibration->mode)},
                                {"T_base_camera", core::calib::basePoseJson(T_base_camera)}};
  if (base.T_base_flange)
    calibration["T_base_flange"] = core::calib::basePoseJson(*base.T_base_flange);
  doc["calibration"] = calibration;
  for (std::size_t i = 0; i < result.detections.size(); ++i) {
    const core::Detection& d = result.detections[i];
    nlohmann::json& out = doc["detections"][i];
    out["pose_base"] = core::calib::basePoseJson(T_base_camera * d.T_scene_model);
    for (std::size_t g = 0; g < d.grip_points_scene.size(); ++g) {
      const Eigen::Vector3d p = T_base_camera * d.grip_points_scene[g].position_mm;
      out["grip_points"][g]["position_base_mm"] = {p.x(), p.y(), p.z()};
    }
  }
  return doc;
}

void saveResultsDocument(const fs::path& path, const nlohmann::json& doc) {
  core::writeFileAtomic(path, core::dumpJsonText(doc, 2) + "\n");
}

/// The suite scene's sensor preset and kind from its ground truth, when there is one.
std::pair<std::string, std::string> truthInfo(const fs::path& scene_path) {
  const fs::path gt = scene_path.parent_path() / (scene_path.stem().string() + ".gt.json");
  if (!fs::exists(gt))
    return {};
  nlohmann::json doc;
  try {
    doc = core::parseJsonText(core::readFile(gt), gt.string(), "");
  } catch (const core::Error&) {
    return {}; // the scene is recognized without its ground truth's sensor and kind
  }
  std::string preset, kind;
  if (doc.contains("sensor") && doc["sensor"].is_object())
    preset = doc["sensor"].value("preset", std::string());
  if (doc.contains("scene") && doc["scene"].is_object())
    kind = doc["scene"].value("kind", std::string());
  return {preset, kind};
}

void printSummary(const std::string& scene, const core::RecognitionResult& r) {
  std::printf("%s: %zu detection(s) in %.0f ms (preprocess %.0f, clustering %.0f, keypoints %.0f, "
              "features %.0f, matching %.0f)\n",
              scene.c_str(), r.detections.size(), r.timings.total_ms, r.timings.preprocess_ms,
              r.timings.clustering_ms, r.timings.keypoints_ms, r.timings.features_ms,
              r.timings.matching_ms);
  for (std::size_t i = 0; i < r.detections.size(); ++i) {
    const auto& d = r.detections[i];
    const Eigen::Vector3d t = d.T_scene_model.translation();
    std::printf("  #%zu score %.3f at (%.1f, %.1f, %.1f) mm, cluster %d, model %d\n", i, d.score,
                t.x(), t.y(), t.z(), d.cluster, d.model_index);
  }
}

int run(const Options& o) {
  // The calibration is checked first: a refused one leaves no results file behind.
  const BaseFrameSource base = baseFrameSource(o);
  if (o.suite.empty()) {
    // Both outputs are checked before the work, so that neither is written when one cannot be.
    core::checkWritable(o.out);
    if (!o.picture.empty())
      core::checkWritable(o.picture);
  }
  const ModelViews loaded = loadModelViews(o.models);
  const core::TaughtModel& first = *loaded.models.front();
  // Without --preset/--params the views' own parameters are used (viewsParams).
  const core::RecognitionParams params = resolveParams(o.recipe, core::viewsParams(loaded.models));
  core::Recognizer recognizer;
  // The views are prepared once, as a cell does when it loads them; the scenes' timings are
  // then their own.
  const auto joined = std::count_if(loaded.models.begin(), loaded.models.end(),
                                    [](const auto& m) { return !m->joined_views.empty(); });
  std::printf("prepared %zu view(s) in %.0f ms", loaded.models.size(),
              core::prepareViews(recognizer, loaded.models, params));
  if (joined > 0)
    std::printf(", %ld of them joined (they know their place in the part)", long(joined));
  std::printf("\n");
  printViewCoverage(core::viewCoverage(loaded.models));
  const auto recognize = [&](const core::PointCloud& scene, const core::SensorModel& sensor) {
    return core::recognizeViews(recognizer, loaded.models, scene, sensor, params);
  };
  const std::string default_sensor = sensorNameFor("", first);
  if (o.suite.empty()) {
    if (o.scene.empty() || o.out.empty())
      throw core::Error("give --scene and --out (or --suite DIR --out RESULTS_DIR)");
    const core::SensorModel sensor =
        core::sensorPreset(o.recipe.sensor.empty() ? default_sensor : o.recipe.sensor);
    const core::PointCloud scene = loadWithUnitsCheck(o.scene, o.recipe.units);
    const auto result = recognize(scene, sensor);
    saveResultsDocument(o.out, resultsDocument(result, loaded, o.scene, base));
    if (!o.picture.empty())
      core::writeOverlayPng(o.picture, scene, loaded.clouds, result.detections, sensor,
                            core::depthOverlayTolerance_mm(params));
    printSummary(o.scene, result);
    return kOk;
  }
  if (!fs::is_directory(o.suite))
    throw core::Error("suite folder '" + o.suite + "' does not exist");
  if (o.out.empty())
    throw core::Error("--out RESULTS_DIR is required with --suite");
  fs::create_directories(o.out);
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(o.suite)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("scene-") && entry.path().extension() == ".pcd")
      scenes.push_back(entry.path());
  }
  std::sort(scenes.begin(), scenes.end());
  if (scenes.empty())
    throw core::Error("suite folder '" + o.suite + "' holds no scene-*.pcd files");
  for (const auto& path : scenes) {
    const auto [preset, kind] = truthInfo(path);
    if (kind == "teach")
      continue; // the scans parts are taught from are not recognition scenes
    const std::string sensor_name =
        !o.recipe.sensor.empty() ? o.recipe.sensor : (!preset.empty() ? preset : default_sensor);
    const core::SensorModel sensor = core::sensorPreset(sensor_name);
    const core::PointCloud scene = loadWithUnitsCheck(path.string(), o.recipe.units);
    const auto result = recognize(scene, sensor);
    const fs::path out = fs::path(o.out) / (path.stem().string() + ".json");
    saveResultsDocument(out, resultsDocument(result, loaded, path.string(), base));
    if (!o.picture.empty())
      core::writeOverlayPng(fs::path(o.out) / (path.stem().string() + ".png"), scene, loaded.clouds,
                            result.detections, sensor, core::depthOverlayTolerance_mm(params));
    printSummary(path.filename().string(), result);
  }
  return kOk;
}

} // namespace

void registerRecognizeCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = addCommand(app, "recognize",
                             "Find a taught part in a scene (or in every scene-*.pcd of a suite)",
                             [o] { return run(*o); });
  sub->add_option("--model", o->models,
                  "Taught model (.spmodel); repeat it for views of one part taught from scans of "
                  "its different sides (each detection names the view that found it)")
      ->required();
  sub->add_option("--scene", o->scene, "Scene scan (.pcd or .ply)");
  sub->add_option("--suite", o->suite, "Folder of scene-XXX.pcd (+ .gt.json) to recognize in turn");
  sub->add_option("--out", o->out, "Results file (or folder with --suite)")->required();
  sub->add_option("--picture", o->picture,
                  "Result picture (PNG): the scan's depth image with each detection tinted in "
                  "its colour, its ID and its grip points, as the GUI's depth view shows it "
                  "(with --suite: any value writes RESULTS_DIR/scene-XXX.png)");
  sub->add_option("--calibration", o->calibration,
                  "Hand-eye calibration file (scanpick-cli calibrate): also write each "
                  "detection's pose and grip points in the robot base frame (\"pose_base\")");
  sub->add_option("--flange-pose", o->flange_pose,
                  "Eye-in-hand: the flange pose at which the scan was taken, in the robot base: "
                  "x,y,z,rx,ry,rz (mm; rotation vector in degrees) or x,y,z,qw,qx,qy,qz");
  o->recipe.add(sub);
}

} // namespace scanpick::cli
