#include "core/cloud/CloudIo.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "tests/support/TempDir.h"

#include <algorithm>
#include <gtest/gtest.h>

using namespace scanpick;

namespace {
core::PointCloud organizedGrid() {
  // 4 x 3 grid, one invalid cell, coordinates in millimetres.
  core::PointCloud c;
  c.width = 4;
  c.height = 3;
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 4; ++col)
      c.points_mm.emplace_back(10.0f * col, 10.0f * r, 500.0f + r + col);
  c.points_mm[5] = core::invalidPoint();
  return c;
}
} // namespace

TEST(CloudIo, PcdRoundTripKeepsOrganizationAndNaN) {
  test::TempDir dir;
  const auto cloud = organizedGrid();
  core::saveCloudPcd(dir / "grid.pcd", cloud);
  const auto loaded = core::loadCloud(dir / "grid.pcd", core::LengthUnit::Millimetres);
  ASSERT_EQ(loaded.cloud.width, 4u);
  ASSERT_EQ(loaded.cloud.height, 3u);
  EXPECT_FALSE(core::isValid(loaded.cloud.points_mm[5]));
  EXPECT_TRUE(loaded.cloud.points_mm[6].isApprox(cloud.points_mm[6]));
  EXPECT_TRUE(loaded.units_warning.empty()) << loaded.units_warning;
}

TEST(PointCloud, CountsAndFindsValidPoints) {
  core::PointCloud cloud = organizedGrid();
  EXPECT_EQ(cloud.validCount(), 11u);
  EXPECT_TRUE(cloud.hasValidPoint());
  for (std::size_t i = 0; i + 1 < cloud.size(); ++i)
    cloud.points_mm[i] = core::invalidPoint();
  EXPECT_EQ(cloud.validCount(), 1u);
  EXPECT_TRUE(cloud.hasValidPoint()) << "the last point is still valid";
  cloud.points_mm.back() = core::invalidPoint();
  EXPECT_EQ(cloud.validCount(), 0u);
  EXPECT_FALSE(cloud.hasValidPoint());
  EXPECT_FALSE(core::PointCloud{}.hasValidPoint());
}

TEST(CloudIo, MetresAreConvertedAndWrongUnitsWarned) {
  test::TempDir dir;
  auto cloud = organizedGrid();
  for (auto& p : cloud.points_mm)
    p /= 1000.0f; // now in metres
  core::saveCloudPly(dir / "grid_m.ply", cloud);
  const auto as_m = core::loadCloud(dir / "grid_m.ply", core::LengthUnit::Metres);
  EXPECT_NEAR(as_m.cloud.points_mm[6].z(), 503.0f, 1e-3f);
  EXPECT_TRUE(as_m.units_warning.empty());
  // Declaring millimetres for a cloud that spans 0.05 units must produce a warning naming --units
  // m.
  const auto as_mm = core::loadCloud(dir / "grid_m.ply", core::LengthUnit::Millimetres);
  EXPECT_NE(as_mm.units_warning.find("--units m"), std::string::npos) << as_mm.units_warning;
  // With no units given, the extent tells: the same file is read as metres, without a warning.
  const auto guessed = core::loadCloud(dir / "grid_m.ply", std::nullopt);
  EXPECT_EQ(guessed.cloud.points_mm[6], as_m.cloud.points_mm[6]);
  EXPECT_TRUE(guessed.units_warning.empty()) << guessed.units_warning;
  core::saveCloudPly(dir / "grid_mm.ply", organizedGrid());
  EXPECT_EQ(core::loadCloud(dir / "grid_mm.ply", std::nullopt).cloud.points_mm[6],
            organizedGrid().points_mm[6]);
}

TEST(CloudIo, LoadingReportsProgressAndCanBeCancelled) {
  test::TempDir dir;
  core::PointCloud big;
  big.width = 1000;
  big.height = 800; // 9.6 MB of binary PCD: ten blocks read
  for (std::uint32_t i = 0; i < big.width * big.height; ++i)
    big.points_mm.emplace_back(float(i % 1000), float(i / 1000), 500.0f);
  core::saveCloudPcd(dir / "big.pcd", big);
  std::vector<double> seen;
  const auto loaded =
      core::loadCloud(dir / "big.pcd", core::LengthUnit::Millimetres, [&](double f) {
        seen.push_back(f);
        return true;
      });
  EXPECT_EQ(loaded.cloud.size(), big.size());
  ASSERT_GE(seen.size(), 10u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_TRUE(std::any_of(seen.begin(), seen.end(), [](double f) { return f > 0 && f < 0.6; }));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  int calls = 0;
  EXPECT_THROW(core::loadCloud(dir / "big.pcd", core::LengthUnit::Millimetres,
                               [&](double) { return ++calls < 3; }),
               core::Cancelled);
}

TEST(CloudIo, BadFilesGiveClearErrors) {
  test::TempDir dir;
  EXPECT_THROW(core::loadCloud(dir / "missing.pcd", core::LengthUnit::Millimetres), core::Error);
  core::writeFileAtomic(dir / "empty.pcd", "");
  EXPECT_THROW(core::loadCloud(dir / "empty.pcd", core::LengthUnit::Millimetres), core::Error);
  core::writeFileAtomic(dir / "x.xyz", "1 2 3\n");
  EXPECT_THROW(core::loadCloud(dir / "x.xyz", core::LengthUnit::Millimetres), core::Error);

  // A valid file cut in the middle of its point data is reported as truncated, not read as a
  // smaller cloud. (PCL pads binary files with zeros, so the cut is made relative to the header.)
  core::saveCloudPcd(dir / "full.pcd", organizedGrid());
  const std::string full = core::readFile(dir / "full.pcd");
  const auto data_start = full.find("DATA binary\n") + 12;
  core::writeFileAtomic(dir / "cut.pcd", full.substr(0, data_start + 6 * 16));
  EXPECT_THROW(core::loadCloud(dir / "cut.pcd", core::LengthUnit::Millimetres), core::Error);

  // All-NaN cloud.
  auto nan_cloud = organizedGrid();
  for (auto& p : nan_cloud.points_mm)
    p = core::invalidPoint();
  core::saveCloudPcd(dir / "nan.pcd", nan_cloud);
  try {
    core::loadCloud(dir / "nan.pcd", core::LengthUnit::Millimetres);
    FAIL();
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no valid point"), std::string::npos);
  }
}

TEST(CloudIo, RealKinectSceneLoadsInMillimetres) {
  const auto path = test::sharedData("pcl/milk_cartoon_all_small_clorox.pcd");
  if (path.empty())
    GTEST_SKIP() << "../shared/data/pcl is absent on this machine; this test reads a real scan";
  const auto loaded = core::loadCloud(path, core::LengthUnit::Metres);
  EXPECT_EQ(loaded.cloud.width, 640u);
  EXPECT_EQ(loaded.cloud.height, 480u);
  EXPECT_EQ(loaded.cloud.colors.size(), loaded.cloud.size());
  const auto box = core::boundingBox(loaded.cloud);
  // A table-top Kinect scene spans roughly half a metre to a few metres.
  EXPECT_GT(box.diagonal().norm(), 300.0f);
  EXPECT_LT(box.diagonal().norm(), 5000.0f);
  EXPECT_TRUE(loaded.units_warning.empty());
}
