// peers_bench: runs a peer recognizer (OpenCV's PPF detector or PCL's correspondence grouping) on
// the scenes of a suite folder with scanpick's taught views as models, and writes one scanpick
// results file per scene, so that `scanpick-cli eval` scores the peer as it scores scanpick
// (docs/peers.md, written by tools/peers.sh). Not part of the product.
//
//   peers_bench --method opencv-ppf|pcl-cg --model VIEW.spmodel [--model ...] --suite DIR
//               --out RESULTS_DIR [--min-score S]
//
// Each scene's time (timings_ms.total) covers what happens after the scan is loaded: the shared
// preparation (PeerCommon.h), the method's matching and ICP, and the shared scoring; the models
// are trained once per run, as scanpick prepares its views once.
#include "PeerCommon.h"
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/output/ResultsJson.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <pcl/console/print.h>

namespace fs = std::filesystem;
using namespace scanpick;

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// The scene-*.pcd files of `suite` that are recognition scenes (their ground truth, when
/// present, does not mark them as teach scans), sorted.
std::vector<fs::path> sceneFiles(const fs::path& suite) {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(suite)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("scene-") || entry.path().extension() != ".pcd")
      continue;
    const fs::path gt = suite / (entry.path().stem().string() + ".gt.json");
    if (fs::exists(gt)) {
      const nlohmann::json doc = core::parseJsonText(core::readFile(gt), gt.string(), "");
      if (doc.contains("scene") && doc["scene"].is_object() &&
          doc["scene"].value("kind", std::string()) == "teach")
        continue;
    }
    scenes.push_back(entry.path());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

struct Options {
  std::string method, suite, out;
  std::vector<std::string> models;
  double min_score = 0.3;
  peers::OpenCvPpfOptions ppf;
};

int run(const Options& o) {
  std::unique_ptr<peers::PeerMethod> method;
  if (o.method == "opencv-ppf")
    method = peers::makeOpenCvPpf(o.ppf);
  else if (o.method == "pcl-cg")
    method = peers::makePclGrouping();
  else
    throw core::Error("--method must be opencv-ppf or pcl-cg, not '" + o.method + "'");

  std::vector<core::TaughtModel> storage;
  peers::PeerSettings settings;
  const std::vector<peers::PeerModel> models = peers::loadPeerModels(o.models, storage, settings);
  const auto train_start = Clock::now();
  method->train(models, settings);
  std::printf("%s: trained %zu view(s) in %.0f ms; spacing %.3f mm, diameter %.1f mm, voxel %.3f "
              "mm\n  %s\n",
              o.method.c_str(), models.size(), msSince(train_start), settings.spacing_mm,
              settings.diameter_mm, settings.voxel_mm, method->describe().c_str());
  std::vector<core::ModelSource> sources;
  for (const auto& m : models)
    sources.push_back({m.taught, m.path});

  fs::create_directories(o.out);
  const auto scenes = sceneFiles(o.suite);
  if (scenes.empty())
    throw core::Error("suite folder '" + o.suite + "' holds no scene-*.pcd files");
  for (const auto& path : scenes) {
    const core::PointCloud cloud = core::loadCloud(path, core::LengthUnit::Millimetres).cloud;
    const auto start = Clock::now();
    const peers::PeerScene scene = peers::prepareScene(cloud, *models.front().taught, settings);
    const double prepare_ms = msSince(start);
    const peers::MethodOutput output = method->detect(scene);
    const auto detections =
        peers::scoreAndSuppress(output.hypotheses, models, scene, settings, o.min_score);

    core::RecognitionResult result;
    for (const auto& d : detections) {
      core::Detection detection;
      detection.T_scene_model = d.hypothesis.T_scene_model;
      detection.score = std::clamp(d.score, 0.0, 1.0);
      detection.coverage = detection.score;
      detection.refined = true;
      detection.model_index = int(d.hypothesis.view);
      detection.centre_mm = d.hypothesis.T_scene_model.translation();
      result.detections.push_back(std::move(detection));
    }
    result.timings.preprocess_ms = prepare_ms;
    result.timings.matching_ms = output.matching_ms;
    result.timings.refine_ms = output.refine_ms;
    result.timings.total_ms = msSince(start);
    core::saveResults(fs::path(o.out) / (path.stem().string() + ".json"), result, sources,
                      path.string());
    std::printf("%s: %zu detection(s) of %zu hypotheses in %.0f ms (prepare %.0f, matching %.0f, "
                "ICP %.0f; %zu scene points)\n",
                path.filename().c_str(), detections.size(), output.hypotheses.size(),
                result.timings.total_ms, prepare_ms, output.matching_ms, output.refine_ms,
                scene.points->size());
    std::fflush(stdout);
  }
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  pcl::console::setVerbosityLevel(pcl::console::L_ERROR);
  CLI::App app{"Peer recognizers on a scanpick suite, written as scanpick results files"};
  Options o;
  app.add_option("--method", o.method, "opencv-ppf or pcl-cg")->required();
  app.add_option("--model", o.models, "Taught view (.spmodel), repeatable")->required();
  app.add_option("--suite", o.suite, "Folder of scene-XXX.pcd (+ .gt.json)")->required();
  app.add_option("--out", o.out, "Folder for the results files scene-XXX.json")->required();
  app.add_option("--min-score", o.min_score,
                 "Detections confirming less than this share of the view's points facing the "
                 "camera are dropped")
      ->capture_default_str();
  app.add_option("--ppf-scene-sample-step", o.ppf.scene_sample_step,
                 "opencv-ppf: share of the sampled scene points used as references")
      ->capture_default_str();
  app.add_option("--ppf-scene-distance", o.ppf.scene_distance,
                 "opencv-ppf: scene sampling step, times the model's diameter")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peers_bench: error: %s\n", e.what());
    return 1;
  }
}
