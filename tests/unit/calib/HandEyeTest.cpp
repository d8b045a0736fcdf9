// The hand-eye solve on exact and noisy sphere centres (no rendering): both modes recover the
// truth, a wrong robot pose is rejected with its reason, and input that cannot determine a
// calibration (too few poses, rotation about one axis, too little rotation) fails with a message
// that says how to record better poses.
#include "core/calib/HandEye.h"

#include "core/common/Error.h"
#include "tests/support/ErrorText.h"
#include "tests/unit/calib/CalibScenes.h"

#include <gtest/gtest.h>
#include <random>

using namespace scanpick;
using namespace scanpick::core::calib;
using test::errorOf;

namespace {

/// The samples a perfect sensor would give for `cell`, with Gaussian noise of `sigma_mm` on each
/// sphere centre.
std::vector<HandEyeSample> samplesOf(const test::SimulatedCell& cell, double sigma_mm = 0,
                                     std::uint64_t seed = 1) {
  const TargetLayout layout = defaultTarget();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_mm > 0 ? sigma_mm : 1.0);
  std::vector<HandEyeSample> samples;
  for (std::size_t i = 0; i < cell.T_base_flange.size(); ++i) {
    HandEyeSample s;
    s.T_base_flange = cell.T_base_flange[i];
    std::vector<Eigen::Vector3d> seen;
    for (const auto& c : layout.sphere_centres_mm) {
      Eigen::Vector3d p = cell.T_camera_target[i] * c;
      if (sigma_mm > 0)
        p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      seen.push_back(p);
      s.observation.centres_camera_mm.emplace_back(p);
    }
    s.observation.T_camera_target = rigidFit(layout.sphere_centres_mm, seen);
    samples.push_back(s);
  }
  return samples;
}

} // namespace

TEST(HandEye, ExactDataGiveTheTruthInBothModes) {
  for (const auto& cell : {test::eyeToHandCell(6, 1), test::eyeInHandCell(6, 2)}) {
    SCOPED_TRACE(modeName(cell.mode));
    const HandEyeResult r = calibrateHandEye(cell.mode, samplesOf(cell), defaultTarget());
    EXPECT_LT(test::distanceBetween_mm(r.T_camera, cell.X), 1e-6);
    EXPECT_LT(test::angleBetween_deg(r.T_camera, cell.X), 1e-6);
    EXPECT_LT(test::distanceBetween_mm(r.T_target, cell.Y), 1e-6);
    EXPECT_LT(test::angleBetween_deg(r.T_target, cell.Y), 1e-6);
    EXPECT_EQ(r.poses_used, 6);
    EXPECT_LT(r.rms_mm, 1e-6);
    ASSERT_EQ(r.residuals.size(), 6u);
    for (const auto& p : r.residuals)
      EXPECT_FALSE(p.rejected);
  }
}

TEST(HandEye, NoiseAveragesOutOverTenPoses) {
  // 0.02 mm noise per centre (what the sphere fit leaves with a PhoXi): the solution lands within
  // 0.05 mm and 0.01° and the residuals show the noise.
  const auto cell = test::eyeToHandCell(10, 3);
  const HandEyeResult r = calibrateHandEye(cell.mode, samplesOf(cell, 0.02, 5), defaultTarget());
  EXPECT_LT(test::distanceBetween_mm(r.T_camera, cell.X), 0.05);
  EXPECT_LT(test::angleBetween_deg(r.T_camera, cell.X), 0.01);
  EXPECT_LT(test::distanceBetween_mm(r.T_target, cell.Y), 0.05);
  EXPECT_GT(r.rms_mm, 0.01);
  EXPECT_LT(r.rms_mm, 0.05);
  EXPECT_EQ(r.poses_used, 10);
}

TEST(HandEye, AWrongRobotPoseIsRejectedAndSaysWhy) {
  auto cell = test::eyeInHandCell(10, 4);
  auto samples = samplesOf(cell, 0.02, 6);
  // Pose 7 was recorded 3 mm and 0.5° away from where the robot really was.
  samples[6].T_base_flange =
      samples[6].T_base_flange * test::pose({3, 0, 0}, test::rotation(0.5, {0, 1, 0}));
  const HandEyeResult r = calibrateHandEye(cell.mode, samples, defaultTarget());
  for (const auto& p : r.residuals)
    EXPECT_EQ(p.rejected, p.index == 6) << p.index;
  EXPECT_NE(r.residuals[6].reason.find("above the limit"), std::string::npos);
  EXPECT_GT(r.residuals[6].rms_mm, 1.0);
  EXPECT_EQ(r.poses_used, 9);
  EXPECT_LT(test::distanceBetween_mm(r.T_camera, cell.X), 0.05);
  EXPECT_LT(test::angleBetween_deg(r.T_camera, cell.X), 0.01);
}

TEST(HandEye, TooFewPosesSayHowManyAreNeeded) {
  const auto cell = test::eyeToHandCell(2, 1);
  const std::string e =
      errorOf([&] { calibrateHandEye(cell.mode, samplesOf(cell), defaultTarget()); });
  EXPECT_NE(e.find("too few poses: 2 given"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 3"), std::string::npos) << e;
  EXPECT_NE(e.find("non-parallel axes"), std::string::npos) << e;
}

TEST(HandEye, RotationsAboutOneAxisAreDegenerate) {
  // The flange only turns about its own z axis (and moves): the camera's offset along that axis
  // cannot be told.
  auto cell = test::eyeToHandCell(0, 1);
  for (int i = 0; i < 6; ++i) {
    const Eigen::Isometry3d A =
        test::pose({400 + 10.0 * i, -100, 600}, test::rotation(25.0 * i, {0, 0, 1}));
    cell.T_base_flange.push_back(A);
    cell.T_camera_target.push_back(cell.X.inverse() * A * cell.Y);
  }
  const std::string e =
      errorOf([&] { calibrateHandEye(cell.mode, samplesOf(cell), defaultTarget()); });
  EXPECT_NE(e.find("degenerate motion: all rotations"), std::string::npos) << e;
  EXPECT_NE(e.find("another axis"), std::string::npos) << e;
}

TEST(HandEye, PosesThatHardlyTurnAreDegenerate) {
  auto cell = test::eyeToHandCell(0, 1);
  for (int i = 0; i < 5; ++i) {
    const Eigen::Isometry3d A =
        test::pose({400 + 30.0 * i, -100 + 20.0 * i, 600}, test::rotation(0.5 * i, {1, 1, 0}));
    cell.T_base_flange.push_back(A);
    cell.T_camera_target.push_back(cell.X.inverse() * A * cell.Y);
  }
  const std::string e =
      errorOf([&] { calibrateHandEye(cell.mode, samplesOf(cell), defaultTarget()); });
  EXPECT_NE(e.find("degenerate motion: the robot poses turn at most 2.0 degrees"),
            std::string::npos)
      << e;
}

TEST(HandEye, ManyDisagreeingPosesFailInsteadOfBeingThrownAway) {
  auto cell = test::eyeToHandCell(6, 9);
  auto samples = samplesOf(cell);
  for (const std::size_t i : {1u, 3u, 5u}) // half the poses are wrong, each differently
    samples[i].T_base_flange = samples[i].T_base_flange *
                               test::pose({5.0 * double(i), 0, 2}, test::rotation(1, {1, 0, 0}));
  const std::string e = errorOf([&] { calibrateHandEye(cell.mode, samples, defaultTarget()); });
  EXPECT_NE(e.find("the poses disagree"), std::string::npos) << e;
}

TEST(HandEye, ModeNames) {
  EXPECT_EQ(modeFromName("eye-to-hand"), HandEyeMode::EyeToHand);
  EXPECT_EQ(modeFromName(modeName(HandEyeMode::EyeInHand)), HandEyeMode::EyeInHand);
  EXPECT_NE(errorOf([] { modeFromName("eye"); }).find("use eye-to-hand"), std::string::npos);
}
