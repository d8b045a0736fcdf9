#include "core/preprocess/FloorRemoval.h"

#include "core/common/Error.h"
#include "core/preprocess/Downsample.h"
#include "tests/support/RaycastScene.h"

#include <gtest/gtest.h>

using namespace scanpick;

namespace {
// A 60 x 40 x 30 mm box on a floor 1000 mm from the camera; projector 300 mm to the side.
test::RaycastScene boxOnFloor() {
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-30, -20, 970), Eigen::Vector3d(30, 20, 1000));
  return scene;
}
} // namespace

TEST(FloorRemoval, RemovesTheFloorPlaneAndKeepsTheBox) {
  auto scene = boxOnFloor();
  const core::PointCloud cloud = scene.render(320, 240, 800.0, {300, 0, 0}, 0.1, 7);
  std::size_t floor_points = 0, box_points = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (core::isValid(cloud.points_mm[i]))
      (scene.labels[i] < 0 ? floor_points : box_points)++;
  ASSERT_GT(floor_points, box_points); // the floor is the dominant plane

  core::FloorParams params; // 2 mm, one plane, 15 % of the points
  const auto result = core::removeFloor(cloud, params, 42);
  ASSERT_EQ(result.planes.size(), 1u);
  // The plane is z = 1000 with its normal towards the camera: (0, 0, -1, 1000).
  EXPECT_NEAR(result.planes[0].z(), -1.0f, 1e-3);
  EXPECT_NEAR(result.planes[0].w(), 1000.0f, 0.5);
  // Organization kept; every floor point gone; the box's top survives (its sides within 2 mm of
  // the floor may go with it, nothing more).
  EXPECT_EQ(result.remaining.width, cloud.width);
  EXPECT_EQ(result.remaining.height, cloud.height);
  std::size_t kept_floor = 0, kept_box = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (core::isValid(result.remaining.points_mm[i]))
      (scene.labels[i] < 0 ? kept_floor : kept_box)++;
  EXPECT_EQ(kept_floor, 0u);
  EXPECT_GT(kept_box, box_points * 9 / 10);
  EXPECT_EQ(result.removed_points, floor_points + (box_points - kept_box));
}

TEST(FloorRemoval, BinFloorAndWallsGoAndThePartsStay) {
  // A bin standing on the ground 1000 mm from the camera: a 10 mm floor slab (its top at 990 mm),
  // 10 mm walls up to a rim at 850 mm, two flat parts and a 100 mm tall block on its floor. With
  // bin_walls the walls go after the floor. The
  // ground around the bin is the dominant plane; the bin's floor, parallel to it, has nothing
  // behind it; the walls have nothing behind them but their rim, the block's faces have the bin's
  // far side behind them. The projector (300 mm to +x) leaves the +x wall's face in shadow: only
  // its rim is seen.
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-160, -110, 990), Eigen::Vector3d(160, 110, 1000));
  scene.boxes.emplace_back(Eigen::Vector3d(-160, -110, 850), Eigen::Vector3d(-150, 110, 990));
  scene.boxes.emplace_back(Eigen::Vector3d(150, -110, 850), Eigen::Vector3d(160, 110, 990));
  scene.boxes.emplace_back(Eigen::Vector3d(-150, -110, 850), Eigen::Vector3d(150, -100, 990));
  scene.boxes.emplace_back(Eigen::Vector3d(-150, 100, 850), Eigen::Vector3d(150, 110, 990));
  scene.boxes.emplace_back(Eigen::Vector3d(-60, -30, 960), Eigen::Vector3d(0, 30, 990));
  scene.boxes.emplace_back(Eigen::Vector3d(40, -50, 975), Eigen::Vector3d(100, 10, 990));
  scene.boxes.emplace_back(Eigen::Vector3d(-20, 30, 890), Eigen::Vector3d(20, 70, 990));
  const core::PointCloud cloud = scene.render(640, 480, 600.0, {300, 0, 0}, 0.1, 3);
  constexpr int kBinFloor = 0, kFirstPart = 5;

  core::FloorParams params; // the ground only
  const auto ground_only = core::removeFloor(cloud, params, 42);
  ASSERT_EQ(ground_only.planes.size(), 1u);
  EXPECT_NEAR(ground_only.planes[0].w(), 1000.0f, 0.5);

  params.bin_floor_fraction = 0.02;
  const auto floor_only = core::removeFloor(cloud, params, 42);
  EXPECT_TRUE(floor_only.remaining_with_walls.empty());
  params.bin_walls = true;
  const auto result = core::removeFloor(cloud, params, 42);
  ASSERT_EQ(result.planes.size(), 2u);
  ASSERT_EQ(result.remaining_with_walls.size(), cloud.size());
  EXPECT_NEAR(result.planes[1].z(), -1.0f, 1e-3);
  EXPECT_NEAR(result.planes[1].w(), 990.0f, 0.2) << "the bin floor's top, fitted exactly";
  // The parts rest on the bin's floor, not on the ground 10 mm below it.
  ASSERT_TRUE(result.resting_plane.has_value());
  EXPECT_EQ(*result.resting_plane, result.planes[1]);
  ASSERT_TRUE(ground_only.resting_plane.has_value());
  EXPECT_EQ(*ground_only.resting_plane, ground_only.planes[0]);
  std::size_t bin_floor_kept = 0, bin_floor_seen = 0, walls = 0, walls_kept = 0, rim_x = 0,
              rim_x_kept = 0, parts = 0, parts_kept = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points_mm[i];
    if (!core::isValid(p))
      continue;
    const bool kept = core::isValid(result.remaining.points_mm[i]);
    const int label = scene.labels[i];
    if (label == kBinFloor) {
      ++bin_floor_seen;
      bin_floor_kept += kept ? 1 : 0;
    } else if (label > kBinFloor && label < kFirstPart) {
      ++walls;
      walls_kept += kept ? 1 : 0;
      // Without bin_walls, and for verification, the walls stay.
      EXPECT_TRUE(core::isValid(floor_only.remaining.points_mm[i]));
      EXPECT_TRUE(core::isValid(result.remaining_with_walls.points_mm[i]));
      if (label == 2) {
        ++rim_x;
        rim_x_kept += kept ? 1 : 0;
      }
    } else if (label >= kFirstPart && p.z() < 986.0f) {
      ++parts;
      parts_kept += kept ? 1 : 0;
    }
  }
  ASSERT_GT(bin_floor_seen, cloud.validCount() / 50);
  EXPECT_EQ(bin_floor_kept, 0u);
  ASSERT_GT(walls, 3000u);
  EXPECT_LT(walls_kept, walls / 100) << "of the walls' " << walls << " points";
  ASSERT_GT(rim_x, 300u);
  EXPECT_EQ(rim_x_kept, 0u) << "the rim of the wall in the projector's shadow";
  ASSERT_GT(parts, 3000u);
  EXPECT_EQ(parts_kept, parts);

  // A part taught from the bin (the first one cropped) rests on the bin's floor: it goes too.
  std::vector<char> first_part(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    first_part[i] = scene.labels[i] == kFirstPart;
  const auto teach = core::removeFloor(cloud, params, 42, {}, first_part);
  ASSERT_EQ(teach.planes.size(), 2u);
  EXPECT_NEAR(teach.planes[1].w(), 990.0f, 0.2);

  // Too small a bin floor for the share asked: nothing more goes.
  params.bin_floor_fraction = 0.5;
  EXPECT_EQ(core::removeFloor(cloud, params, 42).planes.size(), 1u);
}

TEST(FloorRemoval, SupportOnlyKeepsAPlateFaceThatOutnumbersTheTable) {
  // A 360 x 260 x 20 mm plate on a table 1000 mm from the camera fills most of the view: its top
  // face is the largest plane, with the table behind it. As a support, only the table goes.
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-180, -130, 980), Eigen::Vector3d(180, 130, 1000));
  const core::PointCloud cloud = scene.render(320, 240, 800.0, {300, 0, 0}, 0.1, 5);
  std::size_t floor_points = 0, plate_points = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (core::isValid(cloud.points_mm[i]))
      (scene.labels[i] < 0 ? floor_points : plate_points)++;
  ASSERT_GT(plate_points, floor_points); // the plate's face is the dominant plane
  ASSERT_GT(floor_points, plate_points / 10);

  core::FloorParams params;
  params.min_plane_fraction = 0.05;
  const auto any = core::removeFloor(cloud, params, 42);
  ASSERT_EQ(any.planes.size(), 1u);
  EXPECT_NEAR(any.planes[0].w(), 980.0f, 0.5); // the plate's face, without the check

  std::vector<char> plate(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    plate[i] = scene.labels[i] >= 0;
  const auto support = core::removeFloor(cloud, params, 42, {}, plate);
  ASSERT_EQ(support.planes.size(), 1u);
  EXPECT_NEAR(support.planes[0].z(), -1.0f, 1e-3);
  EXPECT_NEAR(support.planes[0].w(), 1000.0f, 0.5);
  std::size_t kept_plate = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (core::isValid(support.remaining.points_mm[i]) && scene.labels[i] >= 0)
      ++kept_plate;
  EXPECT_GT(kept_plate, plate_points * 9 / 10);
}

TEST(FloorRemoval, SupportOnlyRemovesTheTableWithARoomBeyondItsEdge) {
  // A table top 800 mm from the camera ends at x = 100 mm; beyond its edge the camera sees the
  // room's floor at 1600 mm, behind the table's plane. An 80 x 60 x 30 mm part stands on the
  // table. The table is the plane the part rests on: what lies behind it far from the part does
  // not make it a face of a part.
  test::RaycastScene scene;
  scene.floor_z_mm = 1600.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-400, -300, 800), Eigen::Vector3d(100, 300, 1600));
  scene.boxes.emplace_back(Eigen::Vector3d(-40, -30, 770), Eigen::Vector3d(40, 30, 800));
  const core::PointCloud cloud = scene.render(320, 240, 800.0, {300, 0, 0}, 0.1, 5);
  std::size_t room_points = 0, valid = 0;
  std::vector<char> part(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!core::isValid(cloud.points_mm[i]))
      continue;
    ++valid;
    room_points += scene.labels[i] < 0;
    part[i] = scene.labels[i] == 1;
  }
  ASSERT_GT(room_points, valid / 10); // far more than 2 % of the scan lies behind the table

  core::FloorParams params;
  const auto support = core::removeFloor(cloud, params, 42, {}, part);
  ASSERT_FALSE(support.planes.empty());
  EXPECT_NEAR(support.planes[0].z(), -1.0f, 1e-3);
  EXPECT_NEAR(support.planes[0].w(), 800.0f, 0.5);
  std::size_t kept_table = 0, kept_part = 0, part_points = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    part_points += part[i];
    if (core::isValid(support.remaining.points_mm[i]))
      (scene.labels[i] == 0 ? kept_table : kept_part) += scene.labels[i] >= 0;
  }
  EXPECT_EQ(kept_table, 0u);
  EXPECT_GT(kept_part, part_points * 9 / 10);
}

TEST(FloorRemoval, SmallPlanesAreKeptAndDisabledIsACopy) {
  auto scene = boxOnFloor();
  const core::PointCloud cloud = scene.render(160, 120, 400.0, {300, 0, 0});
  core::FloorParams params;
  params.min_plane_fraction = 0.99; // no plane holds 99 % of the points
  EXPECT_TRUE(core::removeFloor(cloud, params, 1).planes.empty());
  params.min_plane_fraction = 0.15;
  params.enabled = false;
  const auto copy = core::removeFloor(cloud, params, 1);
  EXPECT_EQ(copy.remaining.validCount(), cloud.validCount());
  params.enabled = true;
  params.distance_mm = 0;
  EXPECT_THROW(core::removeFloor(cloud, params, 1), core::Error);
}

TEST(FloorRemoval, SameSeedSameResultAndUnorganizedInput) {
  auto scene = boxOnFloor();
  const core::PointCloud cloud =
      core::dropInvalid(scene.render(200, 150, 500.0, {300, 0, 0}, 0.2, 3));
  const auto a = core::removeFloor(cloud, {}, 9), b = core::removeFloor(cloud, {}, 9);
  ASSERT_EQ(a.planes.size(), 1u);
  EXPECT_EQ(a.planes, b.planes);
  EXPECT_EQ(a.remaining.points_mm, b.remaining.points_mm);
  EXPECT_FALSE(a.remaining.isOrganized());
  EXPECT_EQ(a.remaining.size() + a.removed_points, cloud.size());
}

TEST(Downsample, OneCentroidPerVoxel) {
  // 8 points in two 1 mm voxels -> 2 centroids.
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 4; ++i) {
    pts.emplace_back(0.1f + 0.2f * i, 0.5f, 0.5f);
    pts.emplace_back(5.1f + 0.2f * i, 0.5f, 0.5f);
  }
  const auto out = core::voxelDownsample(core::PointCloud::fromPoints(pts), 1.0);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out.points_mm[0].x(), 0.4f, 1e-5);
  EXPECT_NEAR(out.points_mm[1].x(), 5.4f, 1e-5);
  EXPECT_EQ(core::voxelDownsample(core::PointCloud::fromPoints(pts), 0.0).size(), 8u);
}
