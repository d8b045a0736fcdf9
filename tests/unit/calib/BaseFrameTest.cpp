// Poses in the robot base frame (core/calib/BaseFrame.h): the flange pose conventions and the
// chain of transforms of both modes.
#include "core/calib/BaseFrame.h"

#include "tests/support/ErrorText.h"

#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core::calib;

namespace {
Eigen::Isometry3d shifted(const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = t;
  return T;
}
} // namespace

TEST(BaseFrame, RotationVectorIsAxisTimesAngleInDegrees) {
  // 90° about z: x goes to y.
  const Eigen::Isometry3d T = poseFromRotationVector({1, 2, 3}, {0, 0, 90});
  EXPECT_LT((T.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_LT((T.translation() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
  // 180° about x (a flange pointing down) and the zero vector.
  EXPECT_LT((poseFromRotationVector({0, 0, 0}, {180, 0, 0}).linear() * Eigen::Vector3d::UnitZ() +
             Eigen::Vector3d::UnitZ())
                .norm(),
            1e-12);
  EXPECT_TRUE(poseFromRotationVector({0, 0, 0}, {0, 0, 0}).linear().isIdentity());
}

TEST(BaseFrame, FlangePoseTextTakesSixOrSevenNumbers) {
  const Eigen::Isometry3d a = parseFlangePose("10, 20,30,0,0,90", "--flange-pose");
  const double h = std::sqrt(0.5);
  const Eigen::Isometry3d b = parseFlangePose(
      "10,20,30," + std::to_string(h) + ",0,0," + std::to_string(h), "--flange-pose");
  EXPECT_LT((a.matrix() - b.matrix()).norm(), 1e-5);
  EXPECT_EQ(test::errorOf([] { parseFlangePose("1,2,3", "--flange-pose"); }),
            "--flange-pose must be 6 numbers x,y,z,rx,ry,rz (mm; rotation vector in degrees) or 7 "
            "numbers x,y,z,qw,qx,qy,qz (mm; unit quaternion, w first), not 3");
  EXPECT_EQ(test::errorOf([] { parseFlangePose("1,2,,4,5,6", "--flange-pose"); }),
            "--flange-pose '1,2,,4,5,6': expected comma-separated numbers x,y,z,rx,ry,rz (mm; "
            "rotation vector in degrees), e.g. 400,-20,550,180,0,0");
  EXPECT_EQ(test::errorOf([] { parseFlangePose("1,2,3,nan,0,0", "--flange-pose"); }),
            "--flange-pose holds a number that is not finite");
}

TEST(BaseFrame, EyeToHandAndEyeInHandChains) {
  CameraCalibration fixed{HandEyeMode::EyeToHand, shifted({0, 0, 1000}), "fixed.json"};
  EXPECT_TRUE(baseFromCamera(fixed, std::nullopt).isApprox(fixed.T_camera));
  EXPECT_NE(test::errorOf([&] {
              baseFromCamera(fixed, shifted({1, 0, 0}));
            }).find("fixed.json is an eye-to-hand calibration"),
            std::string::npos);
  CameraCalibration riding{HandEyeMode::EyeInHand, shifted({0, 0, 100}), "riding.json"};
  const Eigen::Isometry3d F = poseFromRotationVector({500, 0, 600}, {180, 0, 0});
  // The camera 100 mm along the flange's z, which points down: 500 mm above the base.
  const Eigen::Isometry3d T = baseFromCamera(riding, F);
  EXPECT_LT((T.translation() - Eigen::Vector3d(500, 0, 500)).norm(), 1e-9);
  EXPECT_NE(test::errorOf([&] { baseFromCamera(riding, std::nullopt); })
                .find("riding.json is an eye-in-hand calibration (the camera rides on the "
                      "flange): give the flange pose"),
            std::string::npos);
}
