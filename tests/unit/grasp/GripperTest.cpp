#include "core/grasp/Gripper.h"

#include "core/common/Error.h"
#include "core/grasp/GraspPlanner.h"
#include "core/grasp/GraspPoint.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>

using namespace scanpick::core;
using namespace scanpick::core::grasp;

TEST(Gripper, SuctionCupIsACylinderBehindTheTcpWithTheBodyBehindIt) {
  Gripper g;
  g.suction = {40.0, 12.0};
  g.body.length_mm = 50.0;
  g.body.diameter_mm = 60.0;
  const auto solids = toolSolids(g);
  ASSERT_EQ(solids.size(), 2u);
  EXPECT_EQ(solids[0].name, "cup");
  EXPECT_EQ(solids[0].shape, SolidShape::Cylinder);
  EXPECT_DOUBLE_EQ(solids[0].half_extents_mm.x(), 20.0);
  // The cup spans z in [-12, 0]; the body [-62, -12].
  EXPECT_DOUBLE_EQ(solids[0].centre_mm.z() + solids[0].half_extents_mm.z(), 0.0);
  EXPECT_DOUBLE_EQ(solids[0].centre_mm.z() - solids[0].half_extents_mm.z(), -12.0);
  EXPECT_DOUBLE_EQ(solids[1].centre_mm.z() + solids[1].half_extents_mm.z(), -12.0);
  EXPECT_DOUBLE_EQ(solids[1].centre_mm.z() - solids[1].half_extents_mm.z(), -62.0);
  EXPECT_DOUBLE_EQ(solids[1].half_extents_mm.x(), 30.0);
}

TEST(Gripper, FingersStandOutsideTheOpeningAndReachPastTheGripPoint) {
  Gripper g;
  g.kind = GripperKind::Fingers;
  g.fingers = {8.0, 20.0, 40.0, 50.0, 5.0};
  g.body.length_mm = 0.0;
  const auto solids = toolSolids(g);
  ASSERT_EQ(solids.size(), 3u); // two fingers and the closing region, no body
  const ToolSolid& right = solids[0];
  EXPECT_EQ(right.name, "finger +x");
  EXPECT_TRUE(right.checks_part);
  // Inner face at +25 (half the opening), outer at +33; tip at z = +5, root at -35.
  EXPECT_DOUBLE_EQ(right.centre_mm.x() - right.half_extents_mm.x(), 25.0);
  EXPECT_DOUBLE_EQ(right.centre_mm.x() + right.half_extents_mm.x(), 33.0);
  EXPECT_DOUBLE_EQ(right.centre_mm.z() + right.half_extents_mm.z(), 5.0);
  EXPECT_DOUBLE_EQ(right.centre_mm.z() - right.half_extents_mm.z(), -35.0);
  EXPECT_DOUBLE_EQ(solids[1].centre_mm.x() + solids[1].half_extents_mm.x(), -25.0);
  EXPECT_EQ(solids[2].name, "closing region");
  EXPECT_FALSE(solids[2].checks_part);
  EXPECT_DOUBLE_EQ(solids[2].half_extents_mm.x(), 25.0);
}

TEST(Gripper, BadDimensionsAreRejectedByName) {
  Gripper g;
  g.suction.diameter_mm = 0.0;
  try {
    (void)toolSolids(g);
    FAIL() << "a zero cup diameter was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("suction.diameter_mm"), std::string::npos) << e.what();
  }
  g = Gripper{};
  g.kind = GripperKind::Fingers;
  g.fingers.opening_mm = std::nan("");
  EXPECT_THROW((void)toolSolids(g), Error);
  EXPECT_THROW((void)parseGripperKind("vacuum"), Error);
}

TEST(GraspPoint, SpecsTakeThePositionFromTheModelAndNormalizeDirections) {
  const std::vector<GripPoint> grips{{"top", {1, 2, 3}}, {"side", {4, 5, 6}}};
  const auto all = graspPoints(grips, {});
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].approach, Eigen::Vector3d::UnitZ());
  const auto some = graspPoints(grips, {{"side", {2, 0, 0}, Eigen::Vector3d(1, 1, 0)}});
  ASSERT_EQ(some.size(), 1u);
  EXPECT_EQ(some[0].position_mm, Eigen::Vector3d(4, 5, 6));
  EXPECT_TRUE(some[0].approach.isApprox(Eigen::Vector3d::UnitX()));
  ASSERT_TRUE(some[0].closing_axis);
  // Made perpendicular to the approach.
  EXPECT_TRUE(some[0].closing_axis->isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_THROW((void)graspPoints(grips, {{"handle", {0, 0, 1}, {}}}), Error);
  EXPECT_THROW((void)graspPoints(grips, {{"top", {0, 0, 0}, {}}}), Error);
  EXPECT_THROW((void)graspPoints(grips, {{"top", {0, 0, 1}, Eigen::Vector3d(0, 0, 2)}}), Error);
}

TEST(GraspPoint, AGripPointsTaughtDirectionsApplyUnlessASpecNamesIt) {
  GripPoint side{"side", {4, 5, 6}};
  side.approach = Eigen::Vector3d(-3, 0, 0);
  side.closing_axis = Eigen::Vector3d(0, 2, 1);
  const std::vector<GripPoint> grips{{"top", {1, 2, 3}}, side};
  const auto taught = graspPoints(grips, {});
  ASSERT_EQ(taught.size(), 2u);
  EXPECT_EQ(taught[0].approach, Eigen::Vector3d::UnitZ()); // none taught
  EXPECT_TRUE(taught[1].approach.isApprox(-Eigen::Vector3d::UnitX()));
  ASSERT_TRUE(taught[1].closing_axis);
  EXPECT_TRUE(taught[1].closing_axis->isApprox(Eigen::Vector3d(0, 2, 1).normalized()));
  // A recipe's spec replaces what the grip point was taught with.
  const auto spec = graspPoints(grips, {{"side", {0, 0, 1}, {}}});
  ASSERT_EQ(spec.size(), 1u);
  EXPECT_EQ(spec[0].approach, Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(spec[0].closing_axis);
  // A taught closing axis along the approach is refused.
  side.closing_axis = Eigen::Vector3d(1, 0, 0);
  EXPECT_THROW((void)graspPoints({side}, {}), Error);
}

TEST(GripPoint, MovesWithItsDirectionsAndIsCheckedBeforeUse) {
  GripPoint g{"g", {1, 0, 0}};
  g.approach = Eigen::Vector3d(0, 0, 2);
  g.closing_axis = Eigen::Vector3d(1, 1, 0);
  const GripPoint c = checkedGrip(g);
  EXPECT_TRUE(c.approach->isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(c.closing_axis->isApprox(Eigen::Vector3d(1, 1, 0).normalized()));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).matrix();
  T.translation() = Eigen::Vector3d(0, 0, 100);
  const GripPoint moved = transformed(c, T);
  EXPECT_TRUE(moved.position_mm.isApprox(Eigen::Vector3d(1, 0, 100)));
  EXPECT_TRUE(moved.approach->isApprox(-Eigen::Vector3d::UnitY())); // rotated, not translated
  EXPECT_TRUE(moved.closing_axis->isApprox(T.linear() * *c.closing_axis));
  GripPoint zero = g;
  zero.approach = Eigen::Vector3d::Zero();
  EXPECT_THROW((void)checkedGrip(zero), Error);
  GripPoint no_approach = g;
  no_approach.approach.reset();
  EXPECT_THROW((void)checkedGrip(no_approach), Error); // a closing axis needs an approach
  GripPoint not_finite = g;
  not_finite.position_mm.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)checkedGrip(not_finite), Error);
}

TEST(GraspPoint, TheDefaultApproachGoesIntoTheSurfaceAwayFromTheCamera) {
  // A plane 700 mm in front of the camera, tilted 30 degrees about x, sampled every 2 mm.
  const Eigen::Vector3d normal(0, std::sin(M_PI / 6), -std::cos(M_PI / 6)); // towards the camera
  const Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = normal.cross(u);
  std::vector<Eigen::Vector3f> plane, line;
  for (int i = -10; i <= 10; ++i) {
    line.push_back(Eigen::Vector3f(float(2 * i), 0, 700));
    for (int j = -10; j <= 10; ++j)
      plane.push_back((Eigen::Vector3d(0, 0, 700) + 2.0 * i * u + 2.0 * j * v).cast<float>());
  }
  const Eigen::Vector3d approach =
      surfaceApproach(PointCloud::fromPoints(plane), Eigen::Vector3d(3, 3, 701));
  EXPECT_TRUE(approach.isApprox(-normal, 1e-6)) << approach.transpose();
  EXPECT_THROW((void)surfaceApproach(PointCloud::fromPoints(line), {0, 0, 700}), Error);
  plane.resize(kSurfaceNeighbours - 1);
  EXPECT_THROW((void)surfaceApproach(PointCloud::fromPoints(plane), {0, 0, 700}), Error);
}

TEST(ToolPose, OriginAtTheGripPointZAlongTheApproachXAlongTheClosingAxis) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  T.translation() = Eigen::Vector3d(10, 20, 900);
  GraspPoint g{"g", {5, 0, -3}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()};
  const Eigen::Isometry3d tool = toolPose(T, g);
  EXPECT_TRUE(tool.translation().isApprox(T * g.position_mm));
  EXPECT_TRUE(tool.linear().col(2).isApprox(T.linear() * Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(tool.linear().col(0).isApprox(T.linear() * Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(tool.linear().determinant(), 1.0, 1e-12);
  // Without a closing axis, x follows the scene's x axis (deterministic).
  g.closing_axis.reset();
  const Eigen::Isometry3d free = toolPose(Eigen::Isometry3d::Identity(), g);
  EXPECT_TRUE(free.linear().isApprox(Eigen::Matrix3d::Identity()));
}
