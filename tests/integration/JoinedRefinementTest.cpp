// Views joined (beyond the thesis): refinement and the views' merge. Each view's ICP also fits the
// surfaces the other views saw, which pin down what one view leaves loose; a surface of revolution
// is then slid along its axis to where its wall ends, and a plate in its own plane to where its
// outline ends. The support's view cut from a bin shows one leg face-on: alone, ICP slides it in
// the leg's own plane, held only by its holes and its outline. The merge tells two parts lying
// close together from one part found through two views by the surface they share; a coat-rack
// seen from below reports its half turn, refined.
#include "core/ambiguity/ModelPrep.h"
#include "core/common/Error.h"
#include "core/pipeline/Recognizer.h"
#include "core/sim/Suite.h"
#include "tests/integration/SynthTeach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <map>
#include <optional>
#include <vector>

using namespace scanpick;
using namespace scanpick::core;

namespace {

/// The views of `part` as docs/accuracy.md teaches them from the suite's teach scans `views` (a
/// view cut from a bin, such as "support-bin", as synth-suite cuts it), each knowing its place in
/// the part.
std::vector<std::shared_ptr<const TaughtModel>>
suiteViews(const std::string& part, const std::vector<std::string>& views,
           const RecognitionParams& params, const std::map<std::string, ViewParams>& own = {}) {
  std::vector<std::shared_ptr<const TaughtModel>> taught;
  std::vector<Eigen::Vector3d> taught_directions;
  for (const std::string& view : views)
    for (const SuiteScene& s : suiteScenes("teach", kDefaultSuiteSeed))
      if (s.relative_prefix == "teach/phoxi-m-1032/" + view) {
        SynthScene scan = synthesize(s.request);
        if (s.novel_against.empty())
          taught_directions.push_back(
              viewDirectionInPart(scan.scene, scan.scene.instances.front()));
        else // as synth-suite cuts it
          scan = isolateNovelView(std::move(scan), taught_directions);
        const test::SynthTeach from_scan = test::teachFromScan(scan, part, params);
        from_scan.model->teach_scan = view + ".pcd";
        if (const auto it = own.find(view); it != own.end())
          from_scan.model->view_params = it->second;
        taught.push_back(from_scan.model);
      }
  return taught;
}

/// The support's five views: its four table scans, and one part cut from a bin scan (the view no
/// table scan shows).
std::vector<std::shared_ptr<const TaughtModel>> supportViews(const RecognitionParams& params) {
  return suiteViews("support",
                    {"support", "support-side1", "support-side2", "support-side3", "support-bin"},
                    params);
}

/// The coat-rack's five views, its view cut from a bin with its own minimum coverage `bin_coverage`
/// when given (as docs/accuracy.md teaches it).
std::vector<std::shared_ptr<const TaughtModel>>
coatRackViews(const RecognitionParams& params, std::optional<double> bin_coverage = {}) {
  std::map<std::string, ViewParams> own;
  if (bin_coverage)
    own["coat-rack-bin"] = {{"matching.min_coverage", *bin_coverage}};
  return suiteViews(
      "coat-rack",
      {"coat-rack", "coat-rack-side1", "coat-rack-side2", "coat-rack-side3", "coat-rack-bin"},
      params, own);
}

/// The suite's bins of `part` alone (scene-NNN, NNN in `numbers`).
std::vector<SynthScene> suiteBins(const std::string& numbers) {
  std::vector<SynthScene> bins;
  for (const SuiteScene& s : suiteScenes("phoxi-bin", kDefaultSuiteSeed)) {
    const std::string name = s.relative_prefix.string();
    if (numbers.find(name.substr(name.size() - 3)) != std::string::npos)
      bins.push_back(synthesize(s.request));
  }
  return bins;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

} // namespace

TEST(JoinedRefinement, TheOtherViewsHoldAFaceOnLegInItsPlane) {
  RecognitionParams params = test::bundledPreset("phoxi-bin");
  params.refine.enabled = true;
  const std::vector<std::shared_ptr<const TaughtModel>> views = supportViews(params);
  ASSERT_EQ(views.size(), 5u);
  const std::vector<std::shared_ptr<const TaughtModel>> joined = joinViews(views);
  // The origin error (mm) of each detection the bin view made, against the nearest support (its
  // symmetry keeps the origin), over the suite's five bins of supports.
  const std::vector<SynthScene> bins = suiteBins("000 004 008 012 016"); // supports only
  const auto binViewErrors = [&](const std::vector<std::shared_ptr<const TaughtModel>>& models) {
    std::vector<double> errors;
    for (const SynthScene& bin : bins) {
      Recognizer recognizer;
      for (const Detection& d :
           recognizeViews(recognizer, models, bin.render.cloud, bin.sensor, params).detections) {
        if (d.model_index != 4)
          continue;
        const Eigen::Vector3d origin =
            (d.T_scene_model * models[4]->T_part_model->inverse()).translation();
        double nearest_mm = 1e9;
        for (const PartInstance& instance : bin.scene.instances)
          nearest_mm = std::min(nearest_mm,
                                (bin.scene.T_scene_part(instance).translation() - origin).norm());
        errors.push_back(nearest_mm);
      }
    }
    return errors;
  };
  const std::vector<double> alone = binViewErrors(views), together = binViewErrors(joined);
  ASSERT_GE(alone.size(), 5u);
  ASSERT_GE(together.size(), 5u);
  std::printf("the bin view's detections after ICP: alone %zu at %.3f mm median, joined %zu at "
              "%.3f mm\n",
              alone.size(), median(alone), together.size(), median(together));
  // The bin view's detections that the views' merge keeps; refinement follows the merge.
  EXPECT_LT(median(together), 0.5 * median(alone));
  EXPECT_LT(median(together), 0.3);
}

// Refinement follows the views' merge: ICP polishes the detections the merge kept and cannot
// change which they are (a refined pose used to outrank, or merge away, another view's).
TEST(JoinedRefinement, RefinementKeepsTheDetectionsTheMergeKept) {
  RecognitionParams params = test::bundledPreset("phoxi-bin");
  const std::vector<std::shared_ptr<const TaughtModel>> joined = joinViews(supportViews(params));
  ASSERT_EQ(joined.size(), 5u);
  SynthScene bin;
  for (const SuiteScene& s : suiteScenes("phoxi-bin", kDefaultSuiteSeed))
    if (s.relative_prefix.string().ends_with("000"))
      bin = synthesize(s.request);
  ASSERT_FALSE(bin.scene.instances.empty());
  Recognizer recognizer;
  const RecognitionResult as_found =
      recognizeViews(recognizer, joined, bin.render.cloud, bin.sensor, params);
  params.refine.enabled = true;
  const RecognitionResult refined =
      recognizeViews(recognizer, joined, bin.render.cloud, bin.sensor, params);
  ASSERT_FALSE(as_found.detections.empty());
  ASSERT_EQ(refined.detections.size(), as_found.detections.size());
  std::size_t moved = 0;
  for (const Detection& r : refined.detections) {
    const auto same = std::find_if(
        as_found.detections.begin(), as_found.detections.end(), [&](const Detection& d) {
          return d.model_index == r.model_index &&
                 (d.T_scene_model.translation() - r.T_scene_model.translation()).norm() < 3.0;
        });
    EXPECT_NE(same, as_found.detections.end()) << "a refined detection the merge had not kept";
    if (same != as_found.detections.end() && !same->T_scene_model.isApprox(r.T_scene_model, 1e-9))
      ++moved;
    ASSERT_EQ(r.grip_points_scene.size(), joined[std::size_t(r.model_index)]->grip_points.size());
    for (std::size_t g = 0; g < r.grip_points_scene.size(); ++g)
      EXPECT_LT((r.grip_points_scene[g].position_mm -
                 r.T_scene_model * joined[std::size_t(r.model_index)]->grip_points[g].position_mm)
                    .norm(),
                1e-9)
          << "grip points follow the refined pose";
  }
  std::printf("%zu detections, %zu of them moved by refinement\n", refined.detections.size(),
              moved);
  EXPECT_GT(moved, 0u);
}

namespace {
/// The suite's bin scene whose name ends with `number`.
SynthScene binScene(const std::string& number) {
  for (const SuiteScene& s : suiteScenes("phoxi-bin", kDefaultSuiteSeed))
    if (s.relative_prefix.string().ends_with(number))
      return synthesize(s.request);
  return {};
}

/// Where a detection puts the part's origin (scene frame, mm).
Eigen::Vector3d partOrigin(const Detection& d,
                           const std::vector<std::shared_ptr<const TaughtModel>>& views) {
  return (d.T_scene_model * views[std::size_t(d.model_index)]->T_part_model->inverse())
      .translation();
}
} // namespace

TEST(JoinedMerge, TwoSupportsLyingCloseAreBothFoundAndNoneTwice) {
  // In this bin two supports lie so close that their views' detections are nearer than the merge
  // radius (kViewMergeShare × the diameter): the merge by distance alone took them for one.
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const std::vector<std::shared_ptr<const TaughtModel>> joined = joinViews(supportViews(params));
  ASSERT_EQ(joined.size(), 5u);
  const SynthScene bin = binScene("000");
  ASSERT_FALSE(bin.scene.instances.empty());
  Recognizer recognizer;
  const RecognitionResult result =
      recognizeViews(recognizer, joined, bin.render.cloud, bin.sensor, params);
  double diameter_mm = 0.0;
  for (const auto& view : joined)
    diameter_mm = std::max(diameter_mm, view->diameter_mm);
  // Each detection's nearest instance, and how close two of the instances found lie.
  std::vector<std::size_t> found(bin.scene.instances.size(), 0);
  std::vector<Eigen::Vector3d> centres; // of the detections whose instance was found
  for (const Detection& d : result.detections) {
    const Eigen::Vector3d origin = partOrigin(d, joined);
    std::size_t nearest = 0;
    double nearest_mm = 1e9;
    for (std::size_t i = 0; i < bin.scene.instances.size(); ++i) {
      const double mm =
          (bin.scene.T_scene_part(bin.scene.instances[i]).translation() - origin).norm();
      if (mm < nearest_mm) {
        nearest_mm = mm;
        nearest = i;
      }
    }
    EXPECT_LT(nearest_mm, 0.1 * diameter_mm) << "a detection far from every support";
    ++found[nearest];
    centres.push_back(d.centre_mm);
  }
  for (std::size_t i = 0; i < found.size(); ++i)
    EXPECT_LE(found[i], 1u) << "support " << i << " reported twice";
  double closest_mm = 1e9;
  for (std::size_t a = 0; a < centres.size(); ++a)
    for (std::size_t b = a + 1; b < centres.size(); ++b)
      closest_mm = std::min(closest_mm, (centres[a] - centres[b]).norm());
  std::printf("%zu detections; the closest two centres %.1f mm apart (merge radius %.1f mm)\n",
              result.detections.size(), closest_mm, kViewMergeShare * diameter_mm);
  EXPECT_LT(closest_mm, kViewMergeShare * diameter_mm) << "no two supports lie close in this bin";
}

TEST(JoinedMerge, TheWholePartScoresTheTruePoseAboveATurnedOne) {
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const std::vector<std::shared_ptr<const TaughtModel>> views = supportViews(params);
  const std::vector<std::shared_ptr<const TaughtModel>> joined = joinViews(views);
  const SynthScene bin = binScene("004");
  ASSERT_FALSE(bin.scene.instances.empty());
  Recognizer recognizer;
  const RecognitionResult result =
      recognizeViews(recognizer, joined, bin.render.cloud, bin.sensor, params);
  ASSERT_FALSE(result.detections.empty());
  const PartScorer on_part = recognizer.partScorer(joined, result.scene, params);
  std::size_t compared = 0;
  for (const Detection& d : result.detections) {
    // The true pose of the detection's instance, and that pose turned 11° about the camera's
    // axis through the part's origin (a view's wrong pose that verified as well as the right one).
    const Eigen::Vector3d origin = partOrigin(d, joined);
    for (const PartInstance& instance : bin.scene.instances) {
      const Eigen::Isometry3d T_scene_part = bin.scene.T_scene_part(instance);
      if ((T_scene_part.translation() - origin).norm() > 5.0)
        continue;
      Detection truth = d, turned = d;
      truth.T_scene_model = T_scene_part * *joined[std::size_t(d.model_index)]->T_part_model;
      turned.T_scene_model = Eigen::Translation3d(T_scene_part.translation()) *
                             Eigen::AngleAxisd(11.0 * EIGEN_PI / 180.0, Eigen::Vector3d::UnitZ()) *
                             Eigen::Translation3d(-T_scene_part.translation()) *
                             truth.T_scene_model;
      const double true_score = on_part(truth), turned_score = on_part(turned);
      EXPECT_GT(true_score, turned_score + detail::kPartScoreMargin)
          << "view " << d.model_index << " at (" << origin.transpose() << ") mm";
      ++compared;
    }
  }
  EXPECT_GT(compared, 3u);
  // Views without joined views have no whole part to score on; a view index must be one of them.
  const PartScorer alone = recognizer.partScorer(views, result.scene, params);
  EXPECT_TRUE(std::isnan(alone(result.detections.front())));
  Detection stray = result.detections.front();
  stray.model_index = 5;
  EXPECT_THROW((void)on_part(stray), Error);
}

// A pump-connector lying on its side shows ICP its pipe and the rims of its flanges, which let it
// slide along its axis; refine.axial_ends slides it to where the scan shows the flanges' rims end
// (core/refine/SurfaceEnds.h).
TEST(JoinedRefinement, APipeOnItsSideIsSlidToWhereItsWallEnds) {
  RecognitionParams params = test::bundledPreset("phoxi-bin");
  params.refine.enabled = true;
  const std::vector<std::shared_ptr<const TaughtModel>> views = joinViews(suiteViews(
      "pump-connector",
      {"pump-connector", "pump-connector-side1", "pump-connector-side2", "pump-connector-side3"},
      params));
  ASSERT_EQ(views.size(), 4u);
  const std::vector<SynthScene> bins = suiteBins("002 010");
  ASSERT_EQ(bins.size(), 2u);
  // How far each detection whose turn about its axis is not seen (the part lying on its side)
  // puts the middle of the pipe from the nearest part's: the middle stays under every symmetry.
  const Eigen::Vector3d middle_part(0, 0, 50);
  const auto lyingErrors = [&](bool axial_ends) {
    RecognitionParams p = params;
    p.refine.axial_ends = axial_ends;
    std::vector<double> errors;
    for (const SynthScene& bin : bins) {
      Recognizer recognizer;
      for (const Detection& d :
           recognizeViews(recognizer, views, bin.render.cloud, bin.sensor, p).detections) {
        if (!d.free_turn_axis)
          continue;
        const Eigen::Vector3d middle =
            d.T_scene_model *
            (views[std::size_t(d.model_index)]->T_part_model->inverse() * middle_part);
        double nearest_mm = 1e9;
        for (const PartInstance& instance : bin.scene.instances)
          nearest_mm = std::min(nearest_mm,
                                (bin.scene.T_scene_part(instance) * middle_part - middle).norm());
        errors.push_back(nearest_mm);
      }
    }
    return errors;
  };
  const std::vector<double> icp_alone = lyingErrors(false), slid = lyingErrors(true);
  ASSERT_GE(slid.size(), 5u);
  ASSERT_EQ(slid.size(), icp_alone.size());
  std::printf("pump-connectors lying on their side: %zu, the pipe's middle %.3f mm off after ICP "
              "alone, %.3f mm slid to its ends (medians)\n",
              slid.size(), median(icp_alone), median(slid));
  EXPECT_LT(median(slid), 0.1);
  EXPECT_LT(median(slid), 0.5 * median(icp_alone));
}

TEST(JoinedRefinement, TheOtherViewsPlaceTheHalfTurnOfACoatRackSeenFromBelow) {
  // Seen from below, the coat-rack repeats itself under a half turn about its plate's normal (z
  // through the part's origin). Fitted onto itself, the view leaves that turn a degree or two
  // off about the normal and its axis a millimetre or two off: the plate's faces pin neither.
  // With the other views joined, the turn is made an exact half turn and its axis placed where
  // the part's whole outline maps onto itself.
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const std::vector<std::shared_ptr<const TaughtModel>> views = coatRackViews(params);
  ASSERT_EQ(views.size(), 5u);
  // The half turn about the plate's normal that the view from below (side 3) finds: how far it
  // turns from the part's own half turn (°) and how far it moves the part's origin (mm).
  const auto halfTurnError = [&](const TaughtModel& below) -> std::pair<double, double> {
    const Eigen::Isometry3d T_part_model = *below.T_part_model;
    for (const NearSymmetry& s : test::symmetriesOf(below, params).found) {
      const Eigen::Isometry3d S_part = T_part_model * s.S_model * T_part_model.inverse();
      const Eigen::AngleAxisd turn(S_part.linear());
      if (std::abs(turn.angle() - M_PI) < 5.0 * M_PI / 180 && std::abs(turn.axis().z()) > 0.99) {
        const Eigen::Matrix3d half_turn = Eigen::Vector3d(-1, -1, 1).asDiagonal();
        return {Eigen::AngleAxisd(half_turn.transpose() * S_part.linear()).angle() * 180 / M_PI,
                S_part.translation().norm()};
      }
    }
    return {-1.0, -1.0};
  };
  const auto [alone_deg, alone_mm] = halfTurnError(*views[3]);
  const auto [joined_deg, joined_mm] = halfTurnError(*joinViews(views)[3]);
  std::printf("the half turn from below: alone %.2f° and %.2f mm off, joined %.2f° and %.2f mm\n",
              alone_deg, alone_mm, joined_deg, joined_mm);
  ASSERT_GE(alone_deg, 0.0) << "the view alone finds the half turn";
  ASSERT_GE(joined_deg, 0.0) << "the joined view finds the half turn";
  EXPECT_LT(joined_deg, 0.5);
  EXPECT_LT(joined_mm, 0.5);
  EXPECT_LT(joined_mm, 0.5 * alone_mm);
}

TEST(JoinedRefinement, ACoatRackSeenFromBelowReportsARefinedHalfTurn) {
  // The coat-rack's five views as docs/accuracy.md teaches them, in two of the suite's bins of
  // coat-racks: plates lying flat, on their side, and on their lip (seen from below, where the
  // scan cannot tell the half turn about the plate's normal and reports it as an alternative
  // pose, which ICP then refines from the view's near symmetry, placed by the other views).
  RecognitionParams params = test::bundledPreset("phoxi-bin");
  params.refine.enabled = true;
  params.refine.outline_ends = true;  // each plate also moved in its plane to where its points end
  params.matching.surface_poses = 60; // every plate's alternative among the voted poses
  const std::vector<std::shared_ptr<const TaughtModel>> views =
      joinViews(coatRackViews(params, 0.5));
  ASSERT_EQ(views.size(), 5u);
  const std::vector<SynthScene> bins = suiteBins("003 019");
  ASSERT_EQ(bins.size(), 2u);
  // Per detection, the origin error of the nearest of its poses (its own and its alternatives)
  // that is turned less than 5° from an instance.
  std::vector<double> errors;
  std::size_t with_alternatives = 0;
  for (const SynthScene& bin : bins) {
    Recognizer recognizer;
    for (const Detection& d :
         recognizeViews(recognizer, views, bin.render.cloud, bin.sensor, params).detections) {
      std::vector<Eigen::Isometry3d> poses = d.alternative_poses;
      poses.push_back(d.T_scene_model);
      with_alternatives += d.alternative_poses.empty() ? 0 : 1;
      const Eigen::Isometry3d T_model_part =
          views[std::size_t(d.model_index)]->T_part_model->inverse();
      double nearest_mm = 1e9;
      for (const Eigen::Isometry3d& T_scene_model : poses)
        for (const PartInstance& instance : bin.scene.instances) {
          const Eigen::Isometry3d T_true = bin.scene.T_scene_part(instance);
          const Eigen::Isometry3d T = T_scene_model * T_model_part;
          if (Eigen::AngleAxisd(T_true.linear().transpose() * T.linear()).angle() <
              5.0 * M_PI / 180)
            nearest_mm = std::min(nearest_mm, (T.translation() - T_true.translation()).norm());
        }
      errors.push_back(nearest_mm);
    }
  }
  ASSERT_GE(errors.size(), 15u);
  ASSERT_GE(with_alternatives, 4u);
  std::printf("coat-racks: %zu detections (%zu with an alternative pose), origin error %.3f mm "
              "median, %.3f mm the largest\n",
              errors.size(), with_alternatives, median(errors),
              *std::max_element(errors.begin(), errors.end()));
  EXPECT_LT(median(errors), 0.11);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 0.8);
}

TEST(JoinedMerge, AViewOfOneFaceTakesThePoseTheWholePartBearsOut) {
  // A 22 mm L bracket of the random-parts suite (seed 8730, part 25), taught on its four sides with
  // the parameters teach derives. One side shows little but the flat underside of its base, which
  // a half turn about the base's normal puts back on itself: that view verifies the bracket turned
  // so, its upright pointing into the bin's floor or away from the camera, as well as the right
  // pose. The views joined and the floor the parts rest on tell them apart.
  std::map<std::string, SynthScene> teach_scans; // by name: teach, teach-side1 .. 3, in order
  std::optional<SynthScene> bin;
  for (const SuiteScene& s : suiteScenes("random-parts", 8730, 26)) {
    const std::string prefix = s.relative_prefix.generic_string(), part = "random-parts/part-025/";
    if (prefix.rfind(part + "teach", 0) == 0)
      teach_scans.emplace(prefix.substr(part.size()), synthesize(s.request));
    else if (prefix == part + "scene-000")
      bin = synthesize(s.request);
  }
  ASSERT_EQ(teach_scans.size(), 4u);
  ASSERT_TRUE(bin);
  std::vector<std::shared_ptr<const TaughtModel>> views;
  for (const auto& [name, scan] : teach_scans) {
    const RecognitionParams derived =
        autoTeachParams(scan.render.cloud, test::teachOptionsFor(scan, "bracket")).params;
    views.push_back(test::teachFromScan(scan, "bracket", derived).model);
  }
  views = joinViews(views);
  Recognizer recognizer;
  const RecognitionResult r =
      recognizeViews(recognizer, views, bin->render.cloud, bin->sensor, views.front()->params);
  const double diameter_mm = bin->parts.front().diameter_mm();
  std::vector<bool> found(bin->scene.instances.size(), false);
  for (const Detection& d : r.detections) {
    const Eigen::Isometry3d T_scene_part =
        d.T_scene_model * views[std::size_t(d.model_index)]->T_part_model->inverse();
    const auto off_mm = [&](std::size_t i) {
      return (bin->scene.T_scene_part(bin->scene.instances[i]).translation() -
              T_scene_part.translation())
          .norm();
    };
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < found.size(); ++i)
      if (off_mm(i) < off_mm(nearest))
        nearest = i;
    if (off_mm(nearest) > diameter_mm)
      continue; // not on any instance (a bin wall's rim): not what this test is about
    const Eigen::Isometry3d T_true = bin->scene.T_scene_part(bin->scene.instances[nearest]);
    const double off_deg =
        Eigen::AngleAxisd(T_true.linear().transpose() * T_scene_part.linear()).angle() * 180.0 /
        M_PI;
    const bool right = off_mm(nearest) < 0.1 * diameter_mm && off_deg < 10.0;
    EXPECT_TRUE(right) << "instance " << nearest << ": found " << off_mm(nearest) << " mm and "
                       << off_deg << " deg off";
    found[nearest] = found[nearest] || right;
  }
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (bin->render.visible_fraction[i] >= 0.5) {
      EXPECT_TRUE(found[i]) << "instance " << i << " not found";
    }
  }
}
