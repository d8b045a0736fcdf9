// Projector shadows (beyond the thesis): where a structured-light scan has no point because
// measured surface kept the projector's light off (a cup's inside behind its rim, the floor beside
// a part), verification counts the model neither confirmed nor missing there; so also where the
// part's own body, as a view of a surface of revolution stands for it, hides it. And the same
// verification looking for scene points in pixel windows of the organized scan.
#include "core/ambiguity/ModelPrep.h"
#include "core/keypoints/Keypoints.h"
#include "core/refine/PoseRefinement.h"
#include "tests/integration/SynthTeach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>

using namespace scanpick;
using namespace scanpick::core;

TEST(ProjectorShadow, TheFloorBehindAPlateIsShadowed) {
  // A 100 mm square plate 100 mm above the floor, seen by the PhoXi from 1 m: the floor is
  // unmeasured where the plate blocks the projector's light (its projector sits 300 mm aside).
  const SensorModel sensor = sensorPreset("phoxi-m-1032");
  const Eigen::Vector3d projector = sensor.projectorPosition();
  const auto onPlate = [](const Eigen::Vector3d& p) {
    return std::abs(p.x()) <= 50.0 && std::abs(p.y()) <= 50.0;
  };
  PointCloud scan;
  scan.width = std::uint32_t(sensor.width);
  scan.height = std::uint32_t(sensor.height);
  std::vector<Eigen::Vector3f> in_shadow, lit_floor;
  for (int v = 0; v < sensor.height; ++v)
    for (int u = 0; u < sensor.width; ++u) {
      const Eigen::Vector3d ray((u - sensor.cx) / sensor.fx, (v - sensor.cy) / sensor.fy, 1.0);
      const Eigen::Vector3d plate = 900.0 * ray, floor = 1000.0 * ray;
      Eigen::Vector3f point = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
      if (onPlate(plate)) {
        point = plate.cast<float>();
      } else if (onPlate(floor + 0.1 * (projector - floor))) { // its light crosses z = 900 there
        in_shadow.push_back(floor.cast<float>());
      } else {
        point = floor.cast<float>();
        lit_floor.push_back(point);
      }
      scan.points_mm.push_back(point);
    }
  const ProjectorShadow shadow(scan, sensor);
  const auto count = [&](const std::vector<Eigen::Vector3f>& points) {
    return std::count_if(points.begin(), points.end(),
                         [&](const Eigen::Vector3f& p) { return shadow.shadowed(p, 3.0f); });
  };
  const auto shadowed = std::size_t(count(in_shadow)), lit_shadowed = std::size_t(count(lit_floor));
  std::printf("floor: %zu of %zu unlit points shadowed, %zu of %zu lit ones\n", shadowed,
              in_shadow.size(), lit_shadowed, lit_floor.size());
  ASSERT_GT(in_shadow.size(), 2000u);
  EXPECT_GT(shadowed, in_shadow.size() * 98 / 100);
  // Lit floor taken for shadow: only along the shadow's edge, within the pixel the test allows.
  EXPECT_LT(lit_shadowed, in_shadow.size() / 6);
  EXPECT_LT(lit_shadowed, lit_floor.size() / 1000);
}

TEST(ProjectorShadow, ShadowedPointsAreNeitherConfirmedNorExpected) {
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::VerifyCase c = test::verifyCase("cup", params, 5, 9, 0);
  const ProjectorShadow shadow(c.scan.render.cloud, c.scan.sensor);
  const VerifyScene blind{c.index.get(), &c.scan.render.cloud, &c.scan.sensor, std::nullopt};
  const VerifyScene knowing{c.index.get(), &c.scan.render.cloud, &c.scan.sensor, std::nullopt,
                            &shadow};
  const double tolerance = params.matching.verify_tolerance_mm;
  const PointTally t_blind = tallyPoints(*c.view, blind, c.T_true, tolerance);
  const PointTally t_knowing = tallyPoints(*c.view, knowing, c.T_true, tolerance);
  const double q_blind = verifyPose(*c.view, blind, c.T_true, tolerance, {});
  const double q_knowing = verifyPose(*c.view, knowing, c.T_true, tolerance, {});
  std::printf("true pose: %zu of %zu points confirmed, %zu shadowed; coverage %.3f -> %.3f\n",
              t_knowing.confirmed, t_knowing.points, t_knowing.shadowed, q_blind, q_knowing);
  EXPECT_EQ(t_blind.shadowed, 0u);
  EXPECT_EQ(t_knowing.confirmed, t_blind.confirmed); // the shadow takes only unmeasured points
  EXPECT_EQ(t_knowing.violations, t_blind.violations);
  EXPECT_GE(q_knowing, q_blind);
}

TEST(ProjectorShadow, PixelWindowsVerifyAsTheKdTreeDoes) {
  // On an organized scan whose points lie where the sensor projects them, verification looks for
  // a model point's scene neighbours in the pixel window that must hold them: the same tallies.
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::VerifyCase c = test::verifyCase("cup", params, 5, 9, 0);
  SceneIndexOptions with_sensor;
  with_sensor.sensor = c.scan.sensor;
  const SceneIndex windowed(c.floor.remaining, with_sensor);
  EXPECT_GE(windowed.pixelSlack(), 0.0f);
  EXPECT_LT(windowed.pixelSlack(), 0.01f) << "the renderer puts each point on its pixel's ray";
  const ProjectorShadow shadow(c.scan.render.cloud, c.scan.sensor);
  const VerifyScene tree{c.index.get(), &c.scan.render.cloud, &c.scan.sensor, std::nullopt,
                         &shadow};
  VerifyScene windows = tree;
  windows.index = &windowed;
  const double tolerance = params.matching.verify_tolerance_mm;
  std::size_t confirmed = 0;
  for (const double shift_mm : {0.0, 0.4, 0.9, 3.0}) {
    Eigen::Isometry3d T = c.T_true;
    T.translation() += Eigen::Vector3d(shift_mm, -0.5 * shift_mm, 0.3 * shift_mm);
    T.linear() = T.linear() * Eigen::AngleAxisd(0.01 * shift_mm, Eigen::Vector3d::UnitX());
    const PointTally a = tallyPoints(*c.view, tree, T, tolerance);
    const PointTally b = tallyPoints(*c.view, windows, T, tolerance);
    EXPECT_EQ(b.confirmed, a.confirmed) << "shifted " << shift_mm << " mm";
    EXPECT_EQ(b.violations, a.violations);
    EXPECT_EQ(b.hidden, a.hidden);
    EXPECT_EQ(b.shadowed, a.shadowed);
    confirmed += a.confirmed;
  }
  EXPECT_GT(confirmed, c.view->points.size()) << "poses the scan confirms in part";
  // ICP's nearest points come from the same windows: bitwise the same refinement.
  Eigen::Isometry3d start = c.T_true;
  start.translation() += Eigen::Vector3d(1.5, -1.0, 0.5);
  const RefinementResult by_tree =
      refinePose(c.taught.model->cloud_mm, *c.index, start, params.refine);
  const RefinementResult by_windows =
      refinePose(c.taught.model->cloud_mm, windowed, start, params.refine);
  EXPECT_TRUE(by_tree.T_scene_model.isApprox(by_windows.T_scene_model, 0.0));
  EXPECT_EQ(by_tree.iterations, by_windows.iterations);
  EXPECT_EQ(by_tree.rmse_mm, by_windows.rmse_mm);
  EXPECT_LT((by_tree.T_scene_model.translation() - c.T_true.translation()).norm(), 0.5)
      << "ICP comes back from 1.9 mm";
}

TEST(ProjectorShadow, TheEdgeCheckLooksInPixelWindowsAsInTheKdTree) {
  // The scene's keypoints put at their pixels (edgeKeypointCloud) let the edge check look in pixel
  // windows too: the same scores as with them in a list and the kd-tree.
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  ASSERT_GT(params.matching.edge_tolerance_mm, 0.0);
  const test::VerifyCase c = test::verifyCase("support", params, 5, 9, 0);
  const Keypoints keypoints = extractKeypoints(dropInvalid(c.floor.remaining), params.keypoints);
  ASSERT_GT(keypoints.points_mm.size(), 100u);
  const PointCloud image = edgeKeypointCloud({keypoints, keypoints}, c.scan.sensor);
  ASSERT_EQ(int(image.width), c.scan.sensor.width) << "each keypoint in its own pixel";
  ASSERT_EQ(image.validCount(), keypoints.points_mm.size()) << "found twice, counted once";
  PointCloud list = PointCloud::fromPoints(keypoints.points_mm);
  SceneIndexOptions nearest_only;
  nearest_only.estimate_normals = false;
  const SceneIndex as_list(list, nearest_only);
  nearest_only.sensor = c.scan.sensor;
  const SceneIndex by_pixel(image, nearest_only);
  EXPECT_GE(by_pixel.pixelSlack(), 0.0f);
  EXPECT_LT(by_pixel.pixelSlack(), 0.01f);
  const double tolerance = params.matching.verify_tolerance_mm;
  const EdgeCheck tree{&as_list, params.matching.edge_tolerance_mm};
  const EdgeCheck windows{&by_pixel, params.matching.edge_tolerance_mm};
  SceneIndexOptions with_sensor;
  with_sensor.sensor = c.scan.sensor;
  const SceneIndex windowed(c.floor.remaining, with_sensor);
  VerifyScene scene;
  scene.index = &windowed;
  scene.scan = &c.scan.render.cloud;
  scene.sensor = &c.scan.sensor;
  bool edges_decide = false;
  for (const double shift_mm : {0.0, 0.8, 1.6, 3.0}) {
    Eigen::Isometry3d T = c.T_true;
    T.translation() += Eigen::Vector3d(shift_mm, 0.5 * shift_mm, -0.2 * shift_mm);
    const double a = verifyPose(*c.view, scene, T, tolerance, tree);
    EXPECT_EQ(verifyPose(*c.view, scene, T, tolerance, windows), a) << "shifted " << shift_mm;
    edges_decide = edges_decide || a != verifyPose(*c.view, scene, T, tolerance, {});
  }
  EXPECT_TRUE(edges_decide) << "the edge check lowers the score of a shifted pose";
  // Points that share a pixel cannot be put at their pixels: a list then.
  PointCloud doubled = list;
  doubled.points_mm.push_back(list.points_mm.front() + Eigen::Vector3f(0.01f, 0.0f, 0.0f));
  Keypoints doubled_keypoints;
  doubled_keypoints.points_mm = doubled.points_mm;
  EXPECT_EQ(edgeKeypointCloud({doubled_keypoints}, c.scan.sensor).height, 1u);
}

TEST(ProjectorShadow, AnUprightCupsBodyHidesPartOfItsInside) {
  // The cup taught upright (its top view: rim, inside, the inside's bottom) and a scan of it
  // placed again: its wall keeps the projector's light, and the camera's view, off part of the
  // inside, also where the scan did not measure that wall.
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::VerifyCase c = test::verifyCase("cup", params, 5, 9, 0);
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps;
  const auto prep = detail::prepareModel(preps, c.taught.model, params);
  ASSERT_TRUE(prep->near_axis) << "the top view has an axis through its rim";
  ASSERT_TRUE(prep->verify->body);
  const ProjectorShadow shadow(c.scan.render.cloud, c.scan.sensor);
  const VerifyScene scene{c.index.get(), &c.scan.render.cloud, &c.scan.sensor, std::nullopt,
                          &shadow};
  VerifyModel bodiless = *prep->verify;
  bodiless.body.reset();
  const double tolerance = params.matching.verify_tolerance_mm;
  const PointTally without = tallyPoints(bodiless, scene, c.T_true, tolerance);
  const PointTally with = tallyPoints(*prep->verify, scene, c.T_true, tolerance);
  const double q_without = verifyPose(bodiless, scene, c.T_true, tolerance, {});
  const double q_with = verifyPose(*prep->verify, scene, c.T_true, tolerance, {});
  std::printf("true pose, %zu points: hidden %zu -> %zu, shadowed %zu -> %zu, unexplained %zu -> "
              "%zu; coverage %.3f -> %.3f\n",
              with.points, without.hidden, with.hidden, without.shadowed, with.shadowed,
              without.points - without.confirmed - without.violations - without.hidden -
                  without.shadowed,
              with.points - with.confirmed - with.violations - with.hidden - with.shadowed,
              q_without, q_with);
  // The body takes only unmeasured points.
  EXPECT_EQ(with.confirmed, without.confirmed);
  EXPECT_EQ(with.violations, without.violations);
  EXPECT_GT(with.hidden + with.shadowed, without.hidden + without.shadowed);
  EXPECT_GT(q_with, q_without);
  // Turned a quarter about the axis, the handle stands where the scan has none: the body must
  // not excuse that.
  const Eigen::Isometry3d turned = c.T_true * prep->near_axis->turn(M_PI / 2);
  EXPECT_LT(verifyPose(*prep->verify, scene, turned, tolerance, {}) + 0.05, q_with);
}
