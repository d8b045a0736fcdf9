#include "core/model/ViewCoverage.h"

#include "core/common/Error.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <numbers>

using namespace scanpick::core;

namespace {

/// A view whose teach camera looked at the part from `towards_camera_part` (part frame), placed
/// in the part when `placed`.
std::shared_ptr<const TaughtModel> viewFrom(const Eigen::Vector3d& towards_camera_part,
                                            bool placed = true) {
  auto view = std::make_shared<TaughtModel>();
  // The teach camera at the scan origin looks along +z at the part 700 mm away.
  view->T_teach_model = Eigen::Translation3d(0, 0, 700);
  // The part frame turned so that the model's direction to the camera (-z) maps onto the given one.
  const Eigen::Matrix3d R_part_model =
      Eigen::Quaterniond::FromTwoVectors(-Eigen::Vector3d::UnitZ(),
                                         towards_camera_part.normalized())
          .toRotationMatrix();
  if (placed)
    view->T_part_model = Eigen::Isometry3d(R_part_model);
  return view;
}

double capShare(double degrees) {
  return (1.0 - std::cos(degrees * std::numbers::pi / 180.0)) / 2.0;
}

} // namespace

TEST(ViewCoverage, OneViewCoversACapAndSuggestsTheOppositeSide) {
  const ViewCoverage c = viewCoverage({viewFrom(Eigen::Vector3d::UnitZ())});
  ASSERT_EQ(c.view_directions_part.size(), 1u);
  EXPECT_NEAR(c.view_directions_part[0].z(), 1.0, 1e-9);
  EXPECT_NEAR(c.covered, capShare(60.0), 0.005);
  ASSERT_EQ(c.missing_part.size(), 3u);
  EXPECT_LT(c.missing_part[0].z(), -0.99) << "the side facing away from the camera comes first";
}

TEST(ViewCoverage, SixSidesCoverEverythingAndTwoOppositeOnesHalf) {
  std::vector<std::shared_ptr<const TaughtModel>> six;
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {1.0, -1.0})
      six.push_back(viewFrom(sign * Eigen::Vector3d::Unit(axis)));
  const ViewCoverage all = viewCoverage(six);
  EXPECT_DOUBLE_EQ(all.covered, 1.0);
  EXPECT_TRUE(all.missing_part.empty());
  const ViewCoverage two =
      viewCoverage({viewFrom(Eigen::Vector3d::UnitZ()), viewFrom(-Eigen::Vector3d::UnitZ())});
  EXPECT_NEAR(two.covered, 2 * capShare(60.0), 0.005);
  EXPECT_NEAR(std::abs(two.missing_part[0].z()), 0.0, 0.05) << "the equator is what is missing";
  ViewCoverageOptions wide;
  wide.tolerance_deg = 90.0;
  EXPECT_NEAR(viewCoverage({viewFrom(Eigen::Vector3d::UnitX())}, wide).covered, 0.5, 0.005);
}

TEST(ViewCoverage, ViewsThatDoNotKnowTheirPlaceAreCountedApart) {
  const ViewCoverage c = viewCoverage(
      {viewFrom(Eigen::Vector3d::UnitZ()), viewFrom(-Eigen::Vector3d::UnitZ(), false)});
  EXPECT_EQ(c.unplaced, 1u);
  EXPECT_EQ(c.view_directions_part.size(), 1u);
  // No view placed: the first alone, in its own model frame (towards the camera is -z there).
  const ViewCoverage alone = viewCoverage(
      {viewFrom(Eigen::Vector3d::UnitX(), false), viewFrom(Eigen::Vector3d::UnitY(), false)});
  EXPECT_EQ(alone.unplaced, 1u);
  ASSERT_EQ(alone.view_directions_part.size(), 1u);
  EXPECT_NEAR(alone.view_directions_part[0].z(), -1.0, 1e-9);
  EXPECT_THROW(viewCoverage({}), Error);
  ViewCoverageOptions bad;
  bad.tolerance_deg = 0;
  EXPECT_THROW(viewCoverage({viewFrom(Eigen::Vector3d::UnitZ())}, bad), Error);
}

TEST(ViewCoverage, APartSeenFromEverySideCoversEverything) {
  auto all_around = std::make_shared<TaughtModel>(*viewFrom(Eigen::Vector3d::UnitZ()));
  all_around->all_around = true;
  const ViewCoverage c = viewCoverage({all_around});
  EXPECT_DOUBLE_EQ(c.covered, 1.0);
  EXPECT_TRUE(c.missing_part.empty());
}
