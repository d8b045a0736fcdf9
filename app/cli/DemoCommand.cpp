// scanpick-cli demo: the README's main job. Writes the demo scenes (a simulated PhoXi bin of
// supports and the support's teach scan, with ground truth), teaches the support from its teach
// scans on two sides (crop boxes from the ground truth, floor removed), recognizes it in the bin
// with both views and writes the
// results JSON and the overlay picture.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/RecipeOptions.h"
#include "app/cli/TeachTruth.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/model/ModelFile.h"
#include "core/output/OverlayPicture.h"
#include "core/output/ResultsJson.h"
#include "core/pipeline/Recognizer.h"
#include "core/sim/Suite.h"

#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

namespace scanpick::cli {
namespace {
namespace fs = std::filesystem;

struct DemoOptions {
  std::string out;
  std::string preset = "phoxi-bin";
};

int runDemo(const DemoOptions& o) {
  if (o.out.empty())
    throw core::Error("--out DIR is required");
  const fs::path dir(o.out);
  // The preset first, so a wrong name fails before any work is done.
  const core::RecognitionParams params = core::loadPreset(findPreset(o.preset)).params;
  std::cout << "1/3 simulating the demo scenes (PhoXi M, 8 supports in a bin; one support on a "
               "table, on two sides)\n";
  for (const auto& f : core::writeDemoScenes(dir))
    std::cout << "    wrote " << f.string() << "\n";

  const core::SensorModel sensor = core::sensorPreset("phoxi-m-1032");
  // Two views: the support as it rests in the bin (on both legs, the main model the desktop
  // application opens) and as it lies on the table; one scan shows one side only.
  std::cout
      << "2/3 teaching the support from support-teach-side1.pcd and support-teach.pcd (preset "
      << o.preset << ")\n";
  std::vector<std::shared_ptr<const core::TaughtModel>> models;
  std::vector<core::ModelSource> sources;
  std::vector<const core::PointCloud*> clouds;
  const std::pair<const char*, const char*> views[] = {{"support-teach-side1", "support.spmodel"},
                                                       {"support-teach", "support-table.spmodel"}};
  std::vector<std::string> model_paths;
  for (const auto& [scan_name, model_name] : views) {
    core::TeachOptions teach;
    teach.name = "support";
    teach.remove_floor = true;
    teach.sensor = sensor;
    teachOptionsFromTruth(dir / (std::string(scan_name) + ".gt.json"), teach);
    const fs::path scan_path = dir / (std::string(scan_name) + ".pcd");
    const core::PointCloud teach_scan =
        core::loadCloud(scan_path.string(), core::LengthUnit::Millimetres).cloud;
    core::TaughtModel taught = core::teach(teach_scan, teach, params);
    taught.teach_scan = scan_path.filename().string();
    auto model = std::make_shared<const core::TaughtModel>(std::move(taught));
    const fs::path model_path = dir / model_name;
    core::saveModel(model_path, *model);
    std::printf("    %zu points, %zu keypoints, %zu features, %zu grip points -> %s\n",
                model->cloud_mm.size(), model->keypoints_mm.size(), model->features.size(),
                model->grip_points.size(), model_path.string().c_str());
    model_paths.push_back(model_path.string());
    models.push_back(model);
  }
  for (std::size_t m = 0; m < models.size(); ++m) {
    sources.push_back({models[m].get(), model_paths[m]});
    clouds.push_back(&models[m]->cloud_mm);
  }

  std::cout << "3/3 recognizing the support in demo-bin.pcd\n";
  const fs::path scene_path = dir / "demo-bin.pcd";
  const core::PointCloud scene =
      core::loadCloud(scene_path.string(), core::LengthUnit::Millimetres).cloud;
  core::Recognizer recognizer;
  std::printf("    %zu view(s) prepared in %.0f ms\n", models.size(),
              core::prepareViews(recognizer, models, params));
  const core::RecognitionResult result =
      core::recognizeViews(recognizer, models, scene, sensor, params);
  const fs::path results_path = dir / "demo-results.json";
  const fs::path picture_path = dir / "demo-overlay.png";
  core::saveResults(results_path, result, sources, scene_path.string());
  core::writeOverlayPng(picture_path, scene, clouds, result.detections, sensor,
                        core::depthOverlayTolerance_mm(params));
  std::printf("    %zu detection(s) in %.0f ms\n", result.detections.size(),
              result.timings.total_ms);
  for (std::size_t i = 0; i < result.detections.size(); ++i) {
    const core::Detection& d = result.detections[i];
    const Eigen::Vector3d t = d.T_scene_model.translation();
    std::printf("    #%zu score %.3f at (%.1f, %.1f, %.1f) mm\n", i + 1, d.score, t.x(), t.y(),
                t.z());
  }
  std::cout << "results: " << results_path.string() << "\npicture: " << picture_path.string()
            << " (depth image, detections in their colours with IDs and grip points)\n"
            << "desktop application: scanpick --scan " << scene_path.string();
  for (const auto& path : model_paths)
    std::cout << " --model " << path;
  std::cout << " --recognize\n";
  if (result.detections.empty())
    throw core::Error("the demo found no support in the bin: the build or the preset '" + o.preset +
                      "' is broken (run ./cmake/setup.sh test)");
  return kOk;
}

} // namespace

void registerDemoCommand(CLI::App& app) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* demo = addCommand(
      app, "demo",
      "The main job on the bundled demo: simulate a PhoXi scan of 8 supports in a bin and the "
      "support's teach scans on two sides, teach a view from each, recognize the support in the "
      "bin, write support.spmodel (resting on its legs), support-table.spmodel, "
      "demo-results.json and demo-overlay.png.",
      [o] { return runDemo(*o); });
  demo->add_option("--out", o->out, "output folder")->required();
  demo->add_option("--preset", o->preset, "parameter preset (name in resources/presets or file)")
      ->capture_default_str();
}

} // namespace scanpick::cli
