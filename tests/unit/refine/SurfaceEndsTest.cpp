// Where a part's surface ends (core/refine/SurfaceEnds.h): along a surface of revolution's axis, on
// a cylinder's wall scanned through a pinhole pixel grid, and across a plate seen face-on. The last
// point lies up to a pixel short of each end, at both ends alike.
#include "core/refine/SurfaceEnds.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace {
using namespace scanpick::core;

constexpr double kRadius = 40.0, kHalfLength = 47.5;

/// A cylinder's wall (radius kRadius, heights ±kHalfLength about `centre` along `axis`) where a
/// pinhole camera at the origin, looking along +z with pixels of `pitch` (rad), sees it; the grid
/// starts at the fraction `phase` of a pixel. Pixels whose ray `hidden` rejects (at their hit) see
/// nothing.
template <typename Hidden>
std::vector<Eigen::Vector3f> scanWall(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                                      double pitch, double phase, Hidden hidden) {
  std::vector<Eigen::Vector3f> points;
  const double reach = (kHalfLength + kRadius) / centre.z() / pitch;
  const double cu = centre.x() / centre.z() / pitch, cv = centre.y() / centre.z() / pitch;
  for (int v = int(cv - reach); v <= int(cv + reach); ++v)
    for (int u = int(cu - reach); u <= int(cu + reach); ++u) {
      const Eigen::Vector3d d =
          Eigen::Vector3d((u + phase) * pitch, (v + phase) * pitch, 1.0).normalized();
      // |w + t·d − ((w + t·d)·a)·a|² = r² with w = −centre: a quadratic in t.
      const Eigen::Vector3d w = -centre;
      const Eigen::Vector3d dp = d - d.dot(axis) * axis, wp = w - w.dot(axis) * axis;
      const double a = dp.squaredNorm(), b = 2 * dp.dot(wp),
                   c = wp.squaredNorm() - kRadius * kRadius;
      const double disc = b * b - 4 * a * c;
      if (disc < 0)
        continue;
      const double t = (-b - std::sqrt(disc)) / (2 * a); // the near side
      const Eigen::Vector3d p = t * d;
      const double h = (p - centre).dot(axis);
      if (std::abs(h) > kHalfLength || hidden(h))
        continue;
      points.push_back(p.cast<float>());
    }
  return points;
}

std::vector<Eigen::Vector3f> scanWall(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                                      double pitch, double phase) {
  return scanWall(centre, axis, pitch, phase, [](double) { return false; });
}

constexpr double kFar = 1e9;
const Eigen::Vector3d kOrigin = Eigen::Vector3d::Zero();
/// An axis across the line of sight, turned 7° from the pixel rows so the ends cut the grid at
/// every phase.
const Eigen::Vector3d kAcross =
    Eigen::Vector3d(std::cos(7.0 * M_PI / 180), std::sin(7.0 * M_PI / 180), 0.0);

TEST(AxialEnds, BothEndsAPixelShortAtMostAndTheirMiddleOnThePartsMiddle) {
  const double pitch = 0.7 / 800.0; // 0.7 mm pixels at 800 mm
  const Eigen::Vector3d centre(10, -20, 800);
  for (const double phase : {0.0, 0.3, 0.7}) {
    const auto points = scanWall(centre, kAcross, pitch, phase);
    const AxialEnds ends = findAxialEnds(points, centre, kAcross, kRadius, kOrigin, -kFar, kFar);
    ASSERT_TRUE(ends.low_mm && ends.high_mm) << "phase " << phase;
    EXPECT_GT(*ends.low_mm, -kHalfLength);
    EXPECT_LT(*ends.low_mm, -kHalfLength + 0.7);
    EXPECT_LT(*ends.high_mm, kHalfLength);
    EXPECT_GT(*ends.high_mm, kHalfLength - 0.7);
    EXPECT_NEAR(0.5 * (*ends.low_mm + *ends.high_mm), 0.0, 0.08) << "phase " << phase;
  }
}

TEST(AxialEnds, TheShiftBetweenAViewAndAScanAtAnotherDistanceIsThePosesErrorAlongTheAxis) {
  // The view taught at 630 mm with finer pixels; the scene at 800 mm, the part 0.3 mm further along
  // its axis than the pose says.
  const double pitch = 0.7 / 800.0;
  const Eigen::Vector3d taught(0, 0, 630), posed(-30, 15, 800);
  const auto view = scanWall(taught, kAcross, pitch, 0.2);
  const AxialEnds view_ends = findAxialEnds(view, taught, kAcross, kRadius, kOrigin, -kFar, kFar);
  for (const double error : {-0.6, 0.3, 1.2}) {
    const auto scene = scanWall(posed + error * kAcross, kAcross, pitch, 0.55);
    const AxialEnds scene_ends =
        findAxialEnds(scene, posed, kAcross, kRadius, kOrigin, -kFar, kFar);
    const std::optional<double> shift = axialShift(view_ends, scene_ends, 2.0, 0.5);
    ASSERT_TRUE(shift) << "error " << error;
    EXPECT_NEAR(*shift, error, 0.08);
  }
}

TEST(AxialEnds, AnEndHiddenByANeighbourLeavesTheOtherToTell) {
  const double pitch = 0.7 / 800.0;
  const Eigen::Vector3d centre(0, 0, 800);
  const auto view = scanWall(Eigen::Vector3d(0, 0, 650), kAcross, pitch, 0.4);
  const AxialEnds view_ends =
      findAxialEnds(view, Eigen::Vector3d(0, 0, 650), kAcross, kRadius, kOrigin, -kFar, kFar);
  // A neighbour lies over the high end: the wall is seen up to 30 mm only.
  const auto scene =
      scanWall(centre + 0.4 * kAcross, kAcross, pitch, 0.1, [](double h) { return h > 30.0; });
  const AxialEnds ends = findAxialEnds(scene, centre, kAcross, kRadius, kOrigin, -kFar, kFar);
  ASSERT_TRUE(ends.low_mm);
  // The high "end" is where the neighbour starts, 17 mm short: no end of the part.
  const std::optional<double> shift = axialShift(view_ends, ends, 2.0, 0.5);
  ASSERT_TRUE(shift);
  EXPECT_NEAR(*shift, 0.4, 0.1);
}

/// A closed cylinder (wall and end faces) tilted towards the camera, so that its low end face is
/// seen at an angle: its points with their normals and 0.1 mm of depth noise along each ray.
struct ScannedCylinder {
  std::vector<Eigen::Vector3f> points, normals;
};
ScannedCylinder scanClosedCylinder(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                                   double pitch) {
  ScannedCylinder out;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.1);
  const double reach = (kHalfLength + kRadius) / centre.z() / pitch;
  const double cu = centre.x() / centre.z() / pitch, cv = centre.y() / centre.z() / pitch;
  for (int v = int(cv - reach); v <= int(cv + reach); ++v)
    for (int u = int(cu - reach); u <= int(cu + reach); ++u) {
      const Eigen::Vector3d d = Eigen::Vector3d((u + 0.3) * pitch, v * pitch, 1.0).normalized();
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      const Eigen::Vector3d w = -centre;
      const Eigen::Vector3d dp = d - d.dot(axis) * axis, wp = w - w.dot(axis) * axis;
      const double a = dp.squaredNorm(), b = 2 * dp.dot(wp),
                   c = wp.squaredNorm() - kRadius * kRadius;
      if (const double disc = b * b - 4 * a * c; disc >= 0) {
        const double t = (-b - std::sqrt(disc)) / (2 * a);
        const Eigen::Vector3d q = t * d - centre;
        if (std::abs(q.dot(axis)) <= kHalfLength) {
          best = t;
          normal = (q - q.dot(axis) * axis).normalized();
        }
      }
      for (const double side : {-1.0, 1.0}) {
        const double t = (centre + side * kHalfLength * axis).dot(axis) / d.dot(axis);
        const Eigen::Vector3d q = t * d - centre;
        if (t > 0 && t < best && (q - q.dot(axis) * axis).norm() <= kRadius) {
          best = t;
          normal = side * axis;
        }
      }
      if (!std::isfinite(best))
        continue;
      out.points.push_back(((best + noise(random)) * d).cast<float>());
      out.normals.push_back(normal.cast<float>());
    }
  return out;
}

TEST(AxialEnds, AnEndFaceSeenAtAnAngleDoesNotEndTheWall) {
  const double pitch = 0.7 / 800.0;
  const Eigen::Vector3d centre(0, 0, 800);
  // The axis 35° out of the image plane: its low end face turns towards the camera.
  const Eigen::Vector3d axis = (std::cos(35.0 * M_PI / 180) * kAcross +
                                std::sin(35.0 * M_PI / 180) * Eigen::Vector3d::UnitZ())
                                   .normalized();
  const ScannedCylinder scan = scanClosedCylinder(centre, axis, pitch);
  const AxialEnds with_faces =
      findAxialEnds(scan.points, centre, axis, kRadius, kOrigin, -kFar, kFar);
  const AxialEnds walls_only =
      findAxialEnds(scan.points, centre, axis, kRadius, kOrigin, -kFar, kFar, {}, scan.normals);
  ASSERT_TRUE(walls_only.low_mm && walls_only.high_mm);
  const double middle = 0.5 * (*walls_only.low_mm + *walls_only.high_mm);
  std::printf("middle of the wall's ends %.3f mm\n", middle);
  EXPECT_NEAR(middle, 0.0, 0.08);
  // With the end face's points, its rim seen all round the axis ends the bins behind the wall at
  // the low end too: the high end is lost, or the middle is off.
  EXPECT_TRUE(!with_faces.low_mm || !with_faces.high_mm ||
              std::abs(0.5 * (*with_faces.low_mm + *with_faces.high_mm)) > std::abs(middle));
}

TEST(AxialEnds, AnAxisAlongTheLineOfSightShowsNoEnds) {
  const Eigen::Vector3d centre(0, 0, 800), along = Eigen::Vector3d(0.2, 0, 1).normalized();
  const auto points = scanWall(centre, kAcross, 0.7 / 800.0, 0.0);
  const AxialEnds ends = findAxialEnds(points, centre, along, kRadius, kOrigin, -kFar, kFar);
  EXPECT_FALSE(ends.low_mm);
  EXPECT_FALSE(ends.high_mm);
}

TEST(AxialEnds, TooFewPointsShowNoEnd) {
  const std::vector<Eigen::Vector3f> few{{40, 0, 0}, {40, 0, 10}, {0, 40, -10}};
  const AxialEnds ends = findAxialEnds(few, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                                       kRadius, Eigen::Vector3d(0, -800, 0), -kFar, kFar);
  EXPECT_FALSE(ends.low_mm);
  EXPECT_FALSE(ends.high_mm);
}

TEST(AxialEnds, ShiftsThatDisagreeOrReachTooFarDoNotCount) {
  const AxialEnds view{-47.0, 47.0};
  // Both ends moved alike: their mean.
  EXPECT_NEAR(*axialShift(view, {-46.8, 47.3}, 2.0, 0.5), 0.25, 1e-12);
  // Ends that disagree by more than 0.5 mm: the part is not where either says.
  EXPECT_FALSE(axialShift(view, {-46.0, 47.2}, 2.0, 0.5));
  // An end 94 mm off is the other end (the wall hidden): the near one tells.
  EXPECT_NEAR(*axialShift(view, {47.1, 47.1}, 2.0, 0.5), 0.1, 1e-12);
  // One end seen in the view only: nothing to compare.
  EXPECT_FALSE(axialShift({std::nullopt, 47.0}, {-46.9, std::nullopt}, 2.0, 0.5));
}

TEST(AxialEnds, OuterRadiusIsTheWallsNotAFewStrayPoints) {
  const Eigen::Vector3d centre(0, 0, 800);
  auto points = scanWall(centre, kAcross, 0.7 / 800.0, 0.0);
  points.push_back((centre + Eigen::Vector3d(0, 0, -70)).cast<float>()); // a stray point
  EXPECT_NEAR(outerRadius(points, centre, kAcross), kRadius, 0.01);
  EXPECT_EQ(outerRadius({}, centre, kAcross), 0.0);
}

/// A 60 × 30 mm plate face-on at depth `depth_mm` (in its own frame: x along 60 mm, centred on
/// `centre_mm`), as a camera with pixels of `pitch` (rad) turned 7° about its axis samples it; the
/// points where `hidden` says (relative to the plate's centre) are left out.
template <typename Hidden>
std::vector<Eigen::Vector3f> scanPlate(double depth_mm, double pitch,
                                       const Eigen::Vector2d& centre_mm, Hidden hidden) {
  const double step = pitch * depth_mm, turn = 7.0 * M_PI / 180;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(turn).toRotationMatrix();
  std::vector<Eigen::Vector3f> points;
  for (int i = -80; i <= 80; ++i)
    for (int j = -80; j <= 80; ++j) {
      const Eigen::Vector2d sample = R * Eigen::Vector2d((i + 0.37) * step, j * step);
      const Eigen::Vector2d q = sample - centre_mm;
      if (std::abs(q.x()) <= 30 && std::abs(q.y()) <= 15 && !hidden(q))
        points.emplace_back(static_cast<float>(sample.x()), static_cast<float>(sample.y()), 0.0f);
    }
  return points;
}

TEST(OutlineShift, APlateSeenFaceOnIsPlacedInItsOwnPlaneToTheScansEnds) {
  const double pitch = 0.7 / 800.0;
  const auto none = [](const Eigen::Vector2d&) { return false; };
  const auto view = scanPlate(630, pitch, Eigen::Vector2d::Zero(), none);
  for (const double error : {-0.45, 0.2, 0.8}) {
    // The part lies `error` further along x than the pose puts it: so it appears in the pose's
    // model frame.
    const auto scene = scanPlate(800, pitch, Eigen::Vector2d(error, 0.0), none);
    const std::optional<double> shift = outlineShift(view, scene, Eigen::Vector3d::UnitX());
    ASSERT_TRUE(shift) << "error " << error;
    EXPECT_NEAR(*shift, error, 0.08);
  }
}

TEST(OutlineShift, OtherViewsTellWhereAViewsEndWasHiddenWhenItWasTaught) {
  const double pitch = 0.7 / 800.0;
  const auto none = [](const Eigen::Vector2d&) { return false; };
  // Taught from a bin: a neighbour hid the plate's long top edge right of x = −10 mm (the view
  // ends along a slant 4-8 mm short there); the other views saw all of it.
  const auto view = scanPlate(630, pitch, Eigen::Vector2d::Zero(), [](const Eigen::Vector2d& q) {
    return q.x() > -10 && q.y() > 11 - 0.1 * (q.x() + 10);
  });
  const auto others = scanPlate(650, pitch, Eigen::Vector2d::Zero(), none);
  const auto scene = scanPlate(800, pitch, Eigen::Vector2d(0.0, 0.3), none);
  const std::optional<double> confirmed =
      outlineShift(view, scene, Eigen::Vector3d::UnitY(), {&others});
  ASSERT_TRUE(confirmed);
  EXPECT_NEAR(*confirmed, 0.3, 0.08);
  // Without them, most cells of the top edge end where the neighbour hid it: that side says
  // nothing, and one side alone does not tell.
  EXPECT_FALSE(outlineShift(view, scene, Eigen::Vector3d::UnitY()));
}

TEST(OutlineShift, OneSideAloneDoesNotTell) {
  const double pitch = 0.7 / 800.0;
  const auto none = [](const Eigen::Vector2d&) { return false; };
  const auto view = scanPlate(630, pitch, Eigen::Vector2d::Zero(), none);
  // A neighbour covers the plate's right half in the scene.
  const auto scene = scanPlate(800, pitch, Eigen::Vector2d::Zero(),
                               [](const Eigen::Vector2d& q) { return q.x() > 0; });
  EXPECT_FALSE(outlineShift(view, scene, Eigen::Vector3d::UnitX()));
}

} // namespace
