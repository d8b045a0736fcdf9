// The evaluation suites and the demo scenes: their definitions, and a few of them written to disk.
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/Renderer.h"
#include "core/sim/Scene.h"
#include "core/sim/Suite.h"
#include "tests/support/TempDir.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <set>

using namespace scanpick::core;
using scanpick::test::TempDir;

TEST(SimSuite, PhoxiBinCoversAllPartsWithSixToFifteenInstances) {
  const auto scenes = suiteScenes("phoxi-bin", kDefaultSuiteSeed);
  std::set<std::string> single_parts;
  std::size_t single = 0, mixed = 0;
  for (const auto& s : scenes) {
    EXPECT_EQ(s.request.sensor, "phoxi-m-1032");
    EXPECT_GE(s.request.count, 6);
    EXPECT_LE(s.request.count, 15);
    if (s.request.parts.size() == 1) {
      ++single;
      single_parts.insert(s.request.parts.front());
    } else {
      ++mixed;
    }
  }
  EXPECT_GE(single, 20u);
  EXPECT_GE(mixed, 1u);
  EXPECT_EQ(single_parts.size(), builtInPartNames().size());
  EXPECT_EQ(scenes.front().relative_prefix, std::filesystem::path("phoxi-bin/scene-000"));
}

TEST(SimSuite, KinectAndTeachSuites) {
  const auto kinect = suiteScenes("kinect-bin", kDefaultSuiteSeed);
  EXPECT_GE(kinect.size(), 10u);
  for (const auto& s : kinect)
    EXPECT_EQ(s.request.sensor, "kinect-v1");
  const auto teach = suiteScenes("teach", kDefaultSuiteSeed);
  // kTeachSides table scans and one view cut from a bin, per part and sensor.
  EXPECT_EQ(teach.size(),
            builtInPartNames().size() * sensorPresetNames().size() * (kTeachSides + 1));
  EXPECT_EQ(teach.at(kTeachSides).relative_prefix,
            std::filesystem::path("teach/phoxi-m-1032/support-bin"));
  EXPECT_EQ(teach.at(kTeachSides).novel_against.size(), static_cast<std::size_t>(kTeachSides));
  EXPECT_EQ(teach.front().relative_prefix, std::filesystem::path("teach/phoxi-m-1032/support"));
  EXPECT_THROW(suiteScenes("lidar-bin", 1), Error);
}

TEST(SimSuite, WrittenScenesFollowTheLayoutAndAreReproducible) {
  TempDir dir;
  // One scene of each kind keeps the test short; the suite writes them all the same way.
  std::vector<SuiteScene> some = {suiteScenes("phoxi-bin", kDefaultSuiteSeed).front(),
                                  suiteScenes("kinect-bin", kDefaultSuiteSeed).back(),
                                  *std::prev(suiteScenes("teach", kDefaultSuiteSeed).end(), 2)};
  const auto files = writeSuite(dir.path(), some);
  EXPECT_EQ(files.size(), 9u);
  for (const char* f :
       {"phoxi-bin/scene-000.pcd", "phoxi-bin/scene-000.png", "phoxi-bin/scene-000.gt.json",
        "kinect-bin/scene-011.gt.json", "teach/kinect-v1/coat-rack-side3.gt.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const auto gt = nlohmann::json::parse(readFile(dir / "phoxi-bin/scene-000.gt.json"));
  EXPECT_EQ(gt["instances"].size(), static_cast<std::size_t>(some[0].request.count));
  EXPECT_TRUE(nlohmann::json::parse(readFile(dir / "teach/kinect-v1/coat-rack-side3.gt.json"))
                  .contains("crop_box"));

  TempDir again;
  writeSuite(again.path(), {some[0]});
  EXPECT_EQ(readFile(dir / "phoxi-bin/scene-000.pcd"), readFile(again / "phoxi-bin/scene-000.pcd"));
  EXPECT_EQ(readFile(dir / "phoxi-bin/scene-000.gt.json"),
            readFile(again / "phoxi-bin/scene-000.gt.json"));
}

TEST(SimSuite, DemoScenes) {
  TempDir dir;
  const auto files = writeDemoScenes(dir.path());
  EXPECT_EQ(files.size(), 9u);
  const auto bin = nlohmann::json::parse(readFile(dir / "demo-bin.gt.json"));
  EXPECT_EQ(bin["instances"].size(), 8u);
  EXPECT_EQ(bin["sensor"]["preset"], "phoxi-m-1032");
  EXPECT_EQ(nlohmann::json::parse(readFile(dir / "support-teach.gt.json"))["scene"]["kind"],
            "teach");
}

TEST(SimSuite, TeachSidesShowThePartFromOtherSides) {
  // Where the camera looks from, in the part's frame, for the cup taught on each side.
  const auto viewDirection = [](int side) {
    SceneSpec spec;
    spec.layout = LayoutKind::Teach;
    spec.parts = {builtInPart("cup")};
    spec.count = 1;
    spec.seed = 11;
    spec.teach_side = side;
    const Scene scene = buildScene(spec, sensorPreset("phoxi-m-1032"));
    return Eigen::Vector3d(scene.T_scene_part(scene.instances.front()).linear().transpose() *
                           Eigen::Vector3d::UnitZ());
  };
  const Eigen::Vector3d upright = viewDirection(0), upside_down = viewDirection(1),
                        lying = viewDirection(2);
  EXPECT_LT(upright.dot(upside_down), -0.9);    // seen from the other end
  EXPECT_LT(std::abs(upright.dot(lying)), 0.5); // seen from the side
  SceneSpec bad;
  bad.layout = LayoutKind::Teach;
  bad.parts = {builtInPart("cup")};
  bad.count = 1;
  bad.teach_side = kTeachSides;
  EXPECT_THROW(buildScene(bad, sensorPreset("phoxi-m-1032")), Error);
}

TEST(SimSuite, BinViewKeepsTheInstanceSeenMostDifferentlyFromTheTableScans) {
  // The support's table scans, then a bin of ten: the kept instance is well visible, its view is
  // the farthest from every taught view among the well visible ones, and only its points and the
  // bin's are left in the scan.
  std::vector<SuiteScene> teach_suite = suiteScenes("teach", kDefaultSuiteSeed);
  teach_suite.resize(kTeachSides + 1);
  std::vector<Eigen::Vector3d> taught;
  for (int side = 0; side < kTeachSides; ++side) {
    const SynthScene scan = synthesize(teach_suite[static_cast<std::size_t>(side)].request);
    taught.push_back(viewDirectionInPart(scan.scene, scan.scene.instances.front()));
  }
  const SynthScene bin = synthesize(teach_suite.back().request);
  const SynthScene view = isolateNovelView(bin, taught);
  ASSERT_EQ(view.scene.instances.size(), 1u);
  EXPECT_EQ(view.scene.layout, LayoutKind::Teach);
  ASSERT_TRUE(view.scene.crop_box_world);
  const PartInstance& kept = view.scene.instances.front();
  EXPECT_GE(view.render.visible_fraction.at(static_cast<std::size_t>(kept.id)), 0.9);

  const Eigen::Matrix3d S = bin.scene.parts.front().symmetry.discrete.at(0).linear();
  const auto novelty = [&](const PartInstance& instance) {
    const Eigen::Vector3d d = viewDirectionInPart(bin.scene, instance);
    double nearest = 4.0;
    for (const auto& t : taught)
      for (const Eigen::Vector3d& e : {d, Eigen::Vector3d(S.transpose() * d)})
        nearest = std::min(nearest, std::acos(std::clamp(e.dot(t), -1.0, 1.0)));
    return nearest;
  };
  for (const auto& other : bin.scene.instances) {
    if (bin.render.visible_fraction.at(static_cast<std::size_t>(other.id)) >= 0.9) {
      EXPECT_LE(novelty(other), novelty(kept) + 1e-12) << "instance " << other.id;
    }
  }
  // Seen from a new side: more than 20° from every table scan.
  EXPECT_GT(novelty(kept), 20.0 * 3.14159265358979 / 180.0);

  std::size_t own = 0, others_left = 0;
  for (std::size_t k = 0; k < view.render.cloud.points_mm.size(); ++k) {
    if (!view.render.cloud.points_mm[k].allFinite())
      continue;
    const std::int32_t label = view.render.labels[k];
    own += label == kept.id;
    others_left += label != kept.id && label != kLabelEnvironment;
  }
  EXPECT_EQ(others_left, 0u);
  EXPECT_EQ(own, view.render.visible_points.at(static_cast<std::size_t>(kept.id)));
  EXPECT_THROW(isolateNovelView(SynthScene{}, taught), Error);
}
