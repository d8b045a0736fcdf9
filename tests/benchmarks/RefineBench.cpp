// Pose refinement timings: a PhoXi-like 640 x 480 crop (f = 1000 px, 0.8 mm between samples at
// 800 mm, 0.1 mm noise, 2 % dropouts) of a bin floor with 12 L-brackets and 3 blocks: 307k
// points, all indexed (floor included, as a scene before floor removal would be). The model is
// the tests' teach view of the bracket (0.5 mm sampling), subsampled to 2000 points. Each
// detection starts 3 mm / 5° off its true pose. Run:
//   bench_refine --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (tools/results.sh puts the medians in docs/results.md). Time is wall time, CPU is the
// whole process's CPU time (all threads).
#include "core/refine/PoseRefinement.h"
#include "tests/unit/refine/BracketScene.h"

#include <benchmark/benchmark.h>
#include <optional>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/search/kdtree.h>
#include <tbb/global_control.h>

using namespace scanpick;

namespace {

struct Data {
  test::TaughtView taught;
  core::PointCloud scene;
  std::vector<Eigen::Isometry3d> truths, starts;
};

const Data& data() {
  static const Data d = [] {
    Data out;
    out.taught = test::teachBracketView();
    std::vector<test::PlacedSolid> solids;
    for (int k = 0; k < 12; ++k) {
      test::PlacedSolid part{test::lBracket(), Eigen::Isometry3d::Identity()};
      part.T_camera_part.linear() =
          test::rotationDeg(30.0 * k, Eigen::Vector3d::UnitZ()) *
          test::rotationDeg(20.0 + 5 * (k % 4), Eigen::Vector3d::UnitY()) *
          test::rotationDeg(180, Eigen::Vector3d::UnitX());
      const Eigen::Vector3d centre(-190 + 125 * (k % 4), -120 + 120 * (k / 4), 780);
      part.T_camera_part.translation() =
          centre - part.T_camera_part.linear() * Eigen::Vector3d(30, 20, 20);
      out.truths.push_back(out.taught.modelPose(part.T_camera_part));
      Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
      delta.linear() = test::rotationDeg(5.0, Eigen::Vector3d(1, k, 2));
      Eigen::Isometry3d start = out.truths.back() * delta;
      start.translation() += 3.0 * Eigen::Vector3d(k % 3 - 1.0, 1, 0.5).normalized();
      out.starts.push_back(start);
      solids.push_back(part);
    }
    for (int k = 0; k < 3; ++k) {
      test::PlacedSolid block{{test::DrilledBox{{0, 0, 0}, {50, 40, 30}}},
                              Eigen::Isometry3d::Identity()};
      block.T_camera_part.linear() = test::rotationDeg(20.0 * k, Eigen::Vector3d::UnitZ());
      block.T_camera_part.translation() = Eigen::Vector3d(-250 + 200 * k, 170, 800);
      solids.push_back(block);
    }
    double floor_z = 0;
    for (const auto& s : solids)
      floor_z = std::max(floor_z, test::deepestZ(s));
    out.scene = test::renderSolids(solids, floor_z + 1.0, 640, 480, 1000, 0.1, 0.02, 7);
    return out;
  }();
  return d;
}

const core::SceneIndex& sceneIndex() {
  static const core::SceneIndex index(data().scene);
  return index;
}

const core::RefineModel& refineModel() {
  static const core::RefineModel model(data().taught.model, core::RefineParams{}.model_points);
  return model;
}

void BM_SceneIndexBuild(benchmark::State& state) {
  const bool organized = state.range(0) != 0;
  const core::PointCloud cloud = organized ? data().scene : core::dropInvalid(data().scene);
  std::size_t points = 0;
  for (auto _ : state)
    points = core::SceneIndex(cloud).size();
  state.counters["points"] = static_cast<double>(points);
}

void BM_RefineModelBuild(benchmark::State& state) {
  std::size_t kept = 0;
  for (auto _ : state)
    kept = core::RefineModel(data().taught.model, 2000).size();
  state.counters["model_points"] = static_cast<double>(data().taught.model.size());
  state.counters["kept"] = static_cast<double>(kept);
}

/// Per detection: cycles through the 12 brackets; counters are the mean errors after refinement.
/// Arg 1: 0 = the machine's threads, 1 = one thread (as when the pipeline refines detections in
/// parallel, one per thread; also the honest CPU cost, without TBB workers spinning).
void BM_RefinePose(benchmark::State& state) {
  const auto& d = data();
  core::RefineParams params;
  params.point_to_plane = state.range(0) != 0;
  std::optional<tbb::global_control> limit;
  if (state.range(1) == 1)
    limit.emplace(tbb::global_control::max_allowed_parallelism, 1);
  double sum_t = 0, sum_r = 0, sum_it = 0, max_t = 0;
  std::size_t runs = 0, converged = 0;
  for (auto _ : state) {
    const std::size_t k = runs % d.truths.size();
    const auto result = core::refinePose(refineModel(), sceneIndex(), d.starts[k], params);
    const auto [t, r] = test::poseError(result.T_scene_model, d.truths[k]);
    sum_t += t, sum_r += r, sum_it += result.iterations, max_t = std::max(max_t, t);
    converged += result.converged ? 1 : 0;
    ++runs;
  }
  state.counters["mean_err_mm"] = sum_t / static_cast<double>(runs);
  state.counters["max_err_mm"] = max_t;
  state.counters["mean_err_deg"] = sum_r / static_cast<double>(runs);
  state.counters["iterations"] = sum_it / static_cast<double>(runs);
  state.counters["converged"] = static_cast<double>(converged) / static_cast<double>(runs);
}

void BM_CoverageScore(benchmark::State& state) {
  const auto& d = data();
  double sum = 0;
  std::size_t runs = 0;
  for (auto _ : state) {
    const std::size_t k = runs++ % d.truths.size();
    sum += core::coverageScore(refineModel(), sceneIndex(), d.truths[k], 1.0);
  }
  state.counters["mean_coverage"] = sum / static_cast<double>(runs);
}

/// PCL's IterativeClosestPointWithNormals (point-to-plane LLS) on the same 2000 model points and
/// the same scene normals, target kd-tree built once; fixed 2 mm pair distance, 30 iterations.
void BM_PclIcpPointToPlane(benchmark::State& state) {
  const auto& d = data();
  using Cloud = pcl::PointCloud<pcl::PointNormal>;
  auto target = std::make_shared<Cloud>();
  const auto& index = sceneIndex();
  for (std::size_t i = 0; i < index.size(); ++i) {
    if (!index.normals()[i].allFinite())
      continue;
    pcl::PointNormal p;
    p.getVector3fMap() = index.points()[i];
    p.getNormalVector3fMap() = index.normals()[i];
    target->push_back(p);
  }
  auto source = std::make_shared<Cloud>();
  for (std::size_t i = 0; i < refineModel().size(); ++i) {
    pcl::PointNormal p;
    p.getVector3fMap() = refineModel().points()[i];
    p.getNormalVector3fMap() = refineModel().normals()[i];
    source->push_back(p);
  }
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointNormal>>();
  tree->setInputCloud(target);
  pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal> icp;
  icp.setInputSource(source);
  icp.setInputTarget(target);
  icp.setSearchMethodTarget(tree, true);
  icp.setMaxCorrespondenceDistance(static_cast<double>(state.range(0)));
  icp.setMaximumIterations(30);
  icp.setTransformationEpsilon(1e-10);
  Cloud aligned;
  double sum_t = 0, sum_r = 0, max_t = 0;
  std::size_t runs = 0;
  for (auto _ : state) {
    const std::size_t k = runs++ % d.truths.size();
    icp.align(aligned, d.starts[k].matrix().cast<float>());
    Eigen::Isometry3d T(icp.getFinalTransformation().cast<double>());
    const auto [t, r] = test::poseError(T, d.truths[k]);
    sum_t += t, sum_r += r, max_t = std::max(max_t, t);
  }
  state.counters["mean_err_mm"] = sum_t / static_cast<double>(runs);
  state.counters["max_err_mm"] = max_t;
  state.counters["mean_err_deg"] = sum_r / static_cast<double>(runs);
}

} // namespace

BENCHMARK(BM_SceneIndexBuild)
    ->Arg(1)
    ->Arg(0)
    ->ArgName("organized")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(5);
BENCHMARK(BM_RefineModelBuild)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(5);
BENCHMARK(BM_RefinePose)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({0, 0})
    ->ArgNames({"point_to_plane", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(48);
BENCHMARK(BM_CoverageScore)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(48);
BENCHMARK(BM_PclIcpPointToPlane)
    ->Arg(2)
    ->Arg(5)
    ->ArgName("max_dist_mm")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(24);

BENCHMARK_MAIN();
