// Surface point pair voting beyond the thesis (matching.surface_sampling_mm): in a bin of
// supports it finds instances the line and circle pairs miss, without false detections, and the
// same input gives the same output. In a bin of pump-connectors, the views taught from the side
// report their free turn about the pipe axis.
#include "core/pipeline/Recognizer.h"
#include "tests/integration/SynthTeach.h"

#include <cstdio>
#include <gtest/gtest.h>
#include <set>

using namespace scanpick;
using namespace scanpick::core;

namespace {

/// The instances found (true positives within 0.1 x diameter), failing on any false detection.
/// Detection::model_index names the view whose model found it.
std::set<int> foundInstances(const RecognitionResult& result,
                             const std::vector<test::SynthTeach>& views, const Scene& scene,
                             const char* label) {
  const double diameter = scene.parts.at(0).diameter_mm();
  std::set<int> found;
  for (const auto& d : result.detections) {
    const auto& view = views.at(static_cast<std::size_t>(d.model_index));
    const test::NearestInstance nearest = test::nearestInstance(d, view, scene);
    std::printf("%s: score %.3f, view %d, cluster %d, refined %d: instance %d at %.2f mm\n", label,
                d.score, d.model_index, d.cluster, int(d.refined), nearest.id, nearest.distance_mm);
    EXPECT_LT(nearest.distance_mm, 0.1 * diameter) << label << ": a detection is on no instance";
    EXPECT_TRUE(found.insert(nearest.id).second) << label << ": instance found twice";
  }
  return found;
}

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

} // namespace

TEST(SurfaceVoting, FindsMoreSupportsInBinsWithoutFalseDetections) {
  const RecognitionParams with_surface = test::bundledPreset("phoxi-bin");
  ASSERT_GT(with_surface.matching.surface_sampling_mm, 0.0);
  RecognitionParams features_only = with_surface;
  features_only.matching.surface_sampling_mm = 0.0;
  // Four views, one per side the support rests on, as docs/accuracy.md teaches them.
  std::vector<test::SynthTeach> views;
  std::vector<std::shared_ptr<const TaughtModel>> models;
  for (int side = 0; side < kTeachSides; ++side) {
    views.push_back(test::teachFromSynth("support", 5, with_surface, side));
    models.push_back(views.back().model);
  }
  std::size_t total_features = 0, total_surface = 0;
  for (std::uint64_t seed : {21u, 22u, 23u}) {
    SynthRequest request;
    request.parts = {"support"};
    request.layout = LayoutKind::Bin;
    request.count = 10;
    request.seed = seed;
    const SynthScene bin = synthesize(request);
    Recognizer recognizer;
    const RecognitionResult features =
        recognizeViews(recognizer, models, bin.render.cloud, bin.sensor, features_only);
    const RecognitionResult surface =
        recognizeViews(recognizer, models, bin.render.cloud, bin.sensor, with_surface);
    total_features += foundInstances(features, views, bin.scene, "features").size();
    total_surface += foundInstances(surface, views, bin.scene, "surface").size();

    // Repeatability, with a fresh recognizer (nothing cached).
    Recognizer fresh;
    const RecognitionResult again =
        recognizeViews(fresh, models, bin.render.cloud, bin.sensor, with_surface);
    ASSERT_EQ(again.detections.size(), surface.detections.size());
    for (std::size_t i = 0; i < surface.detections.size(); ++i)
      EXPECT_TRUE(
          again.detections[i].T_scene_model.isApprox(surface.detections[i].T_scene_model, 0.0));

    // Views prepared beforehand (as a cell loads them) that vote alike share a pairing of the
    // scene (ScenePairs) made beside the feature search, before the first of them votes: the
    // same detections as the fresh recognizer's, whose second view pairs the scene.
    Recognizer prepared;
    prepareViews(prepared, models, with_surface);
    const RecognitionResult paired_early =
        recognizeViews(prepared, models, bin.render.cloud, bin.sensor, with_surface);
    ASSERT_EQ(paired_early.detections.size(), again.detections.size());
    for (std::size_t i = 0; i < again.detections.size(); ++i) {
      EXPECT_TRUE(paired_early.detections[i].T_scene_model.isApprox(
          again.detections[i].T_scene_model, 0.0));
      EXPECT_EQ(paired_early.detections[i].coverage, again.detections[i].coverage);
    }

    // The views after the first vote with the scene paired once (ScenePairs): each finds what it
    // finds in a recognizer of its own, which pairs the scene as it votes.
    if (seed != 21u)
      continue;
    Recognizer shared;
    for (const auto& model : models) {
      shared.setModel(model);
      const RecognitionResult together =
          shared.recognize(bin.render.cloud, bin.sensor, with_surface);
      Recognizer own;
      own.setModel(model);
      const RecognitionResult alone = own.recognize(bin.render.cloud, bin.sensor, with_surface);
      ASSERT_EQ(together.detections.size(), alone.detections.size());
      for (std::size_t i = 0; i < alone.detections.size(); ++i) {
        EXPECT_TRUE(
            together.detections[i].T_scene_model.isApprox(alone.detections[i].T_scene_model, 0.0));
        EXPECT_EQ(together.detections[i].coverage, alone.detections[i].coverage);
      }
    }
  }
  std::printf("instances found in three bins of ten: %zu by features, %zu with surface voting\n",
              total_features, total_surface);
  EXPECT_GT(total_surface, total_features);
}

TEST(SurfaceVoting, PumpConnectorsSeenFromTheSideReportTheirPipeAxisAsFreeTurn) {
  RecognitionParams params = test::bundledPreset("phoxi-bin");
  // The bin's floor stays: with it removed, this bin gives one false detection, an upright view's
  // top flange matched on the lower flange of a leaning pump-connector (the view does not hold the
  // rest of the part; docs/design-notes.md, "Floor removal and the bin's floor"). This test is
  // about the free turn axis.
  params.floor.bin_floor_fraction = 0.0;
  std::vector<test::SynthTeach> views;
  std::vector<std::shared_ptr<const TaughtModel>> models;
  for (int side = 0; side < kTeachSides; ++side) {
    views.push_back(test::teachFromSynth("pump-connector", 5, params, side));
    models.push_back(views.back().model);
  }
  SynthRequest request;
  request.parts = {"pump-connector"};
  request.layout = LayoutKind::Bin;
  request.count = 8;
  request.seed = 31;
  const SynthScene bin = synthesize(request);
  Recognizer recognizer;
  const RecognitionResult result =
      recognizeViews(recognizer, models, bin.render.cloud, bin.sensor, params);
  // The part frame's z is the pipe axis and (0, 0, 50) the pipe's centre, the same under every
  // symmetry of the part (the origin is at one flange: an end-to-end flip moves it 100 mm).
  const Eigen::Vector3d pipe_centre(0, 0, 50);
  std::set<int> found, views_with_free_turn, views_without;
  for (const auto& d : result.detections) {
    const auto& view = views.at(static_cast<std::size_t>(d.model_index));
    const Eigen::Vector3d centre_est =
        d.T_scene_model * view.T_part_model().inverse() * pipe_centre;
    const PartInstance* nearest = nullptr;
    for (const auto& instance : bin.scene.instances)
      if (!nearest || (bin.scene.T_scene_part(instance) * pipe_centre - centre_est).norm() <
                          (bin.scene.T_scene_part(*nearest) * pipe_centre - centre_est).norm())
        nearest = &instance;
    const Eigen::Isometry3d T_true = bin.scene.T_scene_part(*nearest);
    const Eigen::Vector3d centre = T_true * pipe_centre;
    std::printf("score %.3f, view %d, free turn %d: instance %d, pipe centre %.2f mm off\n",
                d.score, d.model_index, int(d.free_turn_axis.has_value()), nearest->id,
                (centre - centre_est).norm());
    EXPECT_LT((centre - centre_est).norm(), 3.0) << "the pipe's centre is right";
    EXPECT_TRUE(found.insert(nearest->id).second) << "instance found twice";
    (d.free_turn_axis ? views_with_free_turn : views_without).insert(d.model_index);
    if (!d.free_turn_axis)
      continue;
    const Eigen::Vector3d true_axis = T_true.linear() * Eigen::Vector3d::UnitZ();
    EXPECT_GT(std::abs(d.free_turn_axis->direction.dot(true_axis)), std::cos(3.0 * kDegToRad))
        << "the reported axis is the pipe's";
    const Eigen::Vector3d off = centre - d.free_turn_axis->point_mm;
    EXPECT_LT((off - off.dot(true_axis) * true_axis).norm(), 2.0)
        << "the axis runs through the pipe";
  }
  std::printf("pump-connectors found: %zu of 8; views with a free turn:", found.size());
  for (int v : views_with_free_turn)
    std::printf(" %d", v);
  std::printf("\n");
  EXPECT_GE(found.size(), 4u);
  // A view either is a surface of revolution or not: no view is on both sides.
  for (int v : views_with_free_turn)
    EXPECT_FALSE(views_without.contains(v)) << "view " << v;
  EXPECT_FALSE(views_with_free_turn.empty()) << "parts lying on their side are found by side views";
}
