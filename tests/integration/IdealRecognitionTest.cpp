// The thesis's ideal test (§5.1, tables 5.1 and 5.2) through the whole pipeline: teach the
// two-circle two-line model, find its 12 rotated copies in one scene with clustering on.
#include "core/cloud/Sensor.h"
#include "core/model/TaughtModel.h"
#include "core/pipeline/Recognizer.h"
#include "tests/unit/pipeline/IdealScene.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;

namespace {

struct Outcome {
  int good = 0;                                     // copies found with a pose within the tolerance
  double max_position_mm = 0, max_rotation_deg = 0; // over the good ones
  std::size_t detections = 0;
};

std::shared_ptr<const TaughtModel> teachIdeal() {
  const auto part = test::idealPartPoints();
  Eigen::Isometry3d T_teach_part = Eigen::Isometry3d::Identity();
  T_teach_part.translation() = Eigen::Vector3d(0, 0, 700);
  const PointCloud scan = test::idealScene(part, {T_teach_part}, 0.0, 1);
  TeachOptions options;
  options.name = "ideal";
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  options.sensor = sensorPreset("phoxi-m-1032");
  return std::make_shared<TaughtModel>(teach(scan, options, test::idealParams(0.001)));
}

/// Beyond the thesis: point-level verification re-ranking several hypotheses per search.
RecognitionParams verified(RecognitionParams p, double tolerance_mm) {
  p.matching.verify_tolerance_mm = tolerance_mm;
  p.matching.hypotheses = 8;
  return p;
}

Outcome run(const TaughtModel& model, double noise_mm, double line_threshold_mm,
            double position_tol_mm, double rotation_tol_deg, double verify_mm = 0.0) {
  const auto poses = test::idealCopyPoses();
  const PointCloud scene = test::idealScene(test::idealPartPoints(), poses, noise_mm, 2024);
  Recognizer recognizer(std::make_shared<TaughtModel>(model));
  RecognitionParams params = test::idealParams(line_threshold_mm);
  if (verify_mm > 0)
    params = verified(params, verify_mm);
  const RecognitionResult result =
      recognizer.recognize(scene, sensorPreset("phoxi-m-1032"), params);
  // Expected model pose of copy k: T_scene_part · T_teach_part⁻¹ · T_teach_model, with the teach
  // scan at T_teach_part = translation (0, 0, 700).
  Eigen::Isometry3d T_part_teach = Eigen::Isometry3d::Identity();
  T_part_teach.translation() = Eigen::Vector3d(0, 0, -700);
  Outcome out;
  out.detections = result.detections.size();
  for (const auto& T_scene_part : poses) {
    const Eigen::Isometry3d expected = T_scene_part * T_part_teach * model.T_teach_model;
    double best_dp = 1e9, best_dr = 1e9, best_coverage = -1;
    for (const auto& d : result.detections) {
      const double dp = (d.T_scene_model.translation() - expected.translation()).norm();
      const double dr =
          Eigen::AngleAxisd(d.T_scene_model.linear().transpose() * expected.linear()).angle() *
          180.0 / M_PI;
      if (dp < best_dp) {
        best_dp = dp;
        best_dr = dr;
        best_coverage = d.coverage;
      }
      if (dp < position_tol_mm && dr < rotation_tol_deg) {
        ++out.good;
        out.max_position_mm = std::max(out.max_position_mm, dp);
        out.max_rotation_deg = std::max(out.max_rotation_deg, dr);
        break;
      }
    }
    std::printf("  copy: nearest detection %.3f mm, %.3f deg (coverage %.3f)\n", best_dp, best_dr,
                best_coverage);
  }
  std::printf("noise %.1f mm: %d/12 good, %zu detections, %.2f ms total, worst %.4f mm %.4f deg\n",
              noise_mm, out.good, out.detections, result.timings.total_ms, out.max_position_mm,
              out.max_rotation_deg);
  return out;
}

} // namespace

TEST(IdealRecognition, ModelHasTheFourFeatures) {
  const auto model = teachIdeal();
  EXPECT_EQ(model->features.size(), 4u);
}

TEST(IdealRecognition, AllTwelveCopiesExactWithoutNoise) {
  const auto model = teachIdeal();
  const Outcome o = run(*model, 0.0, 0.001, 0.1, 0.1);
  EXPECT_EQ(o.good, 12);
  EXPECT_EQ(o.detections, 12u); // and nothing else
}

TEST(IdealRecognition, AllTwelveWithNoiseOf0_3mm) {
  // Table 5.2 (line threshold 0.5 mm); the thesis found 12 of 12. Good = within 2 mm and 2°.
  const auto model = teachIdeal();
  EXPECT_EQ(run(*model, 0.3, 0.5, 2.0, 2.0).good, 12);
}

TEST(IdealRecognition, MostWithNoiseOf1mm) {
  // Thesis behaviour (feature score only): the thesis found 9 of 12 with 1 mm of noise; this
  // finds 7 (seed 2024). Every copy is located within 1 mm, but in the other 5 the lines' RANSAC
  // fails on the noise and only the two parallel circles remain, which cannot tell the part from
  // its 180° flip about the axis joining them. The bound guards regressions.
  const auto model = teachIdeal();
  EXPECT_GE(run(*model, 1.0, 0.5, 2.0, 2.0).good, 6);
}

TEST(IdealRecognition, AllWithNoiseOf1mmWhenVerified) {
  // Beyond the thesis: several hypotheses per search re-ranked by the share of model points
  // confirmed within 2 mm (twice the noise). A flip leaves the lines' points where the scene has
  // none, so the right pose wins even when only the circles were matched.
  const auto model = teachIdeal();
  const Outcome o = run(*model, 1.0, 0.5, 2.0, 2.0, 2.0);
  EXPECT_GE(o.good, 11);
}
