// Resting poses: stable hull faces merged up to symmetry, probabilities from seeded drops, and
// teach scenes that rest the part on a chosen one.
#include "core/sim/RestingPoses.h"

#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/Scene.h"

#include <gtest/gtest.h>
#include <numeric>

using namespace scanpick::core;

namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Isometry3d turn(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double angle) {
  return Eigen::Translation3d(point) * Eigen::AngleAxisd(angle, axis.normalized()) *
         Eigen::Translation3d(-point);
}

/// A 100 × 60 × 20 mm box centred on the origin; with `symmetric`, its three half turns.
Part box(bool symmetric) {
  Part p;
  p.name = "box";
  p.components = {boxMesh({-50, -30, -10}, {50, 30, 10})};
  if (symmetric)
    for (const Eigen::Vector3d axis :
         {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()})
      p.symmetry.discrete.push_back(turn(Eigen::Vector3d::Zero(), axis, kPi));
  return p;
}

/// A Ø20 × 100 mm rod (32 facets) standing on z = 0; with `symmetric`, its axis and end flip.
Part rod(bool symmetric) {
  Part p;
  p.name = "rod";
  p.components = {revolveProfile({{0, 0}, {10, 0}, {10, 100}, {0, 100}}, 32)};
  if (symmetric) {
    p.symmetry.continuous_axis = SymmetryAxis{{0, 0, 50}, Eigen::Vector3d::UnitZ()};
    p.symmetry.discrete = {turn({0, 0, 50}, Eigen::Vector3d::UnitX(), kPi)};
  }
  return p;
}

double sumOfProbabilities(const std::vector<RestingPose>& poses) {
  return std::accumulate(poses.begin(), poses.end(), 0.0,
                         [](double s, const RestingPose& p) { return s + p.probability; });
}

/// Every pose's rotation is a rotation and puts its face down.
void expectFaceDown(const std::vector<RestingPose>& poses) {
  for (const auto& p : poses) {
    EXPECT_NEAR((p.R_table_part.transpose() * p.R_table_part - Eigen::Matrix3d::Identity()).norm(),
                0.0, 1e-9);
    EXPECT_NEAR(p.R_table_part.determinant(), 1.0, 1e-9);
    EXPECT_NEAR((p.R_table_part * p.down_normal_part).z(), -1.0, 1e-9);
  }
}

} // namespace

TEST(RestingPoses, BoxHasThreeSidesUpToItsSymmetryTheLargestFaceMostProbable) {
  const auto poses = restingPoses(box(true));
  ASSERT_EQ(poses.size(), 3u);
  // Faces 100 × 60, 100 × 20 and 60 × 20 mm, each with its opposite face as symmetric copy; the
  // broadest face is the most likely to end down, the smallest the least.
  EXPECT_NEAR(poses[0].face_area_mm2, 6000, 1);
  EXPECT_NEAR(poses[1].face_area_mm2, 2000, 1);
  EXPECT_NEAR(poses[2].face_area_mm2, 1200, 1);
  EXPECT_NEAR(std::abs(poses[0].down_normal_part.z()), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(poses[1].down_normal_part.y()), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(poses[2].down_normal_part.x()), 1.0, 1e-6);
  for (const auto& p : poses)
    EXPECT_EQ(p.symmetric_copies, 2);
  EXPECT_GT(poses[0].probability, 0.5);
  EXPECT_GT(poses[0].probability, poses[1].probability);
  EXPECT_GT(poses[1].probability, poses[2].probability);
  EXPECT_NEAR(sumOfProbabilities(poses), 1.0, 1e-9);
  expectFaceDown(poses);
}

TEST(RestingPoses, BoxWithoutSymmetryHasSixSides) {
  const auto poses = restingPoses(box(false));
  ASSERT_EQ(poses.size(), 6u);
  double broad = 0; // both 100 × 60 faces together
  for (const auto& p : poses) {
    EXPECT_EQ(p.symmetric_copies, 1);
    if (std::abs(p.down_normal_part.z()) > 0.999)
      broad += p.probability;
  }
  EXPECT_NEAR(std::abs(poses[0].down_normal_part.z()), 1.0, 1e-6);
  EXPECT_GT(broad, 0.5);
  EXPECT_NEAR(sumOfProbabilities(poses), 1.0, 1e-9);
  expectFaceDown(poses);
}

TEST(RestingPoses, CubeIsOneSideAfterTheSymmetryMerge) {
  Part cube;
  cube.name = "cube";
  cube.components = {boxMesh({0, 0, 0}, {40, 40, 40})};
  // Two quarter turns generate the cube's 24 rotations: all six faces are one side.
  cube.symmetry.discrete = {turn({20, 20, 20}, Eigen::Vector3d::UnitX(), kPi / 2),
                            turn({20, 20, 20}, Eigen::Vector3d::UnitY(), kPi / 2)};
  const auto poses = restingPoses(cube);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].symmetric_copies, 6);
  EXPECT_DOUBLE_EQ(poses[0].probability, 1.0);
  EXPECT_NEAR(poses[0].face_area_mm2, 1600, 1);
  expectFaceDown(poses);
}

TEST(RestingPoses, TallThinRodRestsMostlyOnItsSide) {
  const auto poses = restingPoses(rod(true));
  // On its side (all 32 facets, by the axis symmetry) or on an end (both, by the flip).
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_NEAR(poses[0].down_normal_part.z(), 0.0, 1e-6);
  EXPECT_EQ(poses[0].symmetric_copies, 32);
  EXPECT_GT(poses[0].probability, 0.9);
  EXPECT_NEAR(std::abs(poses[1].down_normal_part.z()), 1.0, 1e-6);
  EXPECT_EQ(poses[1].symmetric_copies, 2);
  // A regular 32-gon of radius 10 mm: 16 · 100 · sin(2π/32).
  EXPECT_NEAR(poses[1].face_area_mm2, 1600 * std::sin(2 * kPi / 32), 0.01);
  expectFaceDown(poses);
}

TEST(RestingPoses, NeighbouringFacetsAreOneSideWithoutDeclaredSymmetry) {
  // The rod's facets are 11.25° apart, within the default same-side angle: one side, and the two
  // ends apart (no flip known).
  const auto poses = stableRestingPoses(rod(false));
  ASSERT_EQ(poses.size(), 3u);
  int side = 0;
  for (const auto& p : poses)
    if (std::abs(p.down_normal_part.z()) < 1e-6) {
      ++side;
      EXPECT_EQ(p.symmetric_copies, 32);
    }
  EXPECT_EQ(side, 1);
  RestingPoseParams strict;
  strict.same_side_deg = 5;
  EXPECT_EQ(stableRestingPoses(rod(false), strict).size(), 34u); // 32 facets + 2 ends
}

TEST(RestingPoses, TiltedFaceThatCannotHoldTheCentreOfMassIsNotListed) {
  // A 100 × 20 × 60 mm bar with a 5 mm chamfer along one long edge. The centre of mass (the
  // origin) projects onto the chamfer's plane 27.5 mm along x and y, far off the chamfer strip:
  // that face is unstable. The six others hold it; the narrowest (+x, 15 mm wide, centre of mass
  // 5 mm from its edge at 50 mm height, tip angle atan(5/50) = 5.7°) only while the required tip
  // angle is below that.
  PlateCell cell;
  cell.boundary_mm = {{-50, -10}, {50, -10}, {50, 5}, {45, 10}, {-50, 10}};
  Part bar;
  bar.name = "chamfered";
  bar.components = {extrudeCells({cell}, -30, 30, 8)};
  ASSERT_EQ(openEdgeCount(bar.components[0]), 0u);
  const auto poses = stableRestingPoses(bar);
  ASSERT_EQ(poses.size(), 6u);
  const Eigen::Vector3d chamfer = Eigen::Vector3d(1, 1, 0).normalized();
  for (const auto& p : poses)
    EXPECT_LT(p.down_normal_part.dot(chamfer), 0.75) << p.down_normal_part.transpose();
  RestingPoseParams strict;
  strict.min_tip_angle_deg = 6;
  const auto fewer = stableRestingPoses(bar, strict);
  ASSERT_EQ(fewer.size(), 5u);
  for (const auto& p : fewer)
    EXPECT_LT(p.down_normal_part.x(), 0.99);
}

TEST(RestingPoses, SameSeedSameResult) {
  RestingPoseParams params;
  params.seed = 7;
  params.drops = 60;
  const auto a = restingPoses(box(false), params);
  const auto b = restingPoses(box(false), params);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].probability, b[i].probability);
    EXPECT_EQ(a[i].down_normal_part, b[i].down_normal_part);
    EXPECT_EQ(a[i].R_table_part, b[i].R_table_part);
  }
}

TEST(RestingPoses, NoDropsListsTheSidesAndBadParamsThrow) {
  RestingPoseParams none;
  none.drops = 0;
  const auto poses = restingPoses(box(true), none);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(sumOfProbabilities(poses), 0.0);
  RestingPoseParams bad;
  bad.drops = -1;
  EXPECT_THROW(restingPoses(box(true), bad), Error);
  bad = {};
  bad.same_side_deg = 90;
  EXPECT_THROW(restingPoses(box(true), bad), Error);
  Part flat;
  flat.name = "flat";
  flat.components = {TriangleMesh{{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {10, 10, 0}}, {}}};
  EXPECT_THROW(stableRestingPoses(flat), Error);
}

TEST(RestingPoses, TeachSceneRestsOnTheChosenSide) {
  const Part part = box(false);
  const auto poses = restingPoses(part);
  const SensorModel phoxi = sensorPreset("phoxi-m-1032");
  for (int side = 0; side < static_cast<int>(poses.size()); ++side) {
    SceneSpec spec;
    spec.layout = LayoutKind::Teach;
    spec.parts = {part};
    spec.count = 1;
    spec.seed = 11;
    spec.resting_side = side;
    const Scene scene = buildScene(spec, phoxi);
    const Eigen::Matrix3d R = scene.instances.front().T_world_part.linear();
    const Eigen::Vector3d down = R * poses[static_cast<std::size_t>(side)].down_normal_part;
    EXPECT_GT(-down.z(), std::cos(1.0 * kPi / 180)) << "side " << side;
  }
}

TEST(RestingPoses, TeachSceneRefusesASideThatDoesNotExist) {
  SceneSpec spec;
  spec.layout = LayoutKind::Teach;
  spec.parts = {box(true)};
  spec.count = 1;
  spec.resting_side = 3;
  const SensorModel phoxi = sensorPreset("phoxi-m-1032");
  try {
    (void)buildScene(spec, phoxi);
    FAIL() << "resting side 3 of 3 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has 3 distinct resting sides (0 to 2)"),
              std::string::npos)
        << e.what();
  }
  spec.resting_side = 0;
  spec.teach_side = 1;
  EXPECT_THROW((void)buildScene(spec, phoxi), Error);
  spec.teach_side = 0;
  spec.layout = LayoutKind::Bin;
  EXPECT_THROW((void)buildScene(spec, phoxi), Error);
}
