// Surface point pair voting (core/matching/PointPairVoting.h) on simulated PhoXi M (1032 x 772)
// scans of the cup: the model from its teach scan lying on its side (as the suite's cup-side2),
// the scene a bin of 10 cups; both cut to the cups' own pixels (the simulator's labels stand in
// for floor removal), normals as the recognizer estimates them, sampled at 6 mm. Run:
//   bench_voting --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// (tools/results.sh puts the medians in docs/results.md).
#include "core/matching/PointPairVoting.h"
#include "core/refine/SceneIndex.h"
#include "core/sim/Synth.h"

#include <benchmark/benchmark.h>

using namespace scanpick;

namespace {

constexpr double kSamplingMm = 6.0;

/// The pixels of `synth` that show a part, with normals, sampled as surface voting samples them.
core::OrientedPoints partSurface(const core::SynthScene& synth) {
  core::PointCloud parts = synth.render.cloud;
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (synth.render.labels[i] < 0)
      parts.points_mm[i] = core::invalidPoint();
  const core::SceneIndex index(parts); // the camera at the origin, as in a scene
  return core::sampleOriented(index.points(), index.normals(), kSamplingMm);
}

struct Data {
  core::OrientedPoints model, scene;
};

const Data& data() {
  static const Data d = [] {
    core::SynthRequest teach;
    teach.parts = {"cup"};
    teach.layout = core::LayoutKind::Teach;
    teach.count = 1;
    teach.teach_side = 2;
    core::SynthRequest bin;
    bin.parts = {"cup"};
    bin.count = 10;
    bin.seed = 13;
    return Data{partSurface(core::synthesize(teach)), partSurface(core::synthesize(bin))};
  }();
  return d;
}

void BM_PairTable(benchmark::State& state) {
  const auto& d = data();
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = core::PointPairModel(d.model, kSamplingMm).pairCount();
  state.counters["model_points"] = double(d.model.points.size());
  state.counters["pairs"] = double(pairs);
}

/// Scene voting: every 16th scene point a reference (Arg 16), or every second (Arg 2); 30
/// poses.
void BM_SceneVote(benchmark::State& state) {
  const auto& d = data();
  const core::PointPairModel model(d.model, kSamplingMm);
  core::VotingOptions options;
  options.reference_stride = static_cast<int>(state.range(0));
  options.max_poses = 30;
  options.cluster_distance_mm = 0.1 * model.diameter();
  int best = 0;
  for (auto _ : state)
    best = model.vote(d.scene, options).front().votes;
  state.counters["scene_points"] = double(d.scene.points.size());
  state.counters["best_votes"] = best;
}

/// A view voting against itself, its neighbourhood left out (the near-symmetry search).
void BM_SelfVote(benchmark::State& state) {
  const auto& d = data();
  const core::PointPairModel model(d.model, kSamplingMm);
  core::VotingOptions options;
  options.reference_stride = 1;
  options.max_poses = 12;
  options.cluster_distance_mm = 0.1 * model.diameter();
  options.exclude_self_mm = 0.1 * model.diameter();
  int best = 0;
  for (auto _ : state)
    best = model.vote(d.model, options).front().votes;
  state.counters["best_votes"] = best;
}

} // namespace

BENCHMARK(BM_PairTable)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_SceneVote)
    ->Arg(16)
    ->Arg(2)
    ->ArgName("stride")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(BM_SelfVote)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
