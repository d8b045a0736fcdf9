// Matching, symmetry-aware errors and metrics of the evaluator, on ground truth built in code.
#include "core/eval/Evaluator.h"

#include "core/common/Error.h"
#include "tests/unit/eval/EvalTestSupport.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace scanpick;
using core::eval::GroundTruth;
using test::pose;

namespace {

/// A bin with three instances of a 60 mm part: two well visible, one mostly hidden.
GroundTruth binOf(const core::eval::PartInfo& part) {
  GroundTruth truth;
  truth.source = "bin (test)";
  truth.kind = "bin";
  truth.parts[part.name] = part;
  truth.instances.push_back(
      {10, part.name, pose({0, 0, 800}, 40, Eigen::Vector3d(1, 0, 1)), 0.9, 900});
  truth.instances.push_back({11, part.name, pose({100, 20, 810}, 170), 0.7, 700});
  truth.instances.push_back(
      {12, part.name, pose({-90, 40, 790}, -60, Eigen::Vector3d::UnitY()), 0.3, 300});
  return truth;
}

core::eval::SceneEvaluation evaluate(const GroundTruth& truth, const core::eval::ResultsFile& r,
                                     const GroundTruth& teach) {
  return core::eval::evaluateScene(truth, r, teach, core::eval::Tolerances{}, "scene");
}

} // namespace

TEST(Evaluator, PerfectDetectionsScoreOneAndZeroError) {
  const auto part = test::makePart("widget", 60.0);
  const auto teach = test::makeTeachTruth(part);
  const auto truth = binOf(part);
  auto results = test::makeResults();
  for (const auto& instance : truth.instances)
    test::addDetection(results, 0.8, instance.T_scene_part, teach);
  results.total_ms = 250.0;

  const auto report = core::eval::makeReport({evaluate(truth, results, teach)}, {});
  const auto& s = report.overall;
  // Every detection sits exactly on an instance: 3 TP; the 30 %-visible instance is matched
  // but is not among the 2 instances recall is computed over.
  EXPECT_EQ(s.true_positives, 3);
  EXPECT_EQ(s.visible_instances, 2);
  ASSERT_TRUE(s.precision && s.recall);
  EXPECT_DOUBLE_EQ(*s.precision, 1.0);
  EXPECT_DOUBLE_EQ(*s.recall, 1.0);
  EXPECT_DOUBLE_EQ(s.recall_at_99_precision, 1.0);
  EXPECT_NEAR(s.average_precision, 1.0, 1e-12);
  EXPECT_NEAR(s.translation_mm.max, 0.0, 1e-9);
  EXPECT_NEAR(s.rotation_deg.max, 0.0, 1e-6);
  EXPECT_EQ(s.grip_mm.count, 3u); // one grip point per true positive
  EXPECT_NEAR(s.grip_mm.max, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.time_ms.median, 250.0);
}

TEST(Evaluator, MovedOrTurnedDetectionIsFalsePositive) {
  // 60 mm part: a true positive must be within 0.1 × 60 = 6 mm and 10°.
  const auto part = test::makePart("widget", 60.0);
  const auto teach = test::makeTeachTruth(part);
  GroundTruth truth;
  truth.parts[part.name] = part;
  const Eigen::Isometry3d T_true = pose({10, 20, 800}, 25, Eigen::Vector3d(0, 1, 0));
  truth.instances.push_back({0, part.name, T_true, 1.0, 1000});

  const Eigen::Isometry3d moved = pose({8, 0, 0}) * T_true; // 8 mm off
  const Eigen::Isometry3d turned = T_true * pose({0, 0, 0}, 20, Eigen::Vector3d::UnitX()); // 20°
  const Eigen::Isometry3d close = pose({0, 3, 0}) * T_true * pose({0, 0, 0}, 5); // 3 mm, 5°
  for (const auto& [T_est, tp, t_mm, r_deg] :
       {std::tuple{moved, false, 8.0, 0.0}, std::tuple{turned, false, 0.0, 20.0},
        std::tuple{close, true, 3.0, 5.0}}) {
    auto results = test::makeResults();
    test::addDetection(results, 0.5, T_est, teach);
    const auto scene = evaluate(truth, results, teach);
    ASSERT_EQ(scene.outcomes.size(), 1u);
    const auto& o = scene.outcomes.front();
    EXPECT_EQ(o.true_positive, tp) << "expected error " << t_mm << " mm, " << r_deg << " deg";
    ASSERT_TRUE(o.error);
    EXPECT_NEAR(o.error->translation_mm, t_mm, 1e-6);
    EXPECT_NEAR(o.error->rotation_deg, r_deg, 1e-6);
    EXPECT_EQ(o.nearest_instance_id, 0);
  }
}

TEST(Evaluator, CupTurnedAboutItsAxisIsWrongButPumpConnectorIsNot) {
  // The cup's handle breaks its rotational symmetry: no symmetry transforms. The pump connector
  // has 4-fold symmetry about its z axis; only the 90° generator is listed, so this also checks
  // that the evaluator closes the group (180°, 270°).
  auto cup = test::makePart("cup", 95.0);
  auto pump = test::makePart("pump-connector", 50.0);
  pump.symmetry.discrete.push_back(pose({0, 0, 0}, 90));

  for (const auto* part : {&cup, &pump}) {
    const auto teach = test::makeTeachTruth(*part);
    GroundTruth truth;
    truth.parts[part->name] = *part;
    const Eigen::Isometry3d T_true = pose({30, -10, 760}, 50, Eigen::Vector3d(1, 1, 0));
    truth.instances.push_back({0, part->name, T_true, 0.8, 800});
    for (const double angle : {90.0, 180.0, 270.0}) {
      auto results = test::makeResults();
      test::addDetection(results, 0.6, T_true * pose({0, 0, 0}, angle), teach);
      const auto evaluation = evaluate(truth, results, teach);
      const auto& o = evaluation.outcomes.front();
      const bool symmetric = part == &pump;
      EXPECT_EQ(o.true_positive, symmetric) << part->name << " turned " << angle << " deg";
      // The cup's error is the full turn (180° for 180°, 90° for 270°); the connector's is zero.
      EXPECT_NEAR(o.error->rotation_deg, symmetric ? 0.0 : std::min(angle, 360.0 - angle), 1e-6);
      // Its grip point 20 mm up the axis does not move when turning about the axis.
      EXPECT_NEAR(o.error->grip_mm.at(0), 0.0, 1e-9);
    }
  }
}

TEST(Evaluator, ContinuousAxisIgnoresRotationAboutIt) {
  // A cylinder whose axis is parallel to z through (10, 0, 0), off its origin: turning about
  // that line by any angle is the same pose; tilting the axis by 20° is not.
  auto cylinder = test::makePart("cylinder", 40.0);
  cylinder.symmetry.continuous_axis = core::eval::ContinuousAxis{{10, 0, 0}, {0, 0, 1}};
  const auto teach = test::makeTeachTruth(cylinder);
  GroundTruth truth;
  truth.parts[cylinder.name] = cylinder;
  const Eigen::Isometry3d T_true = pose({0, 0, 700}, 35, Eigen::Vector3d(0, 1, 0));
  truth.instances.push_back({0, cylinder.name, T_true, 1.0, 1000});

  // Rotation about the axis line: translate to the axis point, turn, translate back.
  const Eigen::Isometry3d about_axis = pose({10, 0, 0}) * pose({0, 0, 0}, 123) * pose({-10, 0, 0});
  const Eigen::Isometry3d tilted = T_true * pose({0, 0, 0}, 20, Eigen::Vector3d::UnitX());
  auto results = test::makeResults();
  test::addDetection(results, 0.9, T_true * about_axis, teach);
  test::addDetection(results, 0.8, tilted, teach);
  const auto scene = evaluate(truth, results, teach);
  ASSERT_EQ(scene.outcomes.size(), 2u);
  EXPECT_TRUE(scene.outcomes[0].true_positive);
  EXPECT_NEAR(scene.outcomes[0].error->rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(scene.outcomes[0].error->translation_mm, 0.0, 1e-6);
  EXPECT_FALSE(scene.outcomes[1].true_positive);
  EXPECT_NEAR(scene.outcomes[1].error->rotation_deg, 20.0, 1e-6);
}

TEST(Evaluator, ReportedFreeTurnIsAcceptedOnlyWhenAsked) {
  // A part without symmetry, detected turned 30° about a line parallel to its z axis through
  // (0, 5, 0) (part frame). The detection reports that line (scene frame) as its free turn axis:
  // strictly it is wrong; with accept_free_turns it is right, with zero error. A detection
  // turned about another line (x) stays wrong either way.
  const auto part = test::makePart("pipe", 100.0);
  const auto teach = test::makeTeachTruth(part);
  GroundTruth truth;
  truth.parts[part.name] = part;
  const Eigen::Isometry3d T_true = pose({20, 0, 780}, 70, Eigen::Vector3d(1, 0, 1));
  truth.instances.push_back({0, part.name, T_true, 0.9, 900});
  const Eigen::Isometry3d turn = pose({0, 5, 0}) * pose({0, 0, 0}, 30) * pose({0, -5, 0});
  const Eigen::Isometry3d T_turned = T_true * turn;
  const core::eval::ContinuousAxis axis_scene{T_turned * Eigen::Vector3d(0, 5, 0),
                                              T_turned.linear() * Eigen::Vector3d::UnitZ()};
  for (const bool accept : {false, true}) {
    auto results = test::makeResults();
    test::addDetection(results, 0.9, T_turned, teach);
    test::addDetection(results, 0.8, T_true * pose({0, 0, 0}, 30, Eigen::Vector3d::UnitX()), teach);
    for (auto& d : results.detections)
      d.free_turn_axis = axis_scene;
    core::eval::Tolerances tolerances;
    tolerances.accept_free_turns = accept;
    const auto scene = core::eval::evaluateScene(truth, results, teach, tolerances, "scene");
    ASSERT_EQ(scene.outcomes.size(), 2u);
    EXPECT_EQ(scene.outcomes[0].true_positive, accept);
    EXPECT_NEAR(scene.outcomes[0].error->rotation_deg, accept ? 0.0 : 30.0, 1e-6);
    EXPECT_NEAR(scene.outcomes[0].error->translation_mm,
                accept ? 0.0 : 2.0 * 5.0 * std::sin(test::degToRad(15.0)), 1e-6);
    EXPECT_FALSE(scene.outcomes[1].true_positive) << "turned about another axis";
  }
}

TEST(Evaluator, ReportedAlternativePoseIsAcceptedOnlyWhenAsked) {
  // A part without symmetry, detected turned 180° about its z axis; the detection reports the
  // true pose as its alternative (a near symmetry its scan could not decide). Strictly it is
  // wrong; with accept_free_turns the alternative scores it, with zero error. A detection whose
  // alternative is wrong too stays wrong either way.
  const auto part = test::makePart("hook-plate", 80.0);
  const auto teach = test::makeTeachTruth(part);
  GroundTruth truth;
  truth.parts[part.name] = part;
  const Eigen::Isometry3d T_true = pose({-40, 10, 800}, 25, Eigen::Vector3d(0, 1, 1));
  truth.instances.push_back({0, part.name, T_true, 1.0, 1000});
  const Eigen::Isometry3d T_turned = T_true * pose({0, 0, 0}, 180);
  for (const bool accept : {false, true}) {
    auto results = test::makeResults();
    test::addDetection(results, 0.9, T_turned, teach);
    test::addDetection(results, 0.8, T_turned, teach);
    results.detections[0].alternative_poses = {
        test::modelPoseFor(T_true * pose({0, 0, 0}, 90), teach), test::modelPoseFor(T_true, teach)};
    results.detections[1].alternative_poses = {
        test::modelPoseFor(T_true * pose({0, 0, 0}, 90), teach)};
    core::eval::Tolerances tolerances;
    tolerances.accept_free_turns = accept;
    const auto scene = core::eval::evaluateScene(truth, results, teach, tolerances, "scene");
    ASSERT_EQ(scene.outcomes.size(), 2u);
    EXPECT_EQ(scene.outcomes[0].true_positive, accept);
    EXPECT_NEAR(scene.outcomes[0].error->rotation_deg, accept ? 0.0 : 180.0, 1e-6);
    EXPECT_FALSE(scene.outcomes[1].true_positive) << "its alternative is wrong too";
  }
}

TEST(Evaluator, AnAlternativePosesFreeTurnIsItsOwn) {
  // A cup-like part found end over end (turned 180° about x); its alternative, the other end,
  // is off by a turn about the part's z axis that the alternative reports as not seen. Accepted,
  // the alternative scores the instance; the same free turn reported for the detection's own pose
  // would not (that pose is the wrong end).
  const auto part = test::makePart("cup-like", 100.0);
  const auto teach = test::makeTeachTruth(part);
  GroundTruth truth;
  truth.parts[part.name] = part;
  const Eigen::Isometry3d T_true = pose({10, -20, 790}, 40, Eigen::Vector3d(1, 1, 0));
  truth.instances.push_back({0, part.name, T_true, 1.0, 1000});
  const Eigen::Isometry3d T_flipped = T_true * pose({0, 0, 0}, 180, Eigen::Vector3d::UnitX());
  const Eigen::Isometry3d T_alternative = T_true * pose({0, 0, 0}, 126);
  const core::eval::ContinuousAxis axis_of_alternative{
      T_alternative.translation(), T_alternative.linear() * Eigen::Vector3d::UnitZ()};
  for (const bool per_alternative : {false, true}) {
    auto results = test::makeResults();
    test::addDetection(results, 0.9, T_flipped, teach);
    auto& d = results.detections[0];
    d.alternative_poses = {test::modelPoseFor(T_alternative, teach)};
    if (per_alternative)
      d.alternative_free_turn_axes = {axis_of_alternative};
    else
      d.free_turn_axis = core::eval::ContinuousAxis{T_flipped.translation(),
                                                    T_flipped.linear() * Eigen::Vector3d::UnitZ()};
    core::eval::Tolerances tolerances;
    tolerances.accept_free_turns = true;
    const auto scene = core::eval::evaluateScene(truth, results, teach, tolerances, "scene");
    ASSERT_EQ(scene.outcomes.size(), 1u);
    EXPECT_EQ(scene.outcomes[0].true_positive, per_alternative);
  }
}

TEST(Evaluator, GreedyOneToOneMatchingAndThresholdSweep) {
  const auto part = test::makePart("widget", 60.0);
  const auto teach = test::makeTeachTruth(part);
  const auto truth = binOf(part); // instances 10, 11 count for recall, 12 does not
  auto results = test::makeResults();
  // Scores 0.9 (on 10), 0.8 (duplicate of 10, 1 mm off), 0.7 (on 11), 0.6 (nowhere).
  test::addDetection(results, 0.9, truth.instances[0].T_scene_part, teach);
  test::addDetection(results, 0.8, pose({1, 0, 0}) * truth.instances[0].T_scene_part, teach);
  test::addDetection(results, 0.7, truth.instances[1].T_scene_part, teach);
  test::addDetection(results, 0.6, pose({0, 0, 300}), teach);
  const auto scene = evaluate(truth, results, teach);
  ASSERT_EQ(scene.outcomes.size(), 4u);
  EXPECT_EQ(scene.outcomes[0].instance_id, 10);
  EXPECT_FALSE(scene.outcomes[1].true_positive) << "an instance is matched once";
  EXPECT_EQ(scene.outcomes[1].nearest_instance_id, 10);
  EXPECT_EQ(scene.outcomes[2].instance_id, 11);
  EXPECT_FALSE(scene.outcomes[3].true_positive);

  const auto s = core::eval::summarize({scene}, "all");
  EXPECT_DOUBLE_EQ(*s.precision, 0.5); // 2 of 4
  EXPECT_DOUBLE_EQ(*s.recall, 1.0);    // both visible instances
  // Thresholds: >=0.9 -> P 1, R 0.5; >=0.8 -> P 0.5; >=0.7 -> P 2/3, R 1; >=0.6 -> P 0.5.
  // Only the first keeps 99 % precision.
  EXPECT_DOUBLE_EQ(s.recall_at_99_precision, 0.5);
  EXPECT_DOUBLE_EQ(*s.threshold_at_99_precision, 0.9);
  // AP = 0.5 × 1 (up to recall 0.5) + 0.5 × 2/3 (up to recall 1).
  EXPECT_NEAR(s.average_precision, 0.5 + 0.5 * 2.0 / 3.0, 1e-12);
}

TEST(Evaluator, DetectionOfAnotherPartIsFalsePositive) {
  const auto part = test::makePart("widget", 60.0);
  const auto other = test::makePart("gear", 60.0);
  const auto teach = test::makeTeachTruth(part);
  GroundTruth truth;
  truth.parts[part.name] = part;
  truth.parts[other.name] = other;
  truth.instances.push_back({0, other.name, pose({0, 0, 800}), 1.0, 1000});
  auto results = test::makeResults();
  test::addDetection(results, 0.9, pose({0, 0, 800}), teach);
  const auto scene = evaluate(truth, results, teach);
  EXPECT_EQ(scene.instances, 0);
  EXPECT_FALSE(scene.outcomes.front().true_positive);
  EXPECT_FALSE(scene.outcomes.front().error);                 // no widget to compare with
  EXPECT_FALSE(core::eval::summarize({scene}, "all").recall); // undefined without instances
}

TEST(Evaluator, StatsUseLinearInterpolation) {
  // Sorted 1..5: median is the middle value; p95 sits at position 0.95 × 4 = 3.8 -> 4.8.
  const auto s = core::eval::computeStats({5, 1, 4, 2, 3});
  EXPECT_EQ(s.count, 5u);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.p95, 4.8);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
}

TEST(Evaluator, SymmetryGroupIsClosedAndBounded) {
  core::eval::PartSymmetry symmetry;
  symmetry.discrete.push_back(pose({0, 0, 0}, 90));
  symmetry.discrete.push_back(pose({0, 0, 0}, 180, Eigen::Vector3d::UnitX()));
  // 4-fold about z plus a flip: the dihedral group D4 with 8 elements.
  EXPECT_EQ(core::eval::symmetryGroup(symmetry, 50.0).size(), 8u);
  symmetry.discrete = {pose({0, 0, 0}, 1.0 / std::numbers::pi)}; // never closes
  EXPECT_THROW(core::eval::symmetryGroup(symmetry, 50.0), core::Error);
}

TEST(Evaluator, TeachTruthMustHoldOneInstance) {
  const auto part = test::makePart("widget", 60.0);
  auto teach = test::makeTeachTruth(part);
  teach.instances.push_back(teach.instances.front());
  EXPECT_THROW(evaluate(binOf(part), test::makeResults(), teach), core::Error);
}
