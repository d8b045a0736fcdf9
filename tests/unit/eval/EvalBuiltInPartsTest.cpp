// The evaluator against the virtual scanner's real parts and ground-truth files (core/sim): the
// built-in parts' symmetries behave as the evaluator needs, and a ground truth written by the
// scanner reads back and scores perfect detections perfectly.
#include "core/eval/Evaluator.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/Synth.h"
#include "tests/unit/eval/EvalTestSupport.h"

#include <gtest/gtest.h>

using namespace scanpick;
using test::pose;

namespace {

/// The evaluator's view of a built-in part (what the ground-truth file carries).
core::eval::PartInfo partInfoOf(const core::Part& part) {
  core::eval::PartInfo info;
  info.name = part.name;
  info.diameter_mm = part.diameter_mm();
  for (const auto& g : part.grip_points)
    info.grip_points_part.push_back({g.name, g.position_mm});
  if (part.symmetry.continuous_axis)
    info.symmetry.continuous_axis = core::eval::ContinuousAxis{
        part.symmetry.continuous_axis->point_mm, part.symmetry.continuous_axis->direction};
  info.symmetry.discrete = part.symmetry.discrete;
  return info;
}

/// Outcome of one detection at `T_est` against one instance at `T_true`.
core::eval::DetectionOutcome judge(const core::eval::PartInfo& part,
                                   const Eigen::Isometry3d& T_true,
                                   const Eigen::Isometry3d& T_est) {
  const auto teach = test::makeTeachTruth(part);
  core::eval::GroundTruth truth;
  truth.parts[part.name] = part;
  truth.instances.push_back({0, part.name, T_true, 1.0, 1000});
  auto results = test::makeResults();
  test::addDetection(results, 0.5, T_est, teach);
  return core::eval::evaluateScene(truth, results, teach, {}, "scene").outcomes.front();
}

} // namespace

TEST(EvalBuiltInParts, PumpConnectorQuarterTurnIsCorrectCupQuarterTurnIsNot) {
  // Both parts have their axis along the part frame's z. The connector's listed symmetries
  // (3 quarter turns, 4 end-to-end flips) already form a group: closing it adds nothing.
  const auto pump = partInfoOf(core::builtInPart("pump-connector"));
  const auto cup = partInfoOf(core::builtInPart("cup"));
  EXPECT_EQ(core::eval::symmetryGroup(pump.symmetry, pump.diameter_mm).size(),
            pump.symmetry.discrete.size() + 1);
  EXPECT_TRUE(cup.symmetry.discrete.empty());
  EXPECT_FALSE(cup.symmetry.continuous_axis);

  const Eigen::Isometry3d T_true = pose({20, -40, 780}, 65, Eigen::Vector3d(1, -1, 0.5));
  const Eigen::Isometry3d quarter = T_true * pose({0, 0, 0}, 90);
  const auto pump_outcome = judge(pump, T_true, quarter);
  EXPECT_TRUE(pump_outcome.true_positive);
  EXPECT_NEAR(pump_outcome.error->rotation_deg, 0.0, 1e-6);
  const auto cup_outcome = judge(cup, T_true, quarter);
  EXPECT_FALSE(cup_outcome.true_positive);
  EXPECT_NEAR(cup_outcome.error->rotation_deg, 90.0, 1e-6);
  // 45° is no symmetry of the connector (its four bolt holes are 90° apart).
  EXPECT_FALSE(judge(pump, T_true, T_true * pose({0, 0, 0}, 45)).true_positive);
  // Every listed symmetry of every built-in part is an exact equivalent pose.
  for (const auto& name : core::builtInPartNames()) {
    const auto part = partInfoOf(core::builtInPart(name));
    for (const auto& S : part.symmetry.discrete) {
      const auto o = judge(part, T_true, T_true * S);
      EXPECT_TRUE(o.true_positive) << name;
      EXPECT_NEAR(o.error->translation_mm, 0.0, 1e-6) << name;
    }
  }
}

TEST(EvalBuiltInParts, ScannerGroundTruthScoresPerfectDetectionsPerfectly) {
  // A teach scan and a small scattered scene from the virtual scanner; detections placed exactly
  // on the ground-truth poses must give precision 1 and zero error, so the scanner's files and
  // the evaluator's reader agree on the format.
  core::SynthRequest teach_request;
  teach_request.parts = {"pump-connector"};
  teach_request.layout = core::LayoutKind::Teach;
  teach_request.count = 1;
  teach_request.seed = 3;
  core::SynthRequest scene_request = teach_request;
  scene_request.layout = core::LayoutKind::Scatter;
  scene_request.count = 3;
  scene_request.seed = 4;
  const auto teach =
      core::eval::parseGroundTruth(nlohmann::json::parse(core::groundTruthJson(
                                       core::synthesize(teach_request), "t.pcd", "t.png")),
                                   "teach");
  const auto truth =
      core::eval::parseGroundTruth(nlohmann::json::parse(core::groundTruthJson(
                                       core::synthesize(scene_request), "s.pcd", "s.png")),
                                   "scene");
  ASSERT_EQ(teach.instances.size(), 1u);
  ASSERT_EQ(truth.instances.size(), 3u);
  EXPECT_EQ(truth.parts.at("pump-connector").symmetry.discrete.size(), 7u);

  auto results = test::makeResults();
  for (const auto& instance : truth.instances)
    test::addDetection(results, 0.7, instance.T_scene_part, teach);
  const auto report =
      core::eval::makeReport({core::eval::evaluateScene(truth, results, teach, {}, "s")}, {});
  EXPECT_DOUBLE_EQ(*report.overall.precision, 1.0);
  EXPECT_EQ(report.overall.true_positives, 3);
  EXPECT_NEAR(report.overall.translation_mm.max, 0.0, 1e-6);
  EXPECT_NEAR(report.overall.rotation_deg.max, 0.0, 1e-6);
}
