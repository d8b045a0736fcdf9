// Pose refinement on a synthetic L-bracket: the model is one noisy view of it (0.5 mm pixel
// pitch), the scene another view of it with a different sampling, 0.1 mm noise (PhoXi class),
// 2 % dropouts, a floor under it and a box beside it. The true model pose is known exactly.
#include "core/refine/PoseRefinement.h"

#include "core/common/Error.h"
#include "tests/unit/refine/BracketScene.h"

#include <cstring>
#include <gtest/gtest.h>
#include <iostream>

using namespace scanpick;
using test::poseError;
using test::rotationDeg;

namespace {

struct BracketData {
  core::PointCloud model; ///< model frame: teach camera axes, origin at the centroid
  core::PointCloud scene; ///< organized, camera frame, NaN dropouts
  Eigen::Isometry3d T_scene_model_true = Eigen::Isometry3d::Identity();
  test::PlacedSolid bracket_in_scene;
};

const BracketData& data() {
  static const BracketData d = [] {
    BracketData out;
    const test::TaughtView taught = test::teachBracketView();
    out.model = taught.model;

    // Scene view: another orientation and place, seen from 560 mm with f = 900 px (0.62 mm
    // between samples, so no scene point coincides with a model point).
    test::PlacedSolid part{test::lBracket(), Eigen::Isometry3d::Identity()};
    part.T_camera_part.linear() =
        rotationDeg(40, Eigen::Vector3d::UnitZ()) * rotationDeg(10, Eigen::Vector3d::UnitX()) *
        rotationDeg(20, Eigen::Vector3d::UnitY()) * rotationDeg(180, Eigen::Vector3d::UnitX());
    part.T_camera_part.translation() =
        Eigen::Vector3d(20, -10, 560) - part.T_camera_part.linear() * Eigen::Vector3d(30, 20, 20);
    // Clutter: a 50 x 40 x 30 block beside the bracket, and the floor under both.
    test::PlacedSolid block{{test::DrilledBox{{0, 0, 0}, {50, 40, 30}}},
                            Eigen::Isometry3d::Identity()};
    block.T_camera_part.linear() = rotationDeg(15, Eigen::Vector3d::UnitZ());
    block.T_camera_part.translation() = Eigen::Vector3d(55, -5, 550);
    const double floor_z = std::max(test::deepestZ(part), test::deepestZ(block)) + 0.5;
    out.scene = test::renderSolids({part, block}, floor_z, 640, 480, 900, 0.1, 0.02, 22);
    out.T_scene_model_true = taught.modelPose(part.T_camera_part);
    out.bracket_in_scene = part;
    return out;
  }();
  return d;
}

/// The true pose moved by `offset_mm` and turned by `angle_deg` about `axis` through the model
/// origin.
Eigen::Isometry3d perturbed(double offset_mm, const Eigen::Vector3d& direction, double angle_deg,
                            const Eigen::Vector3d& axis) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = rotationDeg(angle_deg, axis);
  Eigen::Isometry3d T = data().T_scene_model_true * delta;
  T.translation() += offset_mm * direction.normalized();
  return T;
}

const core::SceneIndex& sceneIndex() {
  static const core::SceneIndex index(data().scene);
  return index;
}

core::RefineParams defaultParams() {
  return core::RefineParams{};
}

} // namespace

TEST(PoseRefinement, FromThreeMillimetresAndFiveDegreesReachesATenthOfAMillimetre) {
  const core::RefineModel model(data().model, defaultParams().model_points);
  ASSERT_LE(model.size(), 2000u);
  ASSERT_GE(model.size(), 1500u); // the view holds far more points; the subsample is near 2000
  const Eigen::Vector3d directions[] = {{1, 0, 0}, {-1, 2, 0.5}, {0.3, -0.4, -1}};
  const Eigen::Vector3d axes[] = {{0, 0, 1}, {1, 1, 0}, {-0.5, 1, 2}};
  for (int k = 0; k < 3; ++k) {
    const auto start = perturbed(3.0, directions[k], 5.0, axes[k]);
    const auto [t0, r0] = poseError(start, data().T_scene_model_true);
    ASSERT_NEAR(t0, 3.0, 1e-9);
    ASSERT_NEAR(r0, 5.0, 1e-6);
    const auto result = core::refinePose(model, sceneIndex(), start, defaultParams());
    const auto [t, r] = poseError(result.T_scene_model, data().T_scene_model_true);
    std::cout << "case " << k << ": error " << t << " mm, " << r << " deg, rmse " << result.rmse_mm
              << " mm, inliers " << result.inlier_fraction << ", iterations " << result.iterations
              << "\n";
    // Noise 0.1 mm averaged over ~2000 points leaves a few micrometres; the bound is the
    // project's target (sub-0.1 mm), far below the thesis's ~2 mm / 3.5°.
    EXPECT_LT(t, 0.1) << "case " << k;
    EXPECT_LT(r, 0.1) << "case " << k;
    EXPECT_TRUE(result.converged) << "case " << k;
    // The residual is the sensor noise: both clouds carry 0.1 mm, so about 0.14 mm.
    EXPECT_LT(result.rmse_mm, 0.25) << "case " << k;
    // The block hides nothing of the bracket here; some model points fall where the scene view
    // sees no surface (grazing faces, hole walls), so not every point is an inlier.
    EXPECT_GT(result.inlier_fraction, 0.8) << "case " << k;
  }
}

TEST(PoseRefinement, UnorganizedSceneGivesTheSameAccuracy) {
  const core::SceneIndex index(core::dropInvalid(data().scene));
  const auto result = core::refinePose(data().model, index,
                                       perturbed(3.0, {0, 1, 1}, 5.0, {1, 0, 0}), defaultParams());
  const auto [t, r] = poseError(result.T_scene_model, data().T_scene_model_true);
  std::cout << "unorganized: error " << t << " mm, " << r << " deg\n";
  EXPECT_LT(t, 0.1);
  EXPECT_LT(r, 0.1);
  EXPECT_TRUE(result.converged);
}

TEST(PoseRefinement, FromThirtyDegreesNeverClaimsAWrongPose) {
  const core::RefineModel model(data().model, defaultParams().model_points);
  const Eigen::Vector3d axes[] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {1, -1, 1}, {-2, 1, 0.5}};
  int converged = 0;
  for (const auto& axis : axes) {
    const auto result = core::refinePose(model, sceneIndex(), perturbed(3.0, {1, 1, 0}, 30.0, axis),
                                         defaultParams());
    const auto [t, r] = poseError(result.T_scene_model, data().T_scene_model_true);
    std::cout << "30 deg about (" << axis.transpose() << "): converged " << result.converged
              << ", error " << t << " mm, " << r << " deg, inliers " << result.inlier_fraction
              << "\n";
    if (result.converged) {
      ++converged;
      EXPECT_LT(t, 0.1);
      EXPECT_LT(r, 0.1);
    } else {
      // Not converged: either it said so through a poor fit, or it ran out of iterations.
      EXPECT_TRUE(result.inlier_fraction < defaultParams().min_inlier_fraction ||
                  result.iterations == defaultParams().max_iterations);
    }
  }
  std::cout << converged << " of 5 converged from 30 degrees\n";
}

TEST(PoseRefinement, BasinOfConvergenceCoversTheFeatureMatchingError) {
  // The feature matching leaves ~2 mm / 3.5° (thesis §5). Starts that far off, then 5 mm with
  // 10° and 15°, about five axes. Each either converges to the true pose or says it did not
  // (min inliers 0.9).
  const core::RefineModel model(data().model, defaultParams().model_points);
  const Eigen::Vector3d axes[] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {1, -1, 1}, {-2, 1, 0.5}};
  for (const auto& [offset, angle] : {std::pair{2.0, 3.5}, {5.0, 10.0}, {5.0, 15.0}}) {
    int converged = 0;
    for (const auto& axis : axes) {
      const auto result = core::refinePose(
          model, sceneIndex(), perturbed(offset, {1, -1, 1}, angle, axis), defaultParams());
      const auto [t, r] = poseError(result.T_scene_model, data().T_scene_model_true);
      std::cout << offset << " mm, " << angle << " deg about (" << axis.transpose()
                << "): converged " << result.converged << ", error " << t << " mm, " << r
                << " deg, inliers " << result.inlier_fraction << "\n";
      if (result.converged) {
        ++converged;
        EXPECT_LT(t, 0.1) << angle << " deg about " << axis.transpose();
        EXPECT_LT(r, 0.1) << angle << " deg about " << axis.transpose();
      }
    }
    // The steps turn about the pairs' centroid with the rotation scaled by the model radius and
    // leave the directions the surface does not pin down (PoseRefinement.cpp, kStableRatio), so
    // the bracket, whose extrusion axis this view sees edge-on, does not slide along it. None
    // claims convergence wrongly (checked above).
    if (angle == 15.0) {
      EXPECT_GE(converged, 4);
    } else {
      EXPECT_EQ(converged, 5);
    }
  }
}

TEST(PoseRefinement, CoverageScoreSeparatesTrueAndFalsePoses) {
  const core::RefineModel model(data().model, 2000);
  const double at_truth = core::coverageScore(model, sceneIndex(), data().T_scene_model_true, 1.0);
  const double shifted =
      core::coverageScore(model, sceneIndex(), perturbed(15.0, {1, 0, 0}, 0.0, {0, 0, 1}), 1.0);
  const double turned =
      core::coverageScore(model, sceneIndex(), perturbed(0.0, {1, 0, 0}, 90.0, {0, 0, 1}), 1.0);
  std::cout << "coverage: truth " << at_truth << ", shifted 15 mm " << shifted << ", turned 90 deg "
            << turned << "\n";
  EXPECT_GT(at_truth, 0.85);
  EXPECT_LT(shifted, 0.5); // faces parallel to the shift still touch scene surfaces
  EXPECT_LT(turned, 0.5);
  EXPECT_THROW((void)core::coverageScore(model, sceneIndex(), data().T_scene_model_true, 0.0),
               core::Error);
}

TEST(PoseRefinement, EmptyAndNaNOnlyInputsThrow) {
  const core::PointCloud empty;
  core::PointCloud nan_only = data().scene;
  for (auto& p : nan_only.points_mm)
    p = core::invalidPoint();
  const auto start = data().T_scene_model_true;
  EXPECT_THROW((void)core::refinePose(empty, data().scene, start, defaultParams()), core::Error);
  EXPECT_THROW((void)core::refinePose(data().model, empty, start, defaultParams()), core::Error);
  EXPECT_THROW((void)core::refinePose(data().model, nan_only, start, defaultParams()), core::Error);
  EXPECT_THROW((void)core::refinePose(nan_only, data().scene, start, defaultParams()), core::Error);
  EXPECT_THROW(core::SceneIndex{nan_only}, core::Error);
  auto bad = defaultParams();
  bad.max_correspondence_mm = 0;
  EXPECT_THROW((void)core::refinePose(data().model, sceneIndex(), start, bad), core::Error);
  bad = defaultParams();
  bad.min_inlier_fraction = 2;
  EXPECT_THROW((void)core::refinePose(data().model, sceneIndex(), start, bad), core::Error);
}

TEST(PoseRefinement, DirectionsBelowTheStableShareKeepThePoseTheyCameWith) {
  // A caller that places the weakly pinned directions itself holds them: held up to nearly the
  // strongest, a pose 3 mm off stays off; with ICP's own share it settles.
  const core::RefineModel model(data().model, 2000);
  const auto start = perturbed(3.0, {1, 1, 0}, 0.0, {0, 0, 1});
  const auto settled = core::refinePose(model, sceneIndex(), start, defaultParams());
  const auto held = core::refinePose(model, sceneIndex(), start, defaultParams(), {}, 0.99);
  const double settled_mm = poseError(settled.T_scene_model, data().T_scene_model_true).first;
  const double held_mm = poseError(held.T_scene_model, data().T_scene_model_true).first;
  std::cout << "from 3 mm off: " << settled_mm << " mm with ICP's own share, " << held_mm
            << " mm holding all but the strongest directions\n";
  EXPECT_LT(settled_mm, 0.1);
  EXPECT_GT(held_mm, 1.0);
  EXPECT_THROW((void)core::refinePose(model, sceneIndex(), start, defaultParams(), {}, 1.0),
               core::Error);
  EXPECT_THROW((void)core::refinePose(model, sceneIndex(), start, defaultParams(), {}, -0.1),
               core::Error);
}

TEST(PoseRefinement, TwoRunsAreBitwiseIdentical) {
  const auto start = perturbed(3.0, {1, -1, 0}, 5.0, {0, 1, 1});
  const auto a = core::refinePose(data().model, data().scene, start, defaultParams());
  const auto b = core::refinePose(data().model, data().scene, start, defaultParams());
  EXPECT_EQ(std::memcmp(a.T_scene_model.matrix().data(), b.T_scene_model.matrix().data(),
                        sizeof(double) * 16),
            0);
  EXPECT_EQ(a.rmse_mm, b.rmse_mm);
  EXPECT_EQ(a.inlier_fraction, b.inlier_fraction);
  EXPECT_EQ(a.iterations, b.iterations);
}

TEST(PoseRefinement, CancelStops) {
  const core::RefineModel model(data().model, 2000);
  EXPECT_THROW((void)core::refinePose(model, sceneIndex(), data().T_scene_model_true,
                                      defaultParams(), [](double) { return false; }),
               core::Cancelled);
}

TEST(PoseRefinement, PointToPointIsSupportedButCoarser) {
  auto params = defaultParams();
  params.point_to_plane = false;
  params.max_iterations = 100;
  const auto result = core::refinePose(data().model, sceneIndex(),
                                       perturbed(3.0, {1, 0, 0}, 5.0, {0, 0, 1}), params);
  const auto [t, r] = poseError(result.T_scene_model, data().T_scene_model_true);
  std::cout << "point-to-point: error " << t << " mm, " << r << " deg, iterations "
            << result.iterations << "\n";
  // Point-to-point pulls towards the nearest scene samples, which lie up to ~0.3 mm off the
  // model's own samples, so pairs on flat faces resist sliding and it creeps along them: better
  // than the 3 mm / 5° start, far from point-to-plane.
  EXPECT_LT(t, 1.5);
  EXPECT_LT(r, 1.0);
}
