#include "core/matching/RigidFit.h"

#include <gtest/gtest.h>

using namespace scanpick::core;

TEST(RigidFit, RotationBetweenMapsFromOntoTo) {
  const Eigen::Vector3d a = Eigen::Vector3d(1, 2, 3).normalized();
  for (const Eigen::Vector3d& b :
       {Eigen::Vector3d(-2, 0.5, 1).normalized(), a, Eigen::Vector3d(-a)}) {
    const Eigen::Matrix3d R = rotationBetween(a, b);
    EXPECT_LT((R * a - b).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  }
}

TEST(RigidFit, AxisAngleIgnoresSign) {
  EXPECT_NEAR(axisAngle({1, 0, 0}, {-1, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(axisAngle({1, 0, 0}, {0, 1, 0}), M_PI / 2, 1e-12);
}

TEST(RigidFit, TwoPairsRecoverAKnownTransform) {
  // A circle and a non-parallel line fix all six degrees of freedom.
  FeatureList model{{FeatureType::Circle, {0, 0, 0}, {0, 0, 1}, 10.0f, 40},
                    {FeatureType::Line, {30, 5, 0}, {0, 1, 0}, 40.0f, 40}};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(100, -20, 600);
  FeatureList scene = model;
  for (auto& f : scene) {
    f.centre_mm = (T * f.centre_mm.cast<double>()).cast<float>();
    // Flip one axis sign: the fit must pick the sign that agrees with the guess.
    f.direction = -(T.linear() * f.direction.cast<double>()).cast<float>();
  }
  Eigen::Isometry3d guess = T;
  guess.linear() =
      Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).toRotationMatrix() * T.linear();
  const Eigen::Isometry3d fit = fitFeaturePairs(model, scene, {{0, 0}, {1, 1}}, guess);
  EXPECT_LT((fit.matrix() - T.matrix()).norm(), 1e-4);
}
