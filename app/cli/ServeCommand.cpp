// scanpick-cli serve: the robot link. A TCP server (docs/robot-link.md) on a camera and one or more
// recipes (docs/grasping.md): trigger, next pick, pick list, set recipe, status.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/ModelViews.h"
#include "app/cli/RecipeOptions.h"
#include "core/calib/BaseFrame.h"
#include "core/common/AtomicFile.h"
#include "core/common/JsonText.h"
#include "core/grasp/GraspJson.h"
#include "core/link/LinkServer.h"
#include "core/link/PlanningCell.h"
#include "core/pipeline/Recognizer.h"

#ifdef SCANPICK_WITH_DEVICES
#include "devices/CameraRegistry.h"
#include "devices/file/FileCamera.h"
#endif

#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <set>

namespace scanpick::cli {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct Options {
  std::vector<std::string> recipes;
  std::string camera;
  std::string calibration; ///< hand-eye calibration: picks also in the robot base frame
  std::string host = "0.0.0.0";
  int port = 50020;
  int max_clients = 32;
  int idle_timeout_s = 600;
  int capture_timeout_ms = 5000;
};

core::link::LinkServer* g_server = nullptr; ///< for the signal handler

extern "C" void onSignal(int) {
  if (g_server != nullptr)
    g_server->stop(); // async-signal-safe
}

Eigen::Isometry3d poseFromJson(const json& j, const std::string& what) {
  if (!j.is_object() || !j.contains("position_mm") || !j.contains("quaternion_wxyz") ||
      !j["position_mm"].is_array() || !j["quaternion_wxyz"].is_array() ||
      j["position_mm"].size() != 3 || j["quaternion_wxyz"].size() != 4)
    throw core::Error(what + " must be {\"position_mm\": [x, y, z], \"quaternion_wxyz\": [w, x, "
                             "y, z]}");
  try {
    const auto& p = j["position_mm"];
    const auto& q = j["quaternion_wxyz"];
    return core::partPose(
        Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()),
        Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(),
                           q[3].get<double>()));
  } catch (const json::exception&) {
    throw core::Error(what + ": positions and quaternion components must be numbers");
  }
}

/// Loads a recipe file (docs/grasping.md, "Recipes") into a cell recipe whose detector runs the
/// recognizer on its models.
core::link::CellRecipe loadRecipe(const std::string& path) {
  const fs::path file(path);
  const json doc = core::parseJsonText(core::readFile(file), path, ": see docs/grasping.md");
  if (!doc.is_object())
    throw core::Error(path + ": a recipe is a JSON object (docs/grasping.md)");
  static const std::set<std::string> kKeys = {"format", "version",  "name",   "models",
                                              "preset", "set",      "sensor", "gripper",
                                              "grasps", "planning", "bin",    "robot_from_camera"};
  for (const auto& item : doc.items())
    if (!kKeys.contains(item.key()))
      throw core::Error(path + ": unknown key '" + item.key() + "' (see docs/grasping.md)");
  if (doc.value("format", std::string()) != "scanpick-recipe")
    throw core::Error(path + ": not a scanpick recipe (\"format\": \"scanpick-recipe\" missing)");
  if (!doc.contains("version") || !doc["version"].is_number_integer() ||
      doc["version"].get<int>() != 1)
    throw core::Error(path + ": recipe version must be 1: this scanpick reads version 1 only");
  if (!doc.contains("models") || !doc["models"].is_array() || doc["models"].empty())
    throw core::Error(path + ": \"models\" must list at least one .spmodel file");
  std::vector<std::string> model_paths;
  for (const auto& m : doc["models"]) {
    if (!m.is_string())
      throw core::Error(path + ": \"models\" entries are file names");
    const fs::path p(m.get<std::string>());
    model_paths.push_back((p.is_absolute() ? p : file.parent_path() / p).string());
  }
  auto views = std::make_shared<ModelViews>(loadModelViews(model_paths));
  const core::TaughtModel& first = *views->models.front();

  RecipeOptions options;
  if (doc.contains("preset")) {
    if (!doc["preset"].is_string())
      throw core::Error(path + ": \"preset\" is a preset name or file");
    options.preset = doc["preset"].get<std::string>();
  }
  core::RecognitionParams params = resolveParams(options, core::viewsParams(views->models));
  if (doc.contains("set"))
    params = core::paramsFromJson(doc["set"], params);
  std::string sensor_name;
  if (doc.contains("sensor") && doc["sensor"].is_string())
    sensor_name = doc["sensor"].get<std::string>();
  const core::SensorModel sensor = core::sensorPreset(sensorNameFor(sensor_name, first));

  core::link::CellRecipe recipe;
  recipe.name = doc.value("name", file.stem().string());
  if (doc.contains("gripper"))
    recipe.gripper = core::grasp::gripperFromJson(doc["gripper"]);
  std::vector<core::grasp::GraspSpec> specs;
  if (doc.contains("grasps"))
    specs = core::grasp::graspSpecsFromJson(doc["grasps"]);
  if (doc.contains("planning"))
    recipe.planning = core::grasp::planParamsFromJson(doc["planning"]);
  if (!doc.contains("bin") || !doc["bin"].is_boolean() || doc["bin"].get<bool>()) {
    core::grasp::BinEstimateParams bin;
    bin.up = recipe.planning.up;
    if (doc.contains("bin") && doc["bin"].is_object())
      bin = core::grasp::binParamsFromJson(doc["bin"], bin);
    recipe.bin = bin;
  }
  if (doc.contains("robot_from_camera"))
    recipe.T_robot_scene = poseFromJson(doc["robot_from_camera"], path + ": robot_from_camera");
  for (const auto& model : views->models) {
    core::grasp::GraspModel gm;
    gm.cloud_mm = model->cloud_mm;
    gm.grasps = core::grasp::graspPoints(model->grip_points, specs);
    recipe.models.push_back(std::move(gm));
  }
  auto recognizer = std::make_shared<core::Recognizer>();
  core::prepareViews(*recognizer, views->models, params);
  recipe.detect = [views, recognizer, sensor, params](const core::PointCloud& scene) {
    return core::recognizeViews(*recognizer, views->models, scene, sensor, params).detections;
  };
  std::printf("recipe '%s': %zu view(s) of '%s', %s gripper, %zu grasp point(s) per view, bin %s\n",
              recipe.name.c_str(), views->models.size(), first.name.c_str(),
              core::grasp::toString(recipe.gripper.kind), recipe.models.front().grasps.size(),
              recipe.bin ? "estimated from each scan" : "not checked");
  return recipe;
}

#ifdef SCANPICK_WITH_DEVICES
core::link::SceneSource openSource(const std::string& id, int timeout_ms) {
  std::shared_ptr<devices::Camera> camera;
  if (id.starts_with("file:")) // a replayed cell keeps cycling through its files
    camera = std::make_shared<devices::FileCamera>(id.substr(5), true);
  else
    camera = devices::openCamera(id);
  return
      [camera, timeout_ms] { return camera->capture(std::chrono::milliseconds(timeout_ms)).cloud; };
}
#endif

int run(const Options& o) {
#ifndef SCANPICK_WITH_DEVICES
  (void)o;
  throw core::Error("this scanpick-cli was built without the devices layer: no camera to serve");
#else
  // The calibration first: a refused one fails before the recipes' models are prepared.
  std::optional<core::calib::CameraCalibration> calibration;
  if (!o.calibration.empty())
    calibration = core::calib::loadCameraCalibration(o.calibration);
  std::vector<core::link::CellRecipe> recipes;
  std::set<std::string> names;
  for (const auto& r : o.recipes) {
    recipes.push_back(loadRecipe(r));
    if (!names.insert(recipes.back().name).second)
      throw core::Error("two recipes are named '" + recipes.back().name +
                        "': give each a distinct \"name\"");
  }
  auto cell = std::make_shared<core::link::PlanningCell>(openSource(o.camera, o.capture_timeout_ms),
                                                         std::move(recipes), calibration);
  if (calibration)
    std::printf("calibration %s (%s): picks also in the robot base frame%s\n",
                calibration->file.c_str(), core::calib::modeName(calibration->mode).c_str(),
                calibration->needsFlangePose() ? "; triggers must carry the flange pose" : "");
  core::link::ServerOptions options;
  options.host = o.host;
  options.port = o.port;
  options.max_clients = o.max_clients;
  options.idle_timeout_ms = o.idle_timeout_s * 1000;
  core::link::LinkServer server(std::make_shared<core::link::CellService>(cell), options);
  server.listen();
  g_server = &server;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  std::printf("serving on %s:%d (camera %s); JSON lines or binary messages, see "
              "docs/robot-link.md; Ctrl+C stops\n",
              o.host.c_str(), server.port(), o.camera.c_str());
  std::fflush(stdout);
  server.run();
  g_server = nullptr;
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  const auto s = server.stats();
  std::printf("stopped: %llu connection(s), %llu request(s), %llu error answer(s), %llu busy\n",
              static_cast<unsigned long long>(s.accepted),
              static_cast<unsigned long long>(s.requests),
              static_cast<unsigned long long>(s.errors), static_cast<unsigned long long>(s.busy));
  return kOk;
#endif
}

} // namespace

void registerServeCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = addCommand(app, "serve",
                             "Robot link: a TCP server that captures, recognizes and plans picks "
                             "on request (docs/robot-link.md)",
                             [o] { return run(*o); });
  sub->add_option("--recipe", o->recipes,
                  "Recipe file (docs/grasping.md); repeat it for recipes a robot can switch "
                  "between (binary set-recipe index = order given)")
      ->required();
  sub->add_option("--camera", o->camera,
                  "Camera id: phoxi:<serial|ip>, kinect:<index>, oni:<file.oni>, file:<cloud or "
                  "folder> (replayed in a loop)")
      ->required();
  sub->add_option("--calibration", o->calibration,
                  "Hand-eye calibration file (scanpick-cli calibrate): picks also in the robot "
                  "base frame (eye-in-hand: each trigger carries the flange pose)");
  sub->add_option("--host", o->host, "IPv4 address to listen on (127.0.0.1: this machine only)")
      ->capture_default_str();
  sub->add_option("--port", o->port, "TCP port (0: any free port, printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  sub->add_option("--max-clients", o->max_clients, "Clients served at once; more are refused")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--idle-timeout-s", o->idle_timeout_s,
                  "Close a client that sends nothing this long (seconds)")
      ->check(CLI::Range(1, 86400 * 7))
      ->capture_default_str();
  sub->add_option("--capture-timeout-ms", o->capture_timeout_ms, "Longest wait for a frame")
      ->check(CLI::Range(1, 3600000))
      ->capture_default_str();
}

} // namespace scanpick::cli
