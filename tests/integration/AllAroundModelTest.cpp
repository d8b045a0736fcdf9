// A part taught from a cloud of its every side (points sampled on its mesh, as merged scans or a
// CAD export give them) instead of one scan: teach sees that no camera took it, turns its normals
// out of the part and derives the scan parameters from the sensor; recognition then finds the part
// in simulated bins however it lies, with no false detection. An organized scan, however noisy,
// is one view.
#include "core/model/AutoParams.h"
#include "core/pipeline/Recognizer.h"
#include "core/sim/Mesh.h"
#include "core/sim/PartCatalog.h"
#include "tests/integration/EvalTruth.h"
#include "tests/integration/SynthTeach.h"

#include <algorithm>
#include <cstdio>
#include <gtest/gtest.h>
#include <set>

using namespace scanpick;
using namespace scanpick::core;

namespace {

/// The part's pose in the cloud it is taught from: 800 mm in front of the teach camera.
Eigen::Isometry3d cloudPose() {
  return Eigen::Isometry3d(Eigen::Translation3d(0, 0, 800));
}

/// `count` points sampled over the part's surface, placed at cloudPose(), without normals.
PointCloud allAroundCloud(const Part& part, std::size_t count) {
  std::vector<Eigen::Vector3d> points, normals;
  sampleSurface(part.mesh(), count, 1, points, normals);
  std::vector<Eigen::Vector3f> placed;
  for (const auto& p : points)
    placed.push_back((cloudPose() * p).cast<float>());
  return PointCloud::fromPoints(std::move(placed));
}

test::SynthTeach teachAllAround(const std::string& name) {
  const PointCloud cloud = allAroundCloud(builtInPart(name), 40000);
  TeachOptions options;
  options.name = name;
  options.sensor = sensorPreset("phoxi-m-1032");
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-500, -500, 300), Eigen::Vector3f(500, 500, 1300));
  const RecognitionParams params = autoTeachParams(cloud, options).params;
  test::SynthTeach out;
  out.model = std::make_shared<TaughtModel>(teach(cloud, options, params));
  out.T_teach_part = cloudPose();
  return out;
}

} // namespace

TEST(AllAroundModel, TheSupportIsFoundInBinsHoweverItLies) {
  const test::SynthTeach taught = teachAllAround("support");
  ASSERT_TRUE(taught.model->all_around);
  // The scenes' spacing, not the dense samples': the sensor's at its working distance.
  EXPECT_GT(taught.model->params.matching.verify_tolerance_mm, 0.8);
  const std::vector<std::shared_ptr<const TaughtModel>> models{taught.model};
  std::size_t found = 0, seen = 0;
  for (const std::uint64_t seed : {5u, 6u, 7u}) {
    SynthRequest request;
    request.parts = {"support"};
    request.count = 10;
    request.seed = seed;
    const SynthScene bin = synthesize(request);
    const test::ScoredPart scored = test::scoredPart(bin, "support");
    Recognizer recognizer;
    const RecognitionResult result =
        recognizeViews(recognizer, models, bin.render.cloud, bin.sensor, taught.model->params);
    std::set<int> instances;
    for (const auto& d : result.detections) {
      const test::NearestInstance nearest = test::nearestInstance(d, taught, bin.scene);
      const Eigen::Isometry3d T_scene_part = d.T_scene_model * taught.T_part_model().inverse();
      const auto instance = std::find_if(bin.scene.instances.begin(), bin.scene.instances.end(),
                                         [&](const auto& i) { return i.id == nearest.id; });
      ASSERT_NE(instance, bin.scene.instances.end());
      const double rotation_deg =
          test::rotationErrorDeg(T_scene_part, bin.scene.T_scene_part(*instance), scored);
      const double visible =
          bin.render.visible_fraction.at(std::size_t(instance - bin.scene.instances.begin()));
      std::printf("seed %llu: score %.3f on instance %d (%.2f visible), %.2f mm, %.2f deg off\n",
                  static_cast<unsigned long long>(seed), d.score, nearest.id, visible,
                  nearest.distance_mm, rotation_deg);
      // A true detection as eval counts it; on an instance in full view, exact.
      EXPECT_LT(nearest.distance_mm, 0.1 * scored.info.diameter_mm) << "on no instance";
      EXPECT_LT(rotation_deg, 10.0);
      if (visible >= 0.9) {
        EXPECT_LT(nearest.distance_mm, 0.5);
        EXPECT_LT(rotation_deg, 0.2);
      }
      EXPECT_TRUE(instances.insert(nearest.id).second) << "an instance found twice";
    }
    found += instances.size();
    for (const double visible : bin.render.visible_fraction)
      seen += visible >= 0.5 ? 1 : 0;
  }
  std::printf("found %zu of the %zu instances at least half visible\n", found, seen);
  EXPECT_GE(found, seen * 2 / 3);
}

TEST(AllAroundModel, AKinectViewIsOneViewHoweverNoisyItsDepth) {
  // A Kinect's depth steps stack points along lines of sight as two surfaces would; the scan is
  // still one camera's image (organized), and its views were taken for the part's every side.
  for (const std::string part : {"support", "cup", "coat-rack"}) {
    for (int side = 0; side < 3; ++side) {
      SynthRequest request;
      request.parts = {part};
      request.layout = LayoutKind::Teach;
      request.count = 1;
      request.seed = 3;
      request.teach_side = side;
      request.sensor = "kinect-v1";
      const SynthScene scan = synthesize(request);
      ASSERT_TRUE(scan.render.cloud.isOrganized());
      const TeachOptions options = test::teachOptionsFor(scan, part);
      const AutoParams derived = autoTeachParams(scan.render.cloud, options);
      EXPECT_FALSE(teach(scan.render.cloud, options, derived.params).all_around)
          << part << " side " << side;
    }
  }
}
