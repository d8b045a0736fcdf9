#include "core/pipeline/Recognizer.h"

#include "core/cloud/Sensor.h"
#include "core/common/Error.h"
#include "core/eval/ResultsFile.h"
#include "core/output/OverlayPicture.h"
#include "core/output/ResultsJson.h"
#include "tests/support/TempDir.h"
#include "tests/unit/pipeline/IdealScene.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;

namespace {
std::shared_ptr<const TaughtModel> idealModel() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 700);
  TeachOptions o;
  o.crop_box_mm = Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  o.grips_scan.push_back({"centre", Eigen::Vector3d(0, 0, 700)});
  return std::make_shared<TaughtModel>(
      teach(test::idealScene(test::idealPartPoints(), {T}, 0.0, 1), o, test::idealParams(0.001)));
}
PointCloud threeCopies(double noise) {
  auto poses = test::idealCopyPoses();
  poses.resize(3);
  return test::idealScene(test::idealPartPoints(), poses, noise, 5);
}
} // namespace

TEST(Recognizer, SameInputSameDetectionsBitwise) {
  const auto model = idealModel();
  const PointCloud scene = threeCopies(0.3);
  const auto params = test::idealParams(0.5);
  const auto a = Recognizer(model).recognize(scene, sensorPreset("phoxi-m-1032"), params);
  const auto b = Recognizer(model).recognize(scene, sensorPreset("phoxi-m-1032"), params);
  ASSERT_EQ(a.detections.size(), 3u);
  ASSERT_EQ(a.detections.size(), b.detections.size());
  for (std::size_t i = 0; i < a.detections.size(); ++i) {
    EXPECT_EQ(a.detections[i].T_scene_model.matrix(), b.detections[i].T_scene_model.matrix());
    EXPECT_EQ(a.detections[i].matched_features, b.detections[i].matched_features);
    EXPECT_EQ(a.detections[i].score, b.detections[i].score);
  }
}

TEST(Recognizer, ChangingAMatchingToleranceReusesTheKeypoints) {
  Recognizer recognizer(idealModel());
  const PointCloud scene = threeCopies(0.0);
  auto params = test::idealParams(0.001);
  const auto first = recognizer.recognize(scene, sensorPreset("phoxi-m-1032"), params);
  params.matching.position_tolerance_mm = 3.0;
  const auto second = recognizer.recognize(scene, sensorPreset("phoxi-m-1032"), params);
  EXPECT_EQ(first.scene->keypoints, second.scene->keypoints); // same cached object
  EXPECT_EQ(first.scene->features, second.scene->features);
  EXPECT_EQ(second.timings.keypoints_ms, 0.0);
  EXPECT_EQ(second.detections.size(), 3u);
  params.keypoints.neighbourhood_radius_mm = 4.0; // invalidates keypoints and later
  const auto third = recognizer.recognize(scene, sensorPreset("phoxi-m-1032"), params);
  EXPECT_NE(third.scene->keypoints, second.scene->keypoints);
  EXPECT_EQ(third.scene->preprocessed, second.scene->preprocessed);
}

TEST(Recognizer, CancellingWhileTheSceneIsIndexedKeepsTheRecognizerUsable) {
  // With verification the scene's index is built in a task beside the clustering; a cancel
  // there must wait for that task, and the next recognition must not see half a cache.
  Recognizer recognizer(idealModel());
  const PointCloud scene = threeCopies(0.3);
  auto params = test::idealParams(0.5);
  params.matching.verify_tolerance_mm = 1.0;
  params.matching.min_coverage = 0.3;
  const auto fresh =
      Recognizer(idealModel()).recognize(scene, sensorPreset("phoxi-m-1032"), params);
  ASSERT_EQ(fresh.detections.size(), 3u);
  double cancelled_at = 0.0; // the first report past the preprocessing, in the clustering
  EXPECT_THROW(recognizer.recognize(scene, sensorPreset("phoxi-m-1032"), params,
                                    [&](double fraction) {
                                      if (fraction <= 0.1)
                                        return true;
                                      cancelled_at = fraction;
                                      return false;
                                    }),
               Cancelled);
  EXPECT_GT(cancelled_at, 0.1);
  EXPECT_LT(cancelled_at, 0.3);
  const auto again = recognizer.recognize(scene, sensorPreset("phoxi-m-1032"), params);
  ASSERT_EQ(again.detections.size(), fresh.detections.size());
  for (std::size_t i = 0; i < again.detections.size(); ++i) {
    EXPECT_EQ(again.detections[i].T_scene_model.matrix(),
              fresh.detections[i].T_scene_model.matrix());
    EXPECT_EQ(again.detections[i].coverage, fresh.detections[i].coverage);
  }
}

TEST(Recognizer, GripPointsFollowThePose) {
  const auto model = idealModel();
  const auto r = Recognizer(model).recognize(threeCopies(0.0), sensorPreset("phoxi-m-1032"),
                                             test::idealParams(0.001));
  ASSERT_FALSE(r.detections.empty());
  for (const auto& d : r.detections) {
    ASSERT_EQ(d.grip_points_scene.size(), 1u);
    EXPECT_LT(
        (d.grip_points_scene[0].position_mm - d.T_scene_model * model->grip_points[0].position_mm)
            .norm(),
        1e-9);
  }
}

TEST(Recognizer, BadScenesAreErrors) {
  Recognizer recognizer(idealModel());
  EXPECT_THROW(recognizer.recognize(PointCloud{}, sensorPreset("phoxi-m-1032"), {}), Error);
  const PointCloud nan = PointCloud::fromPoints({invalidPoint(), invalidPoint()});
  EXPECT_THROW(recognizer.recognize(nan, sensorPreset("phoxi-m-1032"), {}), Error);
  EXPECT_THROW(Recognizer().recognize(threeCopies(0.0), sensorPreset("phoxi-m-1032"), {}), Error);
}

TEST(Recognizer, ResultsFileAndPictureAreWritten) {
  const auto model = idealModel();
  const PointCloud scene = threeCopies(0.0);
  const auto r =
      Recognizer(model).recognize(scene, sensorPreset("phoxi-m-1032"), test::idealParams(0.001));
  test::TempDir dir;
  saveResults(dir / "result.json", r, {{model.get(), "part.spmodel"}}, "scene.pcd");
  const auto back = eval::loadResults(dir / "result.json");
  ASSERT_EQ(back.detections.size(), r.detections.size());
  EXPECT_TRUE(back.detections[0].T_scene_model.isApprox(r.detections[0].T_scene_model, 1e-9));
  EXPECT_TRUE(back.T_teach_model.isApprox(model->T_teach_model, 1e-12));
  // The picture of an unorganized scene (tested in OverlayPictureTest) from a real recognition.
  writeOverlayPng(dir / "overlay.png", scene, {&model->cloud_mm}, r.detections,
                  sensorPreset("phoxi-m-1032"), depthOverlayTolerance_mm(test::idealParams(0.001)));
  EXPECT_GT(std::filesystem::file_size(dir / "overlay.png"), 1000u);
}

TEST(Recognizer, SuppressesDuplicatesCloserThanTheDistance) {
  Detection a, b, c;
  a.score = 0.9;
  b.score = 0.8;
  b.T_scene_model.translation() = Eigen::Vector3d(3, 0, 0);
  c.score = 0.7;
  c.T_scene_model.translation() = Eigen::Vector3d(50, 0, 0);
  const auto kept = suppressDuplicates({a, b, c}, 10.0);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[1].score, 0.7);
}

TEST(Recognizer, ADuplicateTheArbiterPrefersTakesThePlaceOfTheBetterScoredOne) {
  Detection a, b, c, same_pose;
  a.score = 0.9;
  b.score = 0.8; // one instance, turned half about z
  b.T_scene_model =
      Eigen::Translation3d(3, 0, 0) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ());
  same_pose.score = 0.85; // a, a millimetre off: the same pose
  same_pose.T_scene_model.translation() = Eigen::Vector3d(1, 0, 0);
  c.score = 0.7;
  c.T_scene_model.translation() = Eigen::Vector3d(50, 0, 0);
  int asked = 0;
  const SameInstanceArbiter prefer_turned = [&](const Detection& kept, const Detection& candidate) {
    ++asked;
    return kept.score == 0.9 && candidate.score == 0.8;
  };
  const auto kept = suppressDuplicates({a, same_pose, b, c}, 10.0, prefer_turned);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].score, 0.8) << "the turned pose in the first one's place";
  EXPECT_EQ(kept[1].score, 0.7);
  EXPECT_EQ(asked, 1) << "poses that do not differ are not asked about";
  // Without an arbiter the better-scored one stays.
  EXPECT_EQ(suppressDuplicates({a, same_pose, b, c}, 10.0)[0].score, 0.9);
}

namespace {
/// A 60 x 40 x 10 mm block's face at z = 10 (x, y in [0, 60] x [0, 40]) or at x = 0, as a view
/// would scan it, 1 mm apart.
PointCloud blockFace(bool top) {
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i <= (top ? 60 : 10); ++i)
    for (int j = 0; j <= 40; ++j)
      points.emplace_back(top ? float(i) : 0.0f, float(j), top ? 10.0f : float(i));
  return PointCloud::fromPoints(std::move(points));
}

Detection detectionAt(int view, double score, const Eigen::Isometry3d& T_scene_model) {
  Detection d;
  d.model_index = view;
  d.score = score;
  d.T_scene_model = T_scene_model;
  d.centre_mm = T_scene_model * Eigen::Vector3d(30, 20, 5);
  return d;
}

/// Two views of one block, its top and a side, each knowing the other's points and its place in
/// the block (both frames the block's); unjoined: knowing neither.
std::vector<std::shared_ptr<const TaughtModel>> blockViews(bool joined) {
  auto top = std::make_shared<TaughtModel>(), side = std::make_shared<TaughtModel>();
  top->cloud_mm = blockFace(true);
  side->cloud_mm = blockFace(false);
  top->diameter_mm = side->diameter_mm = std::sqrt(60.0 * 60.0 + 40.0 * 40.0 + 10.0 * 10.0);
  if (joined) {
    top->joined_views = {{"side.pcd", side->cloud_mm, Eigen::Vector3d(-500, 20, 5)}};
    side->joined_views = {{"top.pcd", top->cloud_mm, Eigen::Vector3d(30, 20, 500)}};
    top->T_part_model = side->T_part_model = Eigen::Isometry3d::Identity();
  }
  return {top, side};
}
} // namespace

TEST(Recognizer, JoinedViewsKeepTwoPartsLyingCloseButDropOneInstanceFoundTwice) {
  const std::vector<std::shared_ptr<const TaughtModel>> views = blockViews(true);
  Eigen::Isometry3d beside = Eigen::Isometry3d::Identity();
  beside.translation() = Eigen::Vector3d(0, 45, 0);         // 5 mm between the blocks
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity(); // half a turn about its own centre
  turned.linear() = Eigen::AngleAxisd(EIGEN_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  turned.translation() = Eigen::Vector3d(60, 40, 0);
  const std::vector<Detection> found{
      detectionAt(0, 0.9, Eigen::Isometry3d::Identity()),
      detectionAt(1, 0.8, Eigen::Isometry3d::Identity()), // the same block through the side view
      detectionAt(0, 0.7, beside),                        // its neighbour, 45 mm away
      detectionAt(1, 0.6, turned)};                       // the first block turned: same surface
  const auto kept = mergeViewDetections(found, views, 50.0);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].score, 0.9);
  EXPECT_EQ(kept[1].score, 0.7);

  // Without the joined views nothing tells the neighbour from the block: near is the same.
  const auto alone = mergeViewDetections(found, blockViews(false), 50.0);
  ASSERT_EQ(alone.size(), 1u);
  EXPECT_EQ(alone[0].score, 0.9);
  EXPECT_THROW(mergeViewDetections({detectionAt(2, 0.5, beside)}, views, 50.0), Error);
}

TEST(Recognizer, JoinedViewsOfOneInstanceAreMergedWhereverTheirCentresLieOnIt) {
  // The side view's centre is its face's, 30 mm from the top view's: beyond a merge distance of
  // 20 mm, within the block's diameter. The whole block at one pose is one instance.
  const std::vector<std::shared_ptr<const TaughtModel>> views = blockViews(true);
  Detection side = detectionAt(1, 0.8, Eigen::Isometry3d::Identity());
  side.centre_mm = Eigen::Vector3d(0, 20, 5);
  Eigen::Isometry3d beside = Eigen::Isometry3d::Identity();
  beside.translation() = Eigen::Vector3d(0, 45, 0);
  Detection neighbour = detectionAt(1, 0.7, beside);
  neighbour.centre_mm = beside * Eigen::Vector3d(0, 20, 5); // 45 mm away, sharing no surface
  const auto kept = mergeViewDetections(
      {detectionAt(0, 0.9, Eigen::Isometry3d::Identity()), side, neighbour}, views, 20.0);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].score, 0.9);
  EXPECT_EQ(kept[1].score, 0.7);
  // Unjoined views know nothing beyond the merge distance.
  EXPECT_EQ(mergeViewDetections({detectionAt(0, 0.9, Eigen::Isometry3d::Identity()), side},
                                blockViews(false), 20.0)
                .size(),
            2u);
}

TEST(Recognizer, JoinedViewsSmallerThanThePartAreMergedAcrossItsWholeSize) {
  // Each view sees a small face of the 73 mm block (say, the end faces of a bar): their own
  // diameters, 10 mm, are less than the 30 mm between their centres. The whole part's size says
  // how far apart one instance's views may lie.
  std::vector<std::shared_ptr<const TaughtModel>> views;
  for (const auto& view : blockViews(true)) {
    auto small = std::make_shared<TaughtModel>(*view);
    small->diameter_mm = 10.0;
    views.push_back(small);
  }
  Detection side = detectionAt(1, 0.8, Eigen::Isometry3d::Identity());
  side.centre_mm = Eigen::Vector3d(0, 20, 5);
  const auto kept =
      mergeViewDetections({detectionAt(0, 0.9, Eigen::Isometry3d::Identity()), side}, views, 5.0);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].score, 0.9);
}

TEST(Recognizer, ATieBetweenTwoViewsDifferingPosesOfOneInstanceIsLeftToPrefer) {
  const std::vector<std::shared_ptr<const TaughtModel>> views = blockViews(true);
  // The block turned 5° about its own centre: the same instance at another pose.
  const Eigen::Isometry3d turned =
      Eigen::Translation3d(30, 20, 5) *
      Eigen::AngleAxisd(5.0 * EIGEN_PI / 180.0, Eigen::Vector3d::UnitZ()) *
      Eigen::Translation3d(-30, -20, -5);
  int asked = 0;
  const SameInstanceArbiter later_wins = [&](const Detection& kept, const Detection& candidate) {
    ++asked;
    EXPECT_GT(kept.score, candidate.score);
    return true;
  };
  const Detection first = detectionAt(0, 0.900, Eigen::Isometry3d::Identity());
  // A tie at another pose: `prefer` decides, and the later one takes the place.
  auto kept = mergeViewDetections({first, detectionAt(1, 0.895, turned)}, views, 50.0, later_wins);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].model_index, 1);
  EXPECT_EQ(asked, 1);
  // Not a tie: the better one stays without asking.
  kept = mergeViewDetections({first, detectionAt(1, 0.880, turned)}, views, 50.0, later_wins);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].model_index, 0);
  // A tie at the same pose: either will do, nothing to ask.
  kept = mergeViewDetections({first, detectionAt(1, 0.899, Eigen::Isometry3d::Identity())}, views,
                             50.0, later_wins);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].model_index, 0);
  EXPECT_EQ(asked, 1);
}

TEST(Recognizer, PooledSearchFindsEveryCopyInOneUnsplitScene) {
  // No clustering: the three copies are one object, as touching parts in a bin are.
  RecognitionParams params = test::idealParams(0.001);
  params.clustering.enabled = false;
  params.matching.verify_tolerance_mm = 1.0;
  params.matching.min_coverage = 0.5;
  params.matching.pool_size = 200;
  const auto poses = test::idealCopyPoses();
  const auto model = idealModel();
  const auto r =
      Recognizer(model).recognize(threeCopies(0.0), sensorPreset("phoxi-m-1032"), params);
  ASSERT_EQ(r.detections.size(), 3u);
  // Each copy is found once, at its model origin (the teach scan had the part moved by 700 mm
  // along z).
  const Eigen::Vector3d origin_part =
      model->T_teach_model.translation() - Eigen::Vector3d(0, 0, 700);
  for (std::size_t i = 0; i < 3; ++i) {
    const Eigen::Vector3d where = poses[i] * origin_part;
    const auto hits =
        std::count_if(r.detections.begin(), r.detections.end(), [&](const Detection& d) {
          return (d.T_scene_model.translation() - where).norm() < 0.5;
        });
    EXPECT_EQ(hits, 1) << "copy " << i;
  }
}

TEST(Recognizer, ViewsAreMergedWithoutDuplicatesAndNamedInTheResults) {
  const auto view0 = idealModel();
  auto view1 = std::make_shared<TaughtModel>(*view0);
  view1->teach_scan = "side.pcd";
  const PointCloud scene = threeCopies(0.0);
  const auto params = test::idealParams(0.001);
  Recognizer recognizer;
  const auto single = Recognizer(view0).recognize(scene, sensorPreset("phoxi-m-1032"), params);
  const auto merged =
      recognizeViews(recognizer, {view0, view1}, scene, sensorPreset("phoxi-m-1032"), params);
  // The same instances seen through both (identical) views are reported once.
  ASSERT_EQ(merged.detections.size(), single.detections.size());
  for (std::size_t i = 0; i < merged.detections.size(); ++i)
    EXPECT_TRUE(
        merged.detections[i].T_scene_model.isApprox(single.detections[i].T_scene_model, 1e-9));
  test::TempDir dir;
  saveResults(dir / "result.json", merged, {{view0.get(), "a.spmodel"}, {view1.get(), "b.spmodel"}},
              "scene.pcd");
  const auto back = eval::loadResults(dir / "result.json");
  ASSERT_EQ(back.models.size(), 2u);
  EXPECT_EQ(back.models[1].teach_scan, "side.pcd");
  for (std::size_t i = 0; i < back.detections.size(); ++i)
    EXPECT_EQ(back.detections[i].model, static_cast<std::size_t>(merged.detections[i].model_index));
  EXPECT_THROW(recognizeViews(recognizer, {}, scene, sensorPreset("phoxi-m-1032"), params), Error);
}

TEST(Recognizer, AViewsOwnParametersReplaceTheRecognitionParameters) {
  const auto taught = idealModel();
  const PointCloud scene = threeCopies(0.3);
  auto params = test::idealParams(0.5);
  params.matching.verify_tolerance_mm = 0.5;
  params.matching.min_coverage = 0.0;
  const auto all = Recognizer(taught).recognize(scene, sensorPreset("phoxi-m-1032"), params);
  ASSERT_EQ(all.detections.size(), 3u);
  const double best = all.detections.front().score, worst = all.detections.back().score;
  ASSERT_LT(worst, best);
  // The view's own minimum coverage, between the worst and the best score, drops the worst
  // detection although the parameters would keep every one...
  auto strict = std::make_shared<TaughtModel>(*taught);
  strict->view_params["matching.min_coverage"] = 0.5 * (worst + best);
  const auto fewer = Recognizer(strict).recognize(scene, sensorPreset("phoxi-m-1032"), params);
  EXPECT_GE(fewer.detections.size(), 1u);
  EXPECT_LT(fewer.detections.size(), 3u);
  for (const auto& d : fewer.detections)
    EXPECT_GE(d.score, strict->view_params["matching.min_coverage"]);
  // ...and a lower one keeps all three where the parameters alone would not.
  params.matching.min_coverage = strict->view_params["matching.min_coverage"];
  EXPECT_EQ(
      Recognizer(taught).recognize(scene, sensorPreset("phoxi-m-1032"), params).detections.size(),
      fewer.detections.size());
  auto lenient = std::make_shared<TaughtModel>(*taught);
  lenient->view_params["matching.min_coverage"] = 0.0;
  EXPECT_EQ(
      Recognizer(lenient).recognize(scene, sensorPreset("phoxi-m-1032"), params).detections.size(),
      3u);
}

TEST(Recognizer, PreparedViewsGiveTheSameDetectionsAndAreKept) {
  const auto view0 = idealModel();
  auto view1 = std::make_shared<TaughtModel>(*view0);
  view1->teach_scan = "side.pcd";
  view1->view_params = {{"matching.min_coverage", 0.2}};
  const PointCloud scene = threeCopies(0.3);
  auto params = test::idealParams(0.5);
  params.matching.verify_tolerance_mm = 0.5;
  params.matching.min_coverage = 0.5;
  Recognizer fresh;
  const auto expected =
      recognizeViews(fresh, {view0, view1}, scene, sensorPreset("phoxi-m-1032"), params);
  Recognizer prepared;
  EXPECT_THROW(prepared.prepare(params), Error); // no model yet
  EXPECT_GE(prepareViews(prepared, {view0, view1}, params), 0.0);
  EXPECT_EQ(prepared.preparedModels(), 2u);
  const auto got =
      recognizeViews(prepared, {view0, view1}, scene, sensorPreset("phoxi-m-1032"), params);
  EXPECT_EQ(prepared.preparedModels(), 2u); // used, not prepared again
  ASSERT_EQ(got.detections.size(), expected.detections.size());
  ASSERT_FALSE(got.detections.empty());
  for (std::size_t i = 0; i < got.detections.size(); ++i) {
    EXPECT_EQ(got.detections[i].T_scene_model.matrix(),
              expected.detections[i].T_scene_model.matrix());
    EXPECT_EQ(got.detections[i].score, expected.detections[i].score);
  }
  // Without verification or refinement there is nothing to prepare.
  Recognizer plain(view0);
  plain.prepare(test::idealParams(0.5));
  EXPECT_EQ(plain.preparedModels(), 0u);
}
