// The pick judge of the virtual bin-clearing run on hand-made cases: two box parts on a floor
// (scene frame z up), a suction gripper coming straight down.
#include "core/grasp/PickJudge.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace scanpick::core::grasp;
using ::testing::HasSubstr;

namespace {

const Eigen::Vector3d kHalf(30, 20, 15); // a 60 x 40 x 30 mm box part, resting on z = 0

/// Points every millimetre on the faces of the box part centred at `centre`.
std::vector<Eigen::Vector3d> boxSurface(const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> out;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (double sign : {-1.0, 1.0})
      for (double u = -kHalf[b]; u <= kHalf[b]; u += 1.0)
        for (double v = -kHalf[c]; v <= kHalf[c]; v += 1.0) {
          Eigen::Vector3d p;
          p[a] = sign * kHalf[a];
          p[b] = u;
          p[c] = v;
          out.push_back(centre + p);
        }
  }
  return out;
}

/// The tool straight down (tool +z = scene -z) with its centre point at `at`.
Eigen::Isometry3d downAt(const Eigen::Vector3d& at) {
  Eigen::Isometry3d T(Eigen::AngleAxisd(3.14159265358979323846, Eigen::Vector3d::UnitX()));
  T.translation() = at;
  return T;
}

/// A box part at `centre` whose one true grasp is the middle of its top face, from above.
TruthInstance boxInstance(int id, const Eigen::Vector3d& centre) {
  TruthInstance t;
  t.id = id;
  t.T_scene_tool.push_back(downAt(centre + Eigen::Vector3d(0, 0, kHalf.z())));
  t.surface_mm = boxSurface(centre);
  for (const auto& p : t.surface_mm)
    t.bounds_mm.extend(p);
  return t;
}

const Eigen::Vector3d kTopOfA(0, 0, 30); // middle of part 0's top face

} // namespace

TEST(PickJudge, AGraspOnATrueGripPointIsRight) {
  const std::vector<TruthInstance> parts{boxInstance(0, {0, 0, 15}), boxInstance(1, {200, 0, 15})};
  const PickVerdict v = judgePick(downAt(kTopOfA + Eigen::Vector3d(1, 1, 0)), Gripper{}, parts, {});
  EXPECT_FALSE(v.wrong);
  EXPECT_EQ(v.instance, 0);
  EXPECT_NEAR(v.position_error_mm, std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(v.approach_error_deg, 0.0, 1e-6);
  EXPECT_TRUE(v.collisions.empty());
  EXPECT_TRUE(v.success());
}

TEST(PickJudge, AGrasp20mmOffIsWrong) {
  const std::vector<TruthInstance> parts{boxInstance(0, {0, 0, 15}), boxInstance(1, {200, 0, 15})};
  const PickVerdict v =
      judgePick(downAt(kTopOfA + Eigen::Vector3d(20, 0, 0)), Gripper{}, parts, {});
  EXPECT_TRUE(v.wrong);
  EXPECT_EQ(v.instance, -1);
  EXPECT_NEAR(v.position_error_mm, 20.0, 1e-9);
  EXPECT_FALSE(v.success());
}

TEST(PickJudge, AnApproachTiltedPastTheToleranceIsWrong) {
  const std::vector<TruthInstance> parts{boxInstance(0, {0, 0, 15})};
  Eigen::Isometry3d T = downAt(kTopOfA);
  T.linear() =
      Eigen::AngleAxisd(10.0 * 3.14159265358979323846 / 180, Eigen::Vector3d::UnitY()) * T.linear();
  const PickVerdict v = judgePick(T, Gripper{}, parts, {});
  EXPECT_TRUE(v.wrong);
  EXPECT_NEAR(v.approach_error_deg, 10.0, 1e-6);
}

TEST(PickJudge, AGripperOverlappingAnotherInstanceIsACollision) {
  // Part 1 stands 45 mm beside part 0 and 15 mm higher: its top reaches into the 63 mm flange
  // behind the 30 mm cup (the flange's radius 31.5 mm covers part 1's near edge at x = 15 mm).
  const std::vector<TruthInstance> parts{boxInstance(0, {0, 0, 15}), boxInstance(1, {45, 0, 30})};
  const PickVerdict v = judgePick(downAt(kTopOfA), Gripper{}, parts, {});
  EXPECT_FALSE(v.wrong);
  EXPECT_EQ(v.instance, 0);
  ASSERT_FALSE(v.collisions.empty());
  EXPECT_THAT(v.collisions.front(), HasSubstr("hits instance 1"));
  EXPECT_FALSE(v.success());
}

TEST(PickJudge, AGripperCrossingTheBinWallIsACollision) {
  BinBox bin; // bin frame = scene frame: floor at z = 0, walls at x = ±25 and y = ±100, 150 high
  bin.half_size_mm = {25, 100};
  bin.rim_height_mm = 150;
  bin.floor_found = true;
  bin.walls_found = {true, true, true, true};
  const std::vector<TruthInstance> parts{boxInstance(0, {0, 0, 15})};
  const PickVerdict v = judgePick(downAt(kTopOfA), Gripper{}, parts, bin);
  ASSERT_FALSE(v.collisions.empty()); // the 63 mm flange does not fit between walls 50 mm apart...
  EXPECT_THAT(v.collisions.front(), HasSubstr("hits the bin wall"));
  bin.half_size_mm = {100, 100}; // ... but it does between walls 200 mm apart
  EXPECT_TRUE(judgePick(downAt(kTopOfA), Gripper{}, parts, bin).success());
}
