// The axis of revolution of a taught view (core/matching/RevolutionAxis.h): found for a flanged
// pipe seen from its side, refused for views whose turn shows or that pin down no axis; found
// under a detail at a lower share, with the detail's points picked out; refined on the points of
// its wall; and the body such a view stands for, which hides points from a camera or a projector.
#include "core/matching/RevolutionAxis.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

using namespace scanpick::core;

namespace {

struct Oriented {
  std::vector<Eigen::Vector3f> points, normals;
  void add(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    points.push_back(p.cast<float>());
    normals.push_back(n.normalized().cast<float>());
  }
};

constexpr double kPi = std::numbers::pi;

/// The upper half (as a camera above sees it) of a pipe along z (Ø40, 100 mm) with two Ø90
/// flanges 8 mm thick: the pipe's wall, the flanges' rims and their inner faces (normals along z).
Oriented flangedPipeSide() {
  Oriented out;
  for (double angle = 0.0; angle <= kPi; angle += kPi / 60) {
    const Eigen::Vector3d radial(std::cos(angle), std::sin(angle), 0.0);
    for (double z = 8; z <= 92; z += 2)
      out.add(20.0 * radial + Eigen::Vector3d(0, 0, z), radial);
    for (const double z0 : {0.0, 92.0})
      for (double z = z0; z <= z0 + 8; z += 2)
        out.add(45.0 * radial + Eigen::Vector3d(0, 0, z), radial);
    for (double r = 22; r <= 44; r += 2) {
      out.add(r * radial + Eigen::Vector3d(0, 0, 8), Eigen::Vector3d::UnitZ());
      out.add(r * radial + Eigen::Vector3d(0, 0, 92), -Eigen::Vector3d::UnitZ());
    }
  }
  return out;
}

Oriented transformed(const Oriented& in, const Eigen::Isometry3d& T) {
  Oriented out;
  for (std::size_t i = 0; i < in.points.size(); ++i)
    out.add(T * in.points[i].cast<double>(), T.linear() * in.normals[i].cast<double>());
  return out;
}

/// The flanged pipe with a fin on its wall, like a cup's handle: 22 × 41 points in the plane
/// y = 0 from x = 20 to 62 mm, facing along the turn (out of the meridian planes).
Oriented handledPipeSide() {
  Oriented out = flangedPipeSide();
  for (double x = 20; x <= 62; x += 2)
    for (double z = 30; z <= 70; z += 1)
      out.add({x, 0, z}, Eigen::Vector3d::UnitY());
  return out;
}

/// A flat plate: every normal is the same.
Oriented plate() {
  Oriented out;
  for (double x = 0; x <= 80; x += 2)
    for (double y = 0; y <= 80; y += 2)
      out.add({x, y, 0}, Eigen::Vector3d::UnitZ());
  return out;
}

} // namespace

TEST(RevolutionAxis, FindsTheAxisOfAFlangedPipeSeenFromItsSide) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(30, -12, 640);
  const Oriented pipe = transformed(flangedPipeSide(), T);
  const auto axis = fitRevolutionAxis(pipe.points, pipe.normals);
  ASSERT_TRUE(axis);
  EXPECT_GT(axis->inlier_share, 0.99);
  const Eigen::Vector3d true_direction = T.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(std::abs(axis->direction.dot(true_direction)), std::cos(0.2 * kPi / 180));
  EXPECT_NEAR(axis->direction.norm(), 1.0, 1e-9);
  // The fitted point lies on the true axis line.
  const Eigen::Vector3d offset = axis->point_mm - T.translation();
  EXPECT_LT((offset - offset.dot(true_direction) * true_direction).norm(), 0.1);
}

TEST(RevolutionAxis, RefusesViewsThatShowTheirTurnOrPinDownNoAxis) {
  const Oriented handled = handledPipeSide();
  const auto with_handle = fitRevolutionAxis(handled.points, handled.normals);
  EXPECT_FALSE(with_handle) << "share " << (with_handle ? with_handle->inlier_share : 0.0);

  const Oriented flat = plate();
  EXPECT_FALSE(fitRevolutionAxis(flat.points, flat.normals)) << "a plane has no single axis";

  // An L of two plates: each plate's normal is an axis of that plate only.
  Oriented bracket = plate();
  for (double y = 0; y <= 80; y += 2)
    for (double z = 0; z <= 80; z += 2)
      bracket.add({0, y, z}, -Eigen::Vector3d::UnitX());
  EXPECT_FALSE(fitRevolutionAxis(bracket.points, bracket.normals));
}

TEST(RevolutionAxis, SkipsPointsWithoutNormalsAndNeedsEnough) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Oriented pipe = flangedPipeSide();
  for (std::size_t i = 0; i < pipe.normals.size(); i += 3)
    pipe.normals[i] = Eigen::Vector3f(nan, nan, nan);
  EXPECT_TRUE(fitRevolutionAxis(pipe.points, pipe.normals));

  const Oriented few{{pipe.points.begin(), pipe.points.begin() + 10},
                     {pipe.normals.begin() + 1, pipe.normals.begin() + 11}};
  EXPECT_FALSE(fitRevolutionAxis(few.points, few.normals));
  EXPECT_FALSE(fitRevolutionAxis({}, {}));
}

TEST(RevolutionAxis, FindsTheAxisUnderADetailAndPicksOutTheDetail) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(-0.4, Eigen::Vector3d(2, 1, -1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(-25, 40, 710);
  const Oriented plain = handledPipeSide();
  const Oriented handled = transformed(plain, T);
  const std::size_t fin_begin = flangedPipeSide().points.size();
  const auto axis = fitRevolutionAxis(handled.points, handled.normals, 0.17, 0.5);
  ASSERT_TRUE(axis);
  std::printf("share %.3f\n", axis->inlier_share);
  EXPECT_LT(axis->inlier_share, 0.98);
  EXPECT_GT(axis->inlier_share, 0.7);
  // The fin is left out of the fit: the axis is where the pipe's is.
  const Eigen::Vector3d true_direction = T.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_GT(std::abs(axis->direction.dot(true_direction)), std::cos(0.2 * kPi / 180));
  const Eigen::Vector3d offset = axis->point_mm - T.translation();
  EXPECT_LT((offset - offset.dot(true_direction) * true_direction).norm(), 0.1);

  const std::vector<std::uint32_t> detail = detailPoints(handled.points, *axis, 6.0);
  std::size_t on_fin = 0;
  for (const std::uint32_t k : detail)
    on_fin += k >= fin_begin ? 1 : 0;
  // The fin beyond the flanges' rim (x > 48 mm, 7 columns of 41) spans a few degrees about the
  // axis; the fin nearer the axis shares cells with the pipe's wall and the flanges' faces.
  std::printf("%zu detail points, %zu on the fin\n", detail.size(), on_fin);
  EXPECT_GE(on_fin, 7u * 41u);
  EXPECT_EQ(on_fin, detail.size()) << "the pipe and its flanges span 180° at every cell";
}

namespace {

/// Distance of `axis`'s line from the line through `point` along unit `direction`, at `point`,
/// and the angle between them (degrees).
std::pair<double, double> axisError(const RevolutionAxis& axis, const Eigen::Vector3d& point,
                                    const Eigen::Vector3d& direction) {
  const Eigen::Vector3d a = axis.direction.normalized();
  const Eigen::Vector3d to_point = point - axis.point_mm;
  const double offset = (to_point - to_point.dot(a) * a).norm();
  return {offset, std::acos(std::min(1.0, std::abs(a.dot(direction)))) * 180.0 / kPi};
}

} // namespace

TEST(RevolutionAxis, RefinedOnItsWallANoisyViewsAxisComesWithinHundredthsOfAMillimetre) {
  // The pipe with its fin, its points 0.1 mm off along their normals and its normals 3° off (as
  // normals estimated over a radius from such points are): the fit on the normals is tenths off.
  std::mt19937 rng(7);
  std::normal_distribution<double> noise_mm(0.0, 0.1), tilt(0.0, 3.0 * kPi / 180);
  Oriented noisy;
  const Oriented plain = handledPipeSide();
  for (std::size_t i = 0; i < plain.points.size(); ++i) {
    const Eigen::Vector3d n = plain.normals[i].cast<double>();
    const Eigen::Vector3d p = plain.points[i].cast<double>() + noise_mm(rng) * n;
    const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
    noisy.add(p, n + tilt(rng) * u + tilt(rng) * v);
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.9, Eigen::Vector3d(-1, 2, 1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(15, 35, 690);
  const Oriented view = transformed(noisy, T);
  const Eigen::Vector3d true_point = T * Eigen::Vector3d(0, 0, 50);
  const Eigen::Vector3d true_direction = T.linear() * Eigen::Vector3d::UnitZ();

  const auto fitted = fitRevolutionAxis(view.points, view.normals, 0.17, 0.5);
  ASSERT_TRUE(fitted);
  const std::vector<std::uint32_t> detail = detailPoints(view.points, *fitted, 6.0);
  const RevolutionAxis refined = refineRevolutionAxis(view.points, view.normals, *fitted, detail);
  const auto [fit_mm, fit_deg] = axisError(*fitted, true_point, true_direction);
  const auto [refined_mm, refined_deg] = axisError(refined, true_point, true_direction);
  std::printf("fitted on the normals %.3f mm, %.3f deg; refined on the wall %.3f mm, %.3f deg\n",
              fit_mm, fit_deg, refined_mm, refined_deg);
  EXPECT_LT(refined_mm, 0.03);
  EXPECT_LT(refined_deg, 0.03);
  EXPECT_LT(refined_mm, fit_mm);
  EXPECT_NEAR(refined.direction.norm(), 1.0, 1e-9);
  EXPECT_EQ(refined.inlier_share, fitted->inlier_share);
  // Its point is the one nearest the points' centroid, as the fit's.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : view.points)
    centroid += p.cast<double>();
  centroid /= double(view.points.size());
  EXPECT_NEAR((centroid - refined.point_mm).dot(refined.direction), 0.0, 1e-6);
}

TEST(RevolutionAxis, RefinementLeavesAnAxisWithoutAWallToTellAsItIs) {
  // A plate's points all face along the axis through it: none can tell the axis's place.
  const Oriented flat = plate();
  RevolutionAxis axis;
  axis.point_mm = Eigen::Vector3d(40, 40, 0);
  axis.direction = Eigen::Vector3d::UnitZ();
  axis.inlier_share = 1.0;
  const RevolutionAxis refined = refineRevolutionAxis(flat.points, flat.normals, axis);
  EXPECT_EQ(refined.point_mm, axis.point_mm);
  EXPECT_EQ(refined.direction, axis.direction);
  const RevolutionAxis empty = refineRevolutionAxis({}, {}, axis);
  EXPECT_EQ(empty.point_mm, axis.point_mm);
}

namespace {

/// What a camera straight above sees of an upright cup (axis along z, the camera towards −z):
/// the rim (Ø76–Ø88 at z = 100), the inside's bottom (Ø76 at z = 10) and a band of the inside
/// wall (r = 38) near the rim; the rest of the wall it does not see.
std::vector<Eigen::Vector3f> cupFromAbove() {
  std::vector<Eigen::Vector3f> out;
  for (double angle = 0.0; angle < 2 * kPi; angle += kPi / 90) {
    const Eigen::Vector3d radial(std::cos(angle), std::sin(angle), 0.0);
    for (double r = 38; r <= 44; r += 1.5)
      out.push_back((r * radial + Eigen::Vector3d(0, 0, 100)).cast<float>());
    for (double r = 0; r < 38; r += 1.5)
      out.push_back((r * radial + Eigen::Vector3d(0, 0, 10)).cast<float>());
    for (double z = 85; z < 100; z += 1.5)
      out.push_back((38.0 * radial + Eigen::Vector3d(0, 0, z)).cast<float>());
  }
  return out;
}

} // namespace

TEST(RevolvedBody, ItsWallShadowsTheInsideFromALowSourceButNotFromAbove) {
  const RevolutionAxis axis{Eigen::Vector3d(0, 0, 50), Eigen::Vector3d::UnitZ(), 1.0};
  const RevolvedBody body(cupFromAbove(), axis, 2.0);
  const Eigen::Vector3f bottom(20, 0, 10), rim(-41, 0, 100);
  // Straight above the cup and far up at an angle through its mouth: lit, seen.
  EXPECT_FALSE(body.blocks(bottom, {20, 0, 800}));
  EXPECT_FALSE(body.blocks(bottom, {-100, 0, 800}));
  // Lower to the side: the ray leaves the bottom and meets the wall where the view saw it, near
  // the rim (it crosses r = 38 at z = 90).
  EXPECT_TRUE(body.blocks(bottom, {200, 0, 810}));
  // From the other side: across the inside, into the far wall (r = 38 at z = 97).
  EXPECT_TRUE(body.blocks(bottom, {-400, 0, 640}));
  // Where the view did not see the wall (r = 38 at z = 17), the body cannot block.
  EXPECT_FALSE(body.blocks(bottom, {400, 0, 150}));
  // The rim sees everything above it.
  EXPECT_FALSE(body.blocks(rim, {-400, 0, 150}));
  EXPECT_FALSE(body.blocks(rim, {300, 0, 800}));
}

TEST(RevolvedBody, LeavesOutTheDetailAndHasNoBodyWithoutPoints) {
  // The fin of a handled pipe does not become a disc about the axis.
  const Oriented handled = handledPipeSide();
  const std::size_t fin_begin = flangedPipeSide().points.size();
  std::vector<std::uint32_t> fin;
  for (std::size_t k = fin_begin; k < handled.points.size(); ++k)
    fin.push_back(static_cast<std::uint32_t>(k));
  const RevolutionAxis axis{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0};
  // From the inner face of the lower flange (r = 30, z = 8) up and out to (0, 62, 60): the ray
  // crosses z = 30-70 at r = 43-62, where only the fin (at y = 0, x = 20-62) turned about the
  // axis would stand.
  const Eigen::Vector3f flange(0, 30, 8), source(0, 62, 60);
  EXPECT_FALSE(RevolvedBody(handled.points, axis, 2.0, fin).blocks(flange, source));
  EXPECT_TRUE(RevolvedBody(handled.points, axis, 2.0).blocks(flange, source));
  EXPECT_FALSE(RevolvedBody({}, axis, 2.0).blocks(flange, source));
}

TEST(RevolvedBody, ContainsItsSurfaceAtEveryTurnButNotWhatItEncloses) {
  // The flanged pipe seen from one side (angles 0-180°) stands for the whole pipe: its wall at
  // -90° is in the body, the pipe's bore and the gap between its flanges are not.
  const RevolutionAxis axis{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0};
  const RevolvedBody body(flangedPipeSide().points, axis, 2.0);
  EXPECT_TRUE(body.contains({0, -20, 50})); // the pipe's wall, on the side the view did not see
  EXPECT_TRUE(body.contains({-31.8, -31.8, 4})); // a flange, turned 225°
  EXPECT_FALSE(body.contains({0, 0, 50}));       // the bore
  EXPECT_FALSE(body.contains({0, -35, 50}));     // between the flanges
  EXPECT_FALSE(body.contains({0, -20, 110}));    // beyond the pipe's end
  EXPECT_FALSE(RevolvedBody({}, axis, 2.0).contains({0, -20, 50}));
}
