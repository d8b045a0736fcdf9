// Physics: parts come to rest in the bin without interpenetrating; bad specs throw.
#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/Scene.h"

#include <algorithm>
#include <gtest/gtest.h>

using namespace scanpick::core;

namespace {
const SensorModel kPhoxi = sensorPreset("phoxi-m-1032");
}

class BinDrop : public ::testing::TestWithParam<std::string> {};

TEST_P(BinDrop, InstancesRestInsideTheBinWithoutInterpenetration) {
  SceneSpec spec;
  spec.parts = {builtInPart(GetParam())};
  spec.count = 12;
  spec.seed = 3;
  const Scene scene = buildScene(spec, kPhoxi);
  ASSERT_EQ(scene.instances.size(), 12u);
  EXPECT_LT(maxInterpenetration_mm(scene), 0.5);
  for (const auto& inst : scene.instances) {
    const Eigen::AlignedBox3d box =
        boundingBox(transformed(scene.parts[inst.part].mesh(), inst.T_world_part));
    // Inside the walls (180 × 140 mm half sizes) and on or above the floor.
    EXPECT_GT(box.min().x(), -180.5);
    EXPECT_LT(box.max().x(), 180.5);
    EXPECT_GT(box.min().y(), -140.5);
    EXPECT_LT(box.max().y(), 140.5);
    EXPECT_GT(box.min().z(), -0.5);
    // At rest in a pile, nothing floats high above the floor.
    EXPECT_LT(box.min().z(), 400.0);
  }
}

static std::string partTestName(const ::testing::TestParamInfo<std::string>& param) {
  std::string n = param.param;
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

INSTANTIATE_TEST_SUITE_P(Parts, BinDrop, ::testing::ValuesIn(builtInPartNames()), partTestName);

TEST(SceneBuilder, InterpenetrationCheckSeesOverlap) {
  // Two 40 mm cubes side by side along x, overlapping by 2 mm, then 0.3 mm, then deeply, then
  // apart.
  SceneSpec spec;
  Part cube;
  cube.name = "cube";
  cube.components = {boxMesh({0, 0, 0}, {40, 40, 40})};
  spec.parts = {cube};
  spec.count = 2;
  Scene scene = buildScene(spec, kPhoxi);
  scene.instances[0].T_world_part = Eigen::Isometry3d(Eigen::Translation3d(0, 0, 100));
  scene.instances[1].T_world_part = Eigen::Isometry3d(Eigen::Translation3d(38, 0, 100));
  EXPECT_NEAR(maxInterpenetration_mm(scene), 2.0, 0.05);
  scene.instances[1].T_world_part = Eigen::Isometry3d(Eigen::Translation3d(39.7, 0, 100));
  EXPECT_NEAR(maxInterpenetration_mm(scene), 0.3, 0.05);
  // Deep overlaps are only approximated by Bullet's EPA, but never pass as shallow.
  scene.instances[1].T_world_part = Eigen::Isometry3d(Eigen::Translation3d(10, 0, 100));
  EXPECT_GT(maxInterpenetration_mm(scene), 5.0);
  scene.instances[1].T_world_part = Eigen::Isometry3d(Eigen::Translation3d(41, 0, 100));
  EXPECT_LT(maxInterpenetration_mm(scene), 1e-6);
}

TEST(SceneBuilder, SameSeedSamePoses) {
  SceneSpec spec;
  spec.parts = {builtInPart("cup")};
  spec.count = 6;
  spec.seed = 11;
  const Scene a = buildScene(spec, kPhoxi), b = buildScene(spec, kPhoxi);
  for (std::size_t i = 0; i < a.instances.size(); ++i)
    EXPECT_TRUE(a.instances[i].T_world_part.matrix() == b.instances[i].T_world_part.matrix());
  spec.seed = 12;
  const Scene c = buildScene(spec, kPhoxi);
  EXPECT_FALSE(a.instances[0].T_world_part.matrix() == c.instances[0].T_world_part.matrix());
}

TEST(SceneBuilder, TeachSceneHasOnePartInItsNaturalPoseAndACropBox) {
  SceneSpec spec;
  spec.layout = LayoutKind::Teach;
  spec.parts = {builtInPart("cup")};
  spec.count = 1;
  const Scene scene = buildScene(spec, kPhoxi);
  ASSERT_EQ(scene.instances.size(), 1u);
  // The cup stands upright: its axis stays vertical.
  EXPECT_GT((scene.instances[0].T_world_part.linear() * Eigen::Vector3d::UnitZ()).z(), 0.99);
  ASSERT_TRUE(scene.crop_box_world.has_value());
  const Eigen::AlignedBox3d part_box =
      boundingBox(transformed(scene.parts[0].mesh(), scene.instances[0].T_world_part));
  EXPECT_TRUE(scene.crop_box_world->contains(Eigen::Vector3d(part_box.max())));
  EXPECT_GT(scene.crop_box_world->min().z(), 0.0); // the table stays out
}

TEST(SceneBuilder, TeachCameraRisesForAPartTallerThanTheSensorsNearLimitAllows) {
  // A 300 mm column standing on the table would reach within the PhoXi M's 458 mm near limit of
  // a camera at the usual 700 mm: the camera rises until the top is 50 mm beyond it. A short part
  // keeps the usual height.
  SceneSpec spec;
  spec.layout = LayoutKind::Teach;
  spec.count = 1;
  Part column;
  column.name = "column";
  column.components = {boxMesh({-30, -30, 0}, {30, 30, 300})};
  spec.parts = {column};
  const Scene tall = buildScene(spec, kPhoxi);
  const double top_mm =
      boundingBox(transformed(tall.parts[0].mesh(), tall.instances[0].T_world_part)).max().z();
  ASSERT_GT(top_mm, 290.0); // standing
  const double camera_mm = tall.T_camera_world.inverse().translation().z();
  EXPECT_GE(camera_mm - top_mm, kPhoxi.min_range_mm + 50.0 - 1e-6);
  EXPECT_GT(camera_mm, defaultCameraHeight_mm(kPhoxi, LayoutKind::Teach));

  spec.parts = {builtInPart("cup")};
  const Scene cup = buildScene(spec, kPhoxi);
  EXPECT_DOUBLE_EQ(cup.T_camera_world.inverse().translation().z(),
                   defaultCameraHeight_mm(kPhoxi, LayoutKind::Teach));
}

TEST(SceneBuilder, ScatterKeepsPartsOnTheTable) {
  SceneSpec spec;
  spec.layout = LayoutKind::Scatter;
  spec.parts = {builtInPart("coat-rack"), builtInPart("support")};
  spec.count = 5;
  const Scene scene = buildScene(spec, kPhoxi);
  EXPECT_EQ(scene.instances.size(), 5u);
  EXPECT_EQ(scene.instances[1].part, 1u);
  EXPECT_LT(maxInterpenetration_mm(scene), 0.5);
  for (const auto& inst : scene.instances)
    EXPECT_LT(inst.T_world_part.translation().z(), 100.0); // resting, not stacked
}

TEST(SceneBuilder, BadSpecsThrow) {
  SceneSpec spec;
  spec.parts = {builtInPart("cup")};
  spec.count = 0;
  EXPECT_THROW(buildScene(spec, kPhoxi), Error);
  spec.count = 2;
  spec.layout = LayoutKind::Teach;
  EXPECT_THROW(buildScene(spec, kPhoxi), Error);
  spec.parts.clear();
  spec.layout = LayoutKind::Bin;
  EXPECT_THROW(buildScene(spec, kPhoxi), Error);
  EXPECT_THROW(layoutFromName("heap"), Error);
}
