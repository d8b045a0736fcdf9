#include "core/cloud/CloudIo.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/preprocess/ObjectCount.h"

#include <filesystem>
#include <gtest/gtest.h>

using namespace scanpick;

// A real Kinect v1 scan (PCL's test data): a table with a milk carton and household objects.
TEST(RealScene, KinectTableIsRemovedAndTheObjectCountIsPlausible) {
  const std::filesystem::path file =
      std::filesystem::path(SCANPICK_SHARED_DATA_DIR) / "pcl" / "milk_cartoon_all_small_clorox.pcd";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "real scan " << file
                 << " is absent (it lives in ../shared/data beside the project)";
  const auto scene = core::loadCloud(file, core::LengthUnit::Metres).cloud;
  ASSERT_TRUE(scene.isOrganized());

  core::FloorParams floor;
  floor.distance_mm = 10.0; // Kinect depth resolution is about 1 cm at this range
  const auto removed = core::removeFloor(scene, floor, 42);
  ASSERT_EQ(removed.planes.size(), 1u);
  // The table is the largest surface of the scan: well over a third of its points.
  EXPECT_GT(removed.removed_points, scene.validCount() / 3);
  EXPECT_GT(removed.planes[0].w(), 0.0f); // the camera is on the table's visible side

  core::ClusteringParams params;
  params.count_radius_mm = 6.0; // about 3 Kinect pixels at 1 m
  params.count_min_points = 1500;
  const auto count = core::countObjects(removed.remaining, core::sensorPreset("kinect-v1"), params);
  // The scan shows a handful of household objects (carton, bottles, boxes) on the table.
  EXPECT_GE(count.count, 2);
  EXPECT_LE(count.count, 8);
  RecordProperty("object_count", count.count);
}
