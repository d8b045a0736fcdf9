// Hand-eye calibration with the virtual scanner: a simulated robot moves the
// calibration target in front of a fixed PhoXi M 1032 (eye-to-hand), or the PhoXi on its flange
// over the target lying on a table (eye-in-hand), through 10 poses tilted 10-30° about varied
// axes; each pose is scanned with the sensor's typical noise (σ 0.1 mm, dropouts, flying pixels).
// From the scans and the robot poses alone, the calibration must land within 0.2 mm and 0.05° of
// the truth, for both unknowns; a wrong robot pose among them is found and rejected.
#include "core/calib/HandEye.h"
#include "core/calib/TargetDetection.h"
#include "tests/unit/calib/CalibScenes.h"

#include <gtest/gtest.h>
#include <iostream>

using namespace scanpick;
using namespace scanpick::core::calib;

namespace {

constexpr int kPoses = 10;
constexpr double kGoal_mm = 0.2, kGoal_deg = 0.05;

/// Scans every pose of `cell` and finds the target in each.
std::vector<HandEyeSample> scannedSamples(const test::SimulatedCell& cell) {
  const auto mesh = test::targetMesh(defaultTarget());
  std::vector<HandEyeSample> samples;
  for (int i = 0; i < int(cell.T_base_flange.size()); ++i) {
    HandEyeSample s;
    s.T_base_flange = cell.T_base_flange[std::size_t(i)];
    s.observation = detectTarget(test::scanOf(cell, i, mesh), defaultTarget());
    samples.push_back(s);
  }
  return samples;
}

/// The errors of a result against the truth, printed for docs/calibration.md.
struct Errors {
  double camera_mm, camera_deg, target_mm, target_deg;
};

Errors errorsOf(const HandEyeResult& r, const test::SimulatedCell& cell) {
  const Errors e{
      test::distanceBetween_mm(r.T_camera, cell.X), test::angleBetween_deg(r.T_camera, cell.X),
      test::distanceBetween_mm(r.T_target, cell.Y), test::angleBetween_deg(r.T_target, cell.Y)};
  std::cout << modeName(r.mode) << ": " << r.cameraName() << " off by " << e.camera_mm << " mm / "
            << e.camera_deg << " deg, " << r.targetName() << " off by " << e.target_mm << " mm / "
            << e.target_deg << " deg; residuals " << r.rms_mm << " mm / " << r.rms_deg
            << " deg RMS over " << r.poses_used << " poses\n";
  return e;
}

void expectWithinGoal(const Errors& e) {
  EXPECT_LT(e.camera_mm, kGoal_mm);
  EXPECT_LT(e.camera_deg, kGoal_deg);
  EXPECT_LT(e.target_mm, kGoal_mm);
  EXPECT_LT(e.target_deg, kGoal_deg);
}

/// The eye-to-hand cell and its scans, shared by the tests below (rendering is the slow part).
class EyeToHandSim : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    s_cell = test::eyeToHandCell(kPoses, 11);
    s_samples = scannedSamples(s_cell);
  }
  static inline test::SimulatedCell s_cell;
  static inline std::vector<HandEyeSample> s_samples;
};

} // namespace

TEST_F(EyeToHandSim, TenPhoxiPosesLandWithinTheGoal) {
  const HandEyeResult r = calibrateHandEye(s_cell.mode, s_samples, defaultTarget());
  expectWithinGoal(errorsOf(r, s_cell));
  EXPECT_EQ(r.poses_used, kPoses);
  // The residuals are the sphere fits' noise: hundredths of a millimetre.
  EXPECT_LT(r.rms_mm, 0.05);
  EXPECT_LT(r.rms_deg, 0.02);
}

TEST_F(EyeToHandSim, AWrongRobotPoseIsRejected) {
  // Pose 4's robot pose was typed wrong: 1.5 mm off along y and 0.3° about x.
  auto samples = s_samples;
  samples[3].T_base_flange =
      samples[3].T_base_flange * test::pose({0, 1.5, 0}, test::rotation(0.3, {1, 0, 0}));
  const HandEyeResult r = calibrateHandEye(s_cell.mode, samples, defaultTarget());
  for (const auto& p : r.residuals)
    EXPECT_EQ(p.rejected, p.index == 3) << "pose " << p.index + 1 << ": " << p.rms_mm << " mm";
  EXPECT_NE(r.residuals[3].reason.find("the robot pose or the scan of this pose is wrong"),
            std::string::npos);
  EXPECT_EQ(r.poses_used, kPoses - 1);
  expectWithinGoal(errorsOf(r, s_cell));
}

TEST(EyeInHandSim, TenPhoxiPosesLandWithinTheGoal) {
  // The table under the target fills most of each scan; the plane removal takes it away first.
  const auto cell = test::eyeInHandCell(kPoses, 12);
  const HandEyeResult r = calibrateHandEye(cell.mode, scannedSamples(cell), defaultTarget());
  expectWithinGoal(errorsOf(r, cell));
  EXPECT_EQ(r.poses_used, kPoses);
  EXPECT_LT(r.rms_mm, 0.05);
}
