// Views that are a surface of revolution but for an asymmetric feature (beyond the thesis): a cup
// lying on its side is a rotationally symmetric surface and a handle. Where a scan confirms the
// handle, recognition reports the cup's rotation about its axis; where it does not, the detection
// says that rotation is not seen (Detection::free_turn_axis) instead of passing one rotation off
// as found.
#include "core/ambiguity/AmbiguityResolution.h"
#include "core/common/Error.h"
#include "core/pipeline/Recognizer.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/refine/PoseRefinement.h"
#include "core/sim/Suite.h"
#include "tests/integration/SynthTeach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

using namespace scanpick;
using namespace scanpick::core;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The PhoXi preset set up for a surface of revolution whose rim splits into arcs: the cup is
/// searched by its surface alone (sampled at 6 mm, no lines or circles, the scene not split into
/// objects) with a 0.75 minimum coverage.
RecognitionParams cupParams() {
  RecognitionParams params = test::bundledPreset("phoxi-bin");
  params.matching.surface_sampling_mm = 6.0;
  params.matching.min_coverage = 0.75;
  params.features.lines = false;
  params.features.circles = false;
  params.clustering.enabled = false;
  return params;
}

/// The detection's part pose against the truth: rotation (degrees) and origin distance (mm).
struct PoseOff {
  double rotation_deg = 0.0, translation_mm = 0.0;
};

PoseOff offBy(const Eigen::Isometry3d& T_true, const Eigen::Isometry3d& T_found) {
  return {Eigen::AngleAxisd(T_true.linear().transpose() * T_found.linear()).angle() * 180.0 / kPi,
          (T_true.translation() - T_found.translation()).norm()};
}

/// The cup's four table views as docs/accuracy.md teaches them, each knowing its place in the
/// part (joinViews joins them).
std::vector<std::shared_ptr<const TaughtModel>> cupTableViews(const RecognitionParams& params) {
  std::vector<std::shared_ptr<const TaughtModel>> views;
  for (const std::string view : {"cup", "cup-side1", "cup-side2", "cup-side3"})
    for (const SuiteScene& s : suiteScenes("teach", kDefaultSuiteSeed))
      if (s.relative_prefix == "teach/phoxi-m-1032/" + view) {
        const test::SynthTeach taught = test::teachFromScan(synthesize(s.request), "cup", params);
        taught.model->teach_scan = view + ".pcd";
        if (view == "cup-side1") // the cup upside down votes with denser reference points
          taught.model->view_params["matching.surface_reference_stride"] = 2;
        views.push_back(taught.model);
      }
  return views;
}

/// The cup taught lying on its side (a view that sees its handle), and a scan of another cup
/// lying so, with the pose the view should be found at.
struct CupOnItsSide {
  test::SynthTeach side = test::teachFromSynth("cup", 5, cupParams(), 2);
  SynthScene scan = test::teachScan("cup", 21, 2);
  Eigen::Isometry3d T_true =
      scan.scene.T_scene_part(scan.scene.instances.at(0)) * side.T_part_model();
};

/// A scene of the phoxi-bin suite as synth-suite writes it.
SynthScene phoxiBin(const std::string& name) {
  for (const SuiteScene& s : suiteScenes("phoxi-bin", kDefaultSuiteSeed))
    if (s.relative_prefix == "phoxi-bin/" + name)
      return synthesize(s.request);
  throw Error("no suite scene " + name);
}

} // namespace

TEST(NearRevolution, ACupWhoseHandleShowsIsFoundAtItsRotation) {
  const RecognitionParams params = cupParams();
  const CupOnItsSide cup;
  const auto& [side, scan, T_true] = cup;
  Recognizer recognizer;
  recognizer.setModel(side.model);
  const RecognitionResult result = recognizer.recognize(scan.render.cloud, scan.sensor, params);
  ASSERT_EQ(result.detections.size(), 1u);
  const Detection& d = result.detections.front();
  const PoseOff off = offBy(T_true, d.T_scene_model);
  std::printf("found %.2f° and %.2f mm off, free turn %s\n", off.rotation_deg, off.translation_mm,
              d.free_turn_axis ? "reported" : "not reported");
  EXPECT_LT(off.rotation_deg, 3.0);
  EXPECT_LT(off.translation_mm, 2.0);
  EXPECT_FALSE(d.free_turn_axis) << "the handle is in sight: the rotation is seen";
}

TEST(NearRevolution, ACupWhoseHandleIsNotConfirmedReportsItsRotationAsFree) {
  const RecognitionParams params = cupParams();
  const test::SynthTeach side = test::teachFromSynth("cup", 5, params, 2);
  int seen = 0, free = 0, free_right = 0;
  for (const int scan_side : {2, 3})
    for (std::uint64_t seed = 31; seed < 35; ++seed) {
      const SynthScene scan = test::teachScan("cup", seed, scan_side);
      const Eigen::Isometry3d T_scene_part = scan.scene.T_scene_part(scan.scene.instances.at(0));
      const Eigen::Isometry3d T_true = T_scene_part * side.T_part_model();
      // The cup's axis: the part's z axis through its origin.
      const Eigen::Vector3d axis_point = T_scene_part.translation();
      const Eigen::Vector3d axis_direction = T_scene_part.linear().col(2);
      Recognizer recognizer;
      recognizer.setModel(side.model);
      for (const Detection& d :
           recognizer.recognize(scan.render.cloud, scan.sensor, params).detections) {
        const PoseOff off = offBy(T_true, d.T_scene_model);
        std::printf("side %d, seed %d: score %.3f, %.2f° and %.2f mm off, free turn %s\n",
                    scan_side, int(seed), d.score, off.rotation_deg, off.translation_mm,
                    d.free_turn_axis ? "reported" : "not reported");
        if (!d.free_turn_axis) {
          // A rotation reported as seen is the cup's.
          EXPECT_LT(off.rotation_deg, 3.0);
          EXPECT_LT(off.translation_mm, 2.0);
          ++seen;
          continue;
        }
        ++free;
        // The rotation left free is about the cup's own axis: its line is the axis line.
        const FreeTurnAxis& a = *d.free_turn_axis;
        EXPECT_GT(std::abs(a.direction.dot(axis_direction)), std::cos(3.0 * kPi / 180.0));
        const Eigen::Vector3d offset = a.point_mm - axis_point;
        EXPECT_LT((offset - offset.dot(axis_direction) * axis_direction).norm(), 3.0);
        // Rotating the found pose about it reaches the truth, or rotating one of the poses the scan
        // cannot tell from it does (with the handle unseen, the cup's two ends can look alike),
        // or the cup was found end over end (a failure docs/results.md counts).
        double tilt_deg = 180.0;
        std::vector<Eigen::Isometry3d> poses{d.T_scene_model};
        poses.insert(poses.end(), d.alternative_poses.begin(), d.alternative_poses.end());
        for (const Eigen::Isometry3d& T : poses) {
          const Eigen::Vector3d axis_found =
              T.linear() * T_true.linear().transpose() * axis_direction;
          tilt_deg =
              std::min(tilt_deg, std::acos(std::clamp(axis_found.dot(axis_direction), -1.0, 1.0)) *
                                     180.0 / kPi);
        }
        std::printf("  %zu alternative pose(s); the best of them tilts the cup's axis by %.2f°\n",
                    d.alternative_poses.size(), tilt_deg);
        if (tilt_deg < 3.0)
          ++free_right;
        else
          EXPECT_GT(tilt_deg, 177.0) << "the cup's axis is found, if end over end";
      }
    }
  EXPECT_GE(seen, 2) << "scans whose handle shows";
  EXPECT_GE(free, 2) << "scans whose handle the view did not see that way";
  EXPECT_GE(free_right, free - 1) << "at most one cup found end over end";
}

TEST(NearRevolution, ACupFoundAtAWrongRotationIsRotatedToWhereItsHandleIs) {
  // Its surface of revolution verifies at any rotation; which of it the projector lit does not,
  // and can favour a wrong one. The handle decides (detail::resolveAxisRotations).
  const RecognitionParams params = cupParams();
  const CupOnItsSide cup;
  const auto& [side, scan, T_true] = cup;
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps;
  const auto prep = detail::prepareModel(preps, side.model, params);
  ASSERT_TRUE(prep->near_axis) << "a cup on its side is a surface of revolution but for its handle";
  const FloorRemovalResult floor = removeFloor(scan.render.cloud, params.floor, params.seed);
  const SceneIndex index(floor.remaining);
  const ProjectorShadow shadow(scan.render.cloud, scan.sensor);
  const VerifyScene scene{&index, &scan.render.cloud, &scan.sensor, floor.planes.front(), &shadow};
  const double tolerance = params.matching.verify_tolerance_mm;
  const auto verify = [&](const Eigen::Isometry3d& T) {
    return verifyPose(*prep->verify, scene, T, tolerance, {});
  };
  const RevolutionAxis& axis = *prep->near_axis;
  for (const double wrong_deg : {63.4, 127.7, 244.3}) {
    Detection d;
    d.T_scene_model = T_true * axis.turn(wrong_deg * kPi / 180.0);
    d.coverage = verify(d.T_scene_model);
    const std::vector<Detection> detections = detail::resolveAxisRotations(
        {d}, *prep, scene, params.matching, verify, [&](const Eigen::Isometry3d& T) {
          return refinePose(*prep->refine, index, T, params.refine).T_scene_model;
        });
    const PoseOff off = offBy(T_true, detections.front().T_scene_model);
    std::printf("found %.0f° off its rotation (coverage %.3f): now %.2f° and %.2f mm off, coverage "
                "%.3f\n",
                wrong_deg, d.coverage, off.rotation_deg, off.translation_mm,
                detections.front().coverage);
    EXPECT_LT(off.rotation_deg, 3.0) << "rotated to its handle";
  }
}

TEST(NearRevolution, TheRecognizerRotatesADetectionToWhereItsHandleIs) {
  // As recognizeViews does after the views' merge (Recognizer::resolveAmbiguities).
  const RecognitionParams params = cupParams();
  const CupOnItsSide cup;
  const auto& [side, scan, T_true] = cup;
  Recognizer recognizer;
  const RecognitionResult found =
      recognizer.recognize(side.model, scan.render.cloud, scan.sensor, params);
  ASSERT_EQ(found.detections.size(), 1u);
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps;
  const RevolutionAxis axis = *detail::prepareModel(preps, side.model, params)->near_axis;
  std::vector<Detection> rotated = found.detections;
  rotated.front().T_scene_model = found.detections.front().T_scene_model * axis.turn(kPi / 2);
  const std::vector<Detection> detections =
      recognizer.resolveAmbiguities(side.model, rotated, *found.scene, params);
  ASSERT_EQ(detections.size(), 1u);
  const Detection& d = detections.front();
  const PoseOff off = offBy(T_true, d.T_scene_model);
  std::printf("rotated 90° off: now %.2f° and %.2f mm off, coverage %.3f\n", off.rotation_deg,
              off.translation_mm, d.coverage);
  EXPECT_LT(off.rotation_deg, 3.0) << "rotated to its handle";
  ASSERT_EQ(d.grip_points_scene.size(), side.model->grip_points.size());
  for (std::size_t g = 0; g < d.grip_points_scene.size(); ++g)
    EXPECT_LT((d.grip_points_scene[g].position_mm -
               d.T_scene_model * side.model->grip_points[g].position_mm)
                  .norm(),
              1e-9)
        << "grip points follow the rotated pose";
  // The stage works on the scene analysis it is given, whatever the recognizer saw since.
  SynthScene other = scan;
  for (auto& p : other.render.cloud.points_mm)
    if (isValid(p)) {
      p.z() += 1.0f;
      break;
    }
  (void)recognizer.recognize(side.model, other.render.cloud, scan.sensor, params);
  const std::vector<Detection> again =
      recognizer.resolveAmbiguities(side.model, rotated, *found.scene, params);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again.front().T_scene_model.matrix(), d.T_scene_model.matrix());
}

TEST(NearRevolution, AnUprightCupInABinIsFoundByItsTopView) {
  // The phoxi-bin suite's scene-009 as synth-suite writes it: an upright cup (instance 2) among
  // others, off to the side of the projector, so its wall keeps the light off half its inside
  // (ProjectorShadow.AnUprightCupsBodyHidesPartOfItsInside). Surface voting's pose of it has the
  // handle facing away and verifies under the minimum; rotated to where the handle is, it
  // verifies.
  const RecognitionParams params = cupParams();
  const auto find = [](const std::string& name) {
    for (const SuiteScene& s :
         suiteScenes(name == "teach/phoxi-m-1032/cup" ? "teach" : "phoxi-bin", kDefaultSuiteSeed))
      if (s.relative_prefix == name)
        return synthesize(s.request);
    throw Error("no suite scene " + name);
  };
  const test::SynthTeach top = test::teachFromScan(find("teach/phoxi-m-1032/cup"), "cup", params);
  const SynthScene bin = find("phoxi-bin/scene-009");
  const auto upright = std::find_if(bin.scene.instances.begin(), bin.scene.instances.end(),
                                    [](const PartInstance& i) { return i.id == 2; });
  ASSERT_NE(upright, bin.scene.instances.end());
  const Eigen::Isometry3d T_true = bin.scene.T_scene_part(*upright) * top.T_part_model();
  Recognizer recognizer;
  recognizer.setModel(top.model);
  const RecognitionResult result = recognizer.recognize(bin.render.cloud, bin.sensor, params);
  const auto found =
      std::find_if(result.detections.begin(), result.detections.end(), [&](const Detection& d) {
        return (d.T_scene_model.translation() - T_true.translation()).norm() < 10.0;
      });
  ASSERT_NE(found, result.detections.end()) << result.detections.size() << " detections";
  const PoseOff off = offBy(T_true, found->T_scene_model);
  // The cup's axis (the part frame's z) as found against the truth.
  const Eigen::Matrix3d R_model_part = top.T_part_model().inverse().linear();
  const Eigen::Vector3d axis_true = T_true.linear() * R_model_part * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d axis_found =
      found->T_scene_model.linear() * R_model_part * Eigen::Vector3d::UnitZ();
  const double axis_deg = std::acos(std::clamp(axis_true.dot(axis_found), -1.0, 1.0)) * 180.0 / kPi;
  std::printf("upright cup found %.2f° (axis %.2f°) and %.2f mm off, coverage %.3f\n",
              off.rotation_deg, axis_deg, off.translation_mm, found->coverage);
  EXPECT_LT(axis_deg, 2.0);
  EXPECT_LT(off.translation_mm, 2.0);
  EXPECT_LT(off.rotation_deg, 10.0) << "the handle tells the rotation";
}

TEST(NearRevolution, ViewsJoinedTellTheRotationOfACupWhoseHandleNoViewSawFromThatSide) {
  // The phoxi-bin suite's scene-005 as synth-suite writes it, searched with the cup's four table
  // views as docs/accuracy.md teaches them. Instances 1 and 5 lie on their sides with the handle
  // towards the camera: the view that finds them (the cup on its side, handle up and away from its
  // teach camera) saw the handle from behind, so alone it cannot tell their rotation. Joined, the
  // other views' handle tells it.
  const RecognitionParams params = cupParams();
  const std::vector<std::shared_ptr<const TaughtModel>> views = cupTableViews(params);
  ASSERT_EQ(views.size(), 4u);
  const SynthScene bin = phoxiBin("scene-005");
  ASSERT_EQ(bin.scene.instances.size(), 6u);
  // The rotation (degrees) between each of the instances and the detection lying nearest to it.
  const auto rotationErrors = [&](const std::vector<std::shared_ptr<const TaughtModel>>& models) {
    Recognizer recognizer;
    const RecognitionResult result =
        recognizeViews(recognizer, models, bin.render.cloud, bin.sensor, params);
    std::vector<double> errors;
    for (const std::size_t i : {std::size_t{1}, std::size_t{5}}) {
      const Eigen::Isometry3d T_true = bin.scene.T_scene_part(bin.scene.instances[i]);
      double nearest_mm = 1e9, error_deg = 180.0;
      for (const Detection& d : result.detections) {
        const Eigen::Isometry3d T_found =
            d.T_scene_model * models[std::size_t(d.model_index)]->T_part_model->inverse();
        if (const PoseOff off = offBy(T_true, T_found); off.translation_mm < nearest_mm) {
          nearest_mm = off.translation_mm;
          error_deg = off.rotation_deg;
        }
      }
      std::printf("instance %zu: nearest detection %.1f mm and %.1f° off\n", i, nearest_mm,
                  error_deg);
      EXPECT_LT(nearest_mm, 16.5) << "instance " << i << " is found";
      errors.push_back(error_deg);
    }
    return errors;
  };
  std::printf("views searched each alone:\n");
  for (const double error_deg : rotationErrors(views))
    EXPECT_GT(error_deg, 10.0) << "alone, the views find the cup at a wrong rotation";
  std::printf("views joined:\n");
  for (const double error_deg : rotationErrors(joinViews(views)))
    EXPECT_LT(error_deg, 2.0) << "joined, they tell its rotation";
}

TEST(NearRevolution, ViewsJoinedTellWhichEndOfALyingCupFacesTheCamera) {
  // The phoxi-bin suite's scene-013: cups lying on their sides, three of them tilted so that one
  // end faces the camera (the mouth of instances 5 and 7, the bottom of instance 10). The views
  // that find them saw the cup from the side, where it looks the same flipped end over end, and
  // the table views that saw its ends did not see them lying so. Joined, the views' ends tell.
  const RecognitionParams params = cupParams();
  const std::vector<std::shared_ptr<const TaughtModel>> views = joinViews(cupTableViews(params));
  ASSERT_EQ(views.size(), 4u);
  const SynthScene bin = phoxiBin("scene-013");
  Recognizer recognizer;
  const RecognitionResult result =
      recognizeViews(recognizer, views, bin.render.cloud, bin.sensor, params);
  const Eigen::Vector3d bottom_part(0, 0, 0), top_part(0, 0, 95); // the cup's two ends
  for (const int id : {5, 7, 10}) {
    const auto instance = std::find_if(bin.scene.instances.begin(), bin.scene.instances.end(),
                                       [&](const PartInstance& i) { return i.id == id; });
    ASSERT_NE(instance, bin.scene.instances.end());
    const Eigen::Isometry3d T_true = bin.scene.T_scene_part(*instance);
    const Eigen::Vector3d middle = T_true * ((bottom_part + top_part) / 2);
    const Detection* nearest = nullptr;
    double nearest_mm = 30.0;
    for (const Detection& d : result.detections) {
      const Eigen::Isometry3d T_found =
          d.T_scene_model * views[std::size_t(d.model_index)]->T_part_model->inverse();
      if (const double mm = (T_found * ((bottom_part + top_part) / 2) - middle).norm();
          mm < nearest_mm) {
        nearest_mm = mm;
        nearest = &d;
      }
    }
    ASSERT_NE(nearest, nullptr) << "instance " << id << " is found";
    const Eigen::Isometry3d T_found =
        nearest->T_scene_model * views[std::size_t(nearest->model_index)]->T_part_model->inverse();
    const double bottom_mm = (T_found * bottom_part - T_true * bottom_part).norm();
    std::printf("instance %d: found with its bottom %.1f mm from the true bottom\n", id, bottom_mm);
    EXPECT_LT(bottom_mm, 5.0) << "instance " << id << " is found end over end";
  }
}

TEST(NearRevolution, ViewsJoinedTakeTheEndAtWhichTheScanConfirmsTheHandle) {
  // The phoxi-bin suite's scene-020: instance 9 lies on its side, its bottom tilted a little
  // towards the camera and its handle in sight. The side view finds it end over end, where its
  // handle would lie out of sight at every rotation; flipped back, the joined handle is confirmed.
  const RecognitionParams params = cupParams();
  const std::vector<std::shared_ptr<const TaughtModel>> views = joinViews(cupTableViews(params));
  const SynthScene bin = phoxiBin("scene-020");
  const auto instance = std::find_if(bin.scene.instances.begin(), bin.scene.instances.end(),
                                     [](const PartInstance& i) { return i.id == 9; });
  ASSERT_NE(instance, bin.scene.instances.end());
  const Eigen::Isometry3d T_true = bin.scene.T_scene_part(*instance);
  Recognizer recognizer;
  const RecognitionResult result =
      recognizeViews(recognizer, views, bin.render.cloud, bin.sensor, params);
  // The detection whose cup's middle lies nearest, wherever its ends are.
  const Eigen::Vector3d middle(0, 0, 47.5);
  double nearest_mm = 30.0, rotation_deg = 180.0;
  for (const Detection& d : result.detections) {
    const Eigen::Isometry3d T_found =
        d.T_scene_model * views[std::size_t(d.model_index)]->T_part_model->inverse();
    if (const double mm = (T_found * middle - T_true * middle).norm(); mm < nearest_mm) {
      nearest_mm = mm;
      rotation_deg = offBy(T_true, T_found).rotation_deg;
    }
  }
  std::printf("instance 9: nearest detection %.2f mm and %.2f° off\n", nearest_mm, rotation_deg);
  EXPECT_LT(nearest_mm, 16.5) << "instance 9 is found";
  EXPECT_LT(rotation_deg, 10.0) << "at its rotation";
}

TEST(NearRevolution, ALegSeenFaceOnIsNotASurfaceOfRevolution) {
  // The support's table view shows one leg face-on: its normals point one way, so a rim axis fits
  // through a circle among its nearest points, but none of the leg is rotationally symmetric about
  // it. Taken for a cup, every detection of it would search its "handle" (all of it) at 360
  // rotations.
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::SynthTeach top = test::teachFromSynth("support", 5, params, 0);
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps;
  const auto prep = detail::prepareModel(preps, top.model, params);
  EXPECT_FALSE(prep->axis);
  EXPECT_FALSE(prep->near_axis) << prep->near_axis_asymmetry.size() << " of "
                                << prep->verify->points.size()
                                << " points taken for an asymmetric feature";
  EXPECT_TRUE(prep->near_axis_asymmetry.empty());
}
