#include "core/verification/SelfOcclusion.h"

#include <gtest/gtest.h>

using namespace scanpick::core;

namespace {

/// A roof over a floor (model frame, mm, samples 1 mm apart): the floor plate spans x -40..40 at
/// z = 0, the roof x -40..0 at z = 20, both y -20..20.
std::vector<Eigen::Vector3f> roofOverFloor() {
  std::vector<Eigen::Vector3f> points;
  for (int x = -40; x <= 40; ++x)
    for (int y = -20; y <= 20; ++y) {
      points.emplace_back(float(x), float(y), 0.0f);
      if (x <= 0)
        points.emplace_back(float(x), float(y), 20.0f);
    }
  return points;
}

/// The model 500 mm in front of the camera, its +z towards the camera.
Eigen::Isometry3f facingCamera() {
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = Eigen::AngleAxisf(float(M_PI), Eigen::Vector3f::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3f(0, 0, 500);
  return T;
}

} // namespace

TEST(SelfOcclusion, TheFloorUnderTheRoofIsHiddenAndTheRestIsNot) {
  const auto points = roofOverFloor();
  const std::vector<char> hidden = selfHidden(points, facingCamera(), 1.0, 3.0f);
  ASSERT_EQ(hidden.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    const bool roof = p.z() > 10.0f;
    // Lines of sight diverge by 4 % over the roof's 20 mm: 2 mm of margin at its edges.
    const bool under_roof = !roof && p.x() < -2.0f && std::abs(p.y()) < 18.0f;
    const bool clear = roof || p.x() > 2.0f;
    if (under_roof) {
      EXPECT_TRUE(hidden[i]) << p.transpose();
    } else if (clear) {
      EXPECT_FALSE(hidden[i]) << p.transpose();
    }
  }
}

TEST(SelfOcclusion, TurnedOverTheRoofHidesNothingOfTheFloor) {
  // Seen from below, the floor is in front: it hides the roof instead.
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.translation() = Eigen::Vector3f(0, 0, 500);
  const auto points = roofOverFloor();
  const std::vector<char> hidden = selfHidden(points, T, 1.0, 3.0f);
  std::size_t roof_hidden = 0, roof = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].z() < 10.0f) {
      EXPECT_FALSE(hidden[i]) << points[i].transpose();
    } else {
      ++roof;
      roof_hidden += hidden[i];
    }
  }
  EXPECT_GT(roof_hidden, roof * 9 / 10);
}

TEST(SelfOcclusion, WithoutASpacingOrBehindTheCameraNothingIsHidden) {
  const auto points = roofOverFloor();
  const auto none = [](const std::vector<char>& hidden) {
    return std::none_of(hidden.begin(), hidden.end(), [](char h) { return h != 0; });
  };
  EXPECT_TRUE(none(selfHidden(points, facingCamera(), 0.0, 3.0f)));
  Eigen::Isometry3f behind = facingCamera();
  behind.translation().z() = 10.0f; // the roof's points lie behind the camera
  EXPECT_TRUE(none(selfHidden(points, behind, 1.0, 3.0f)));
}
