// Timings of the scene stages on a PhoXi M (1032 x 772) sized synthetic scan: a floor at 800 mm
// with 10 boxes and cylinders, projector shadows, 0.1 mm noise. Run:
//   bench_core_stages --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (tools/results.sh puts the medians in docs/results.md).
#include "core/features/FeatureExtraction.h"
#include "core/keypoints/Keypoints.h"
#include "core/params/ParamsJson.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/preprocess/ObjectCount.h"
#include "core/preprocess/SceneSplit.h"
#include "tests/support/RaycastScene.h"

#include <benchmark/benchmark.h>
#include <filesystem>

using namespace scanpick;

namespace {

struct Data {
  core::SensorModel sensor = core::sensorPreset("phoxi-m-1032");
  core::RecognitionParams params;
  core::PointCloud scene, remaining;
  core::SceneSplit split;
  std::vector<core::Keypoints> object_keypoints;
  core::Keypoints scene_keypoints; ///< of the whole scan as one object (parts that touch)
};

const Data& data() {
  static const Data d = [] {
    Data out;
    test::RaycastScene scene;
    scene.floor_z_mm = 800;
    // A 4 x 3 layout (10 parts, 130-170 mm) filling about half of the ~840 x 630 mm field of
    // view at 800 mm, so that ~350k points remain after floor removal as in a full bin.
    int placed = 0;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 4 && placed < 10; ++col, ++placed) {
        const double x = -310 + 205 * col, y = -200 + 200 * row, s = 130 + 13 * (placed % 4);
        const double h = 30 + 7 * (placed % 5);
        if (placed % 3 == 2)
          scene.cylinders.push_back({Eigen::Vector2d(x, y), s / 2, 800 - h, 800});
        else
          scene.boxes.emplace_back(Eigen::Vector3d(x - s / 2, y - s * 0.4, 800 - h),
                                   Eigen::Vector3d(x + s / 2, y + s * 0.4, 800));
      }
    const auto& sensor = out.sensor;
    out.scene = scene.render(sensor.width, sensor.height, sensor.fx, sensor.projectorPosition(),
                             sensor.noise_sigma_mm, 1);
    out.remaining = core::removeFloor(out.scene, out.params.floor, out.params.seed).remaining;
    out.split =
        core::splitIntoObjects(out.remaining, sensor, out.params.clustering, out.params.seed);
    for (const auto& object : out.split.objects)
      out.object_keypoints.push_back(core::extractKeypoints(object, out.params.keypoints));
    out.scene_keypoints = core::extractKeypoints(out.remaining, out.params.keypoints);
    return out;
  }();
  return d;
}

void BM_FloorRemoval(benchmark::State& state) {
  const auto& d = data();
  std::size_t removed = 0;
  for (auto _ : state)
    removed = core::removeFloor(d.scene, d.params.floor, d.params.seed).removed_points;
  state.counters["scene_points"] = static_cast<double>(d.scene.validCount());
  state.counters["removed"] = static_cast<double>(removed);
}

void BM_ObjectCount(benchmark::State& state) {
  const auto& d = data();
  int count = 0;
  for (auto _ : state)
    count = core::countObjects(d.remaining, d.sensor, d.params.clustering).count;
  state.counters["points"] = static_cast<double>(d.remaining.validCount());
  state.counters["objects"] = count;
}

void BM_SceneSplit(benchmark::State& state) {
  const auto& d = data();
  auto params = d.params.clustering;
  params.method = static_cast<core::ClusteringParams::Method>(state.range(0));
  std::size_t objects = 0;
  int runs = 0;
  for (auto _ : state) {
    const auto split = core::splitIntoObjects(d.remaining, d.sensor, params, d.params.seed);
    objects = split.objects.size();
    runs = split.kmeans_runs;
  }
  state.counters["objects"] = static_cast<double>(objects);
  state.counters["kmeans_runs"] = runs;
}

void BM_Keypoints(benchmark::State& state) {
  const auto& d = data();
  auto params = d.params.keypoints;
  params.method = static_cast<core::KeypointParams::Method>(state.range(0));
  std::size_t count = 0;
  for (auto _ : state)
    count = core::extractKeypoints(d.remaining, params).points_mm.size();
  state.counters["points"] = static_cast<double>(d.remaining.validCount());
  state.counters["keypoints"] = static_cast<double>(count);
}

void BM_Features(benchmark::State& state) {
  const auto& d = data();
  auto params = d.params.features;
  params.estimator = static_cast<core::FeatureParams::Estimator>(state.range(0));
  std::size_t lines = 0, circles = 0, keypoints = 0;
  for (auto _ : state) {
    lines = circles = keypoints = 0;
    for (const auto& k : d.object_keypoints) {
      keypoints += k.points_mm.size();
      for (const auto& f : core::extractFeatures(k.points_mm, params, d.params.seed).features)
        (f.type == core::FeatureType::Line ? lines : circles)++;
    }
  }
  state.counters["objects"] = static_cast<double>(d.object_keypoints.size());
  state.counters["keypoints"] = static_cast<double>(keypoints);
  state.counters["lines"] = static_cast<double>(lines);
  state.counters["circles"] = static_cast<double>(circles);
}

/// Parts that touch make one object of the whole bin: its rounds of RANSAC follow each other.
void BM_FeaturesOneObject(benchmark::State& state) {
  const auto& d = data();
  const core::FeatureParams params = core::loadPreset(std::filesystem::path(SCANPICK_SOURCE_DIR) /
                                                      "resources/presets/phoxi-bin.json")
                                         .params.features;
  std::size_t features = 0;
  for (auto _ : state)
    features =
        core::extractFeatures(d.scene_keypoints.points_mm, params, d.params.seed).features.size();
  state.counters["keypoints"] = static_cast<double>(d.scene_keypoints.points_mm.size());
  state.counters["features"] = static_cast<double>(features);
}

} // namespace

BENCHMARK(BM_FloorRemoval)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_ObjectCount)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_SceneSplit)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("method")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_Keypoints)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("method")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_Features)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("estimator")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_FeaturesOneObject)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
