#include "core/grasp/BinBox.h"

#include "GraspScenes.h"
#include "core/common/Error.h"

#include <gtest/gtest.h>

using namespace scanpick::core;
using namespace scanpick::core::grasp;
using namespace scanpick::core::grasp::test;

namespace {
PointCloud cloudOf(std::vector<Eigen::Vector3f> points) {
  return PointCloud::fromPoints(std::move(points));
}
} // namespace

TEST(BinBox, EstimatesFloorWallsAndRimOfABinStandingOnATable) {
  // A 400 x 300 mm bin, 150 mm walls, on a table 10 mm below its floor reaching 400 mm out, and a
  // few parts on the floor: the table is larger than the floor but lies outside the walls, so the
  // floor must still be the bin's own.
  auto points = binPoints(200.0, 150.0, 150.0, 400.0);
  addPosed(points, boxSurface({30, 20, 15}), onFloor(-50, 0, 15));
  addPosed(points, boxSurface({30, 20, 15}), onFloor(80, 40, 15, 30));
  const auto bin = estimateBin(cloudOf(points));
  ASSERT_TRUE(bin);
  EXPECT_TRUE(bin->floor_found);
  for (bool w : bin->walls_found)
    EXPECT_TRUE(w);
  // The floor's origin lies at z = 1000, the bin frame's z is up (-z of the camera).
  EXPECT_NEAR(bin->T_scene_bin.translation().z(), kFloorZ, 1.0);
  EXPECT_NEAR(bin->T_scene_bin.translation().x(), 0.0, 2.0);
  EXPECT_NEAR(bin->T_scene_bin.translation().y(), 0.0, 2.0);
  EXPECT_TRUE(bin->T_scene_bin.linear().col(2).isApprox(-Eigen::Vector3d::UnitZ(), 1e-3));
  EXPECT_NEAR(bin->rim_height_mm, 150.0, 2.0);
  // Which wall pair became x depends on which was found first; the sizes must match one way.
  const Eigen::Vector2d h = bin->half_size_mm;
  const bool x_long = std::abs(h.x() - 200.0) < 2.0 && std::abs(h.y() - 150.0) < 2.0;
  const bool y_long = std::abs(h.y() - 200.0) < 2.0 && std::abs(h.x() - 150.0) < 2.0;
  EXPECT_TRUE(x_long || y_long) << h.transpose();
  // Points: inside free, under the floor, beyond a wall below the rim, above the rim.
  EXPECT_EQ(binCollision(*bin, {0, 0, 950}), "");
  EXPECT_EQ(binCollision(*bin, {0, 0, 1005}), "bin floor");
  EXPECT_NE(binCollision(*bin, {230, 0, 950}).find("bin wall"), std::string::npos);
  EXPECT_EQ(binCollision(*bin, {230, 0, 800}), "");
}

TEST(BinBox, IsDeterministicAndReportsNoBinOnAPlainTable) {
  auto points = binPoints(200.0, 150.0, 150.0, 0.0);
  const auto a = estimateBin(cloudOf(points)), b = estimateBin(cloudOf(points));
  ASSERT_TRUE(a && b);
  EXPECT_TRUE(a->T_scene_bin.isApprox(b->T_scene_bin, 0.0));
  EXPECT_EQ(a->half_size_mm, b->half_size_mm);
  std::vector<Eigen::Vector3f> table;
  addPlane(table, {-300, -300, kFloorZ}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 600,
           600, 5.0);
  addPosed(table, boxSurface({30, 20, 15}), onFloor(0, 0, 15));
  EXPECT_FALSE(estimateBin(cloudOf(table)));
  EXPECT_FALSE(estimateBin(PointCloud{}));
}

TEST(BinBox, AMissingWallLeavesItsSideOpen) {
  // Only the floor and the walls at x = +200 and y = ±150.
  std::vector<Eigen::Vector3f> points;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  addPlane(points, {-200, -150, kFloorZ}, X, Y, 400, 300, 4.0);
  addPlane(points, {200, -150, kFloorZ - 150}, Y, Z, 300, 150, 4.0);
  addPlane(points, {-200, -150, kFloorZ - 150}, X, Z, 400, 150, 4.0);
  addPlane(points, {-200, 150, kFloorZ - 150}, X, Z, 400, 150, 4.0);
  const auto bin = estimateBin(PointCloud::fromPoints(points));
  ASSERT_TRUE(bin);
  int found = 0;
  for (bool w : bin->walls_found)
    found += w ? 1 : 0;
  EXPECT_EQ(found, 3);
  EXPECT_NE(binCollision(*bin, {205, 0, 950}).find("bin wall"), std::string::npos);
  EXPECT_EQ(binCollision(*bin, {-260, 0, 950}), ""); // the open side
}

TEST(BinBox, RejectsBadParameters) {
  BinEstimateParams p;
  p.up = Eigen::Vector3d(0, 0, 2);
  EXPECT_THROW((void)estimateBin(PointCloud::fromPoints({{0, 0, 0}}), p), Error);
  p = {};
  p.distance_mm = 0.0;
  EXPECT_THROW((void)estimateBin(PointCloud::fromPoints({{0, 0, 0}}), p), Error);
}
