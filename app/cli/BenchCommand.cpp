// scanpick-cli bench: time recognition of one scene (per stage, several cold runs, or runs after a
// warm-up scene as a running cell sees them). Wall and process CPU time are both reported, since
// the machine may be shared.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/ModelViews.h"
#include "app/cli/RecipeOptions.h"
#include "core/model/ModelFile.h"
#include "core/pipeline/Recognizer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <sys/resource.h>
#include <thread>

namespace scanpick::cli {
namespace {

/// User + system CPU time of the whole process (all threads), milliseconds.
double processCpuMs() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) / 1e3; };
  return ms(usage.ru_utime) + ms(usage.ru_stime);
}

double median(std::vector<double> v) {
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Options {
  RecipeOptions recipe;
  std::vector<std::string> models;
  std::string scene;
  std::string warm_up;
  bool prepare = false;
  int runs = 5;
};

int run(const Options& o) {
  if (o.runs < 1)
    throw core::Error("--runs must be at least 1");
  const ModelViews views = loadModelViews(o.models);
  const auto& model = views.models.front();
  const core::RecognitionParams params = resolveParams(o.recipe, model->params);
  const core::SensorModel sensor = core::sensorPreset(sensorNameFor(o.recipe.sensor, *model));
  const core::PointCloud scene = loadWithUnitsCheck(o.scene, o.recipe.units);
  std::optional<core::PointCloud> warm_up;
  if (!o.warm_up.empty())
    warm_up = loadWithUnitsCheck(o.warm_up, o.recipe.units);
  std::printf("bench: %s (%u x %u, %zu valid points), model '%s' (%zu view(s), %zu features in the "
              "first), %d %s runs, %u hardware threads\n",
              o.scene.c_str(), scene.width, scene.height, scene.validCount(), model->name.c_str(),
              views.models.size(), model->features.size(), o.runs, warm_up ? "warm" : "cold",
              std::thread::hardware_concurrency());
  if (warm_up)
    std::printf("warm-up: each run's recognizer first recognizes %s (untimed), so its views are "
                "prepared; every scene stage is then timed anew\n",
                o.warm_up.c_str());
  if (o.prepare)
    std::printf("prepare: each run's recognizer first prepares the views (timed on its own line), "
                "as a cell does when it loads them\n");
  std::vector<double> prep, pre, clu, key, fea, mat, ref, total, cpu, wall;
  std::size_t detections = 0;
  for (int r = 0; r < o.runs; ++r) {
    core::Recognizer recognizer; // a fresh recognizer: nothing served from the cache
    if (warm_up)
      core::recognizeViews(recognizer, views.models, *warm_up, sensor, params);
    if (o.prepare)
      prep.push_back(core::prepareViews(recognizer, views.models, params));
    const double cpu0 = processCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    const auto result = core::recognizeViews(recognizer, views.models, scene, sensor, params);
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(processCpuMs() - cpu0);
    const auto& t = result.timings;
    pre.push_back(t.preprocess_ms);
    clu.push_back(t.clustering_ms);
    key.push_back(t.keypoints_ms);
    fea.push_back(t.features_ms);
    mat.push_back(t.matching_ms);
    ref.push_back(t.refine_ms);
    total.push_back(t.total_ms);
    detections = result.detections.size();
    if (r == 0 && result.scene) {
      const core::SceneAnalysis& analysis = *result.scene;
      std::size_t keypoints = 0, features = 0;
      for (const auto& k : *analysis.keypoints)
        keypoints += k.points_mm.size();
      for (const auto& f : *analysis.features)
        features += f.size();
      std::printf("%zu object(s) after the split, %zu keypoints, %zu features; largest object %zu "
                  "keypoints\n",
                  analysis.objects->size(), keypoints, features,
                  analysis.keypoints->empty()
                      ? std::size_t{0}
                      : std::max_element(analysis.keypoints->begin(), analysis.keypoints->end(),
                                         [](const auto& a, const auto& b) {
                                           return a.points_mm.size() < b.points_mm.size();
                                         })
                            ->points_mm.size());
    }
  }
  std::printf("| stage | median wall (ms) |\n|---|---|\n");
  if (o.prepare)
    std::printf("| view preparation (once per model, not in the total) | %.1f |\n", median(prep));
  std::printf("| preprocess (floor, downsample) | %.1f |\n", median(pre));
  std::printf("| clustering (object count + split) | %.1f |\n", median(clu));
  std::printf("| keypoints | %.1f |\n", median(key));
  std::printf("| features | %.1f |\n", median(fea));
  std::printf("| matching (+ verification) | %.1f |\n", median(mat));
  std::printf("| refinement (ICP) | %.1f |\n", median(ref));
  std::printf("| total | %.1f |\n", median(total));
  std::printf(
      "process CPU time per run (user + system, all threads): median %.1f ms; wall %.1f ms; "
      "%zu detection(s)\n",
      median(cpu), median(wall), detections);
  return kOk;
}

} // namespace

void registerBenchCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = addCommand(app, "bench",
                             "Time recognition of one scene per stage (median of cold runs, or "
                             "of runs after a warm-up scene)",
                             [o] { return run(*o); });
  sub->add_option("--model", o->models, "Taught model (.spmodel); repeat it for views of one part")
      ->required();
  sub->add_option("--scene", o->scene, "Scene scan (.pcd or .ply)")->required();
  sub->add_option("--runs", o->runs, "Runs (a fresh recognizer each)")->capture_default_str();
  sub->add_option("--warm-up", o->warm_up,
                  "Another scene each run's recognizer recognizes first, untimed: the views are "
                  "then prepared (their surface pairs and near symmetries), as in a cell that "
                  "has recognized a scene before; the scene stages still run anew");
  sub->add_flag("--prepare", o->prepare,
                "Each run's recognizer first prepares the views, as a cell does when it loads "
                "them; the preparation is timed on its own line, the scene stages as before");
  o->recipe.add(sub);
}

} // namespace scanpick::cli
