// The render check (core/eval/RenderCheck.h) with the virtual scanner's built-in parts: a pose the
// scan cannot tell from the truth changes no pixel, a wrong one changes many.
#include "core/eval/RenderCheck.h"

#include "core/common/Error.h"
#include "core/sim/PartCatalog.h"
#include "tests/unit/eval/EvalTestSupport.h"

#include <gtest/gtest.h>
#include <memory>

using namespace scanpick;
using test::pose;

namespace {

/// A PhoXi scene of a cup lying on its side and a pump-connector standing on a flange, both about
/// 800 mm in front of the camera (scene frame = camera frame, z along the view).
core::eval::GroundTruth twoParts() {
  core::eval::GroundTruth truth;
  truth.source = "two-parts";
  truth.sensor_preset = "phoxi-m-1032";
  truth.parts["cup"] = test::makePart("cup", 165);
  truth.parts["pump-connector"] = test::makePart("pump-connector", 140);
  truth.instances.push_back(
      {3, "cup", pose({-90, 10, 800}, 90, Eigen::Vector3d::UnitX()), 1.0, 1000});
  truth.instances.push_back(
      {5, "pump-connector", pose({90, -10, 800}, 180, Eigen::Vector3d::UnitX()), 1.0, 1000});
  return truth;
}

} // namespace

TEST(RenderCheck, TheTruePoseChangesNothingAndAShiftChangesMuch) {
  const auto truth = twoParts();
  const core::eval::TruthRenderer renderer(truth);
  for (const auto& instance : truth.instances) {
    const auto same = renderer.difference(instance.id, instance.T_scene_part, 1.0);
    EXPECT_GT(same.pixels, 2000u) << instance.part;
    EXPECT_EQ(same.differing, 0u) << instance.part;
    // 5 mm sideways: the part's outline and every slanted face move (fewest for the connector
    // seen along its axis, its flange face flat).
    const auto shifted =
        renderer.difference(instance.id, pose({5, 0, 0}) * instance.T_scene_part, 1.0);
    EXPECT_GT(shifted.fraction(), 0.15) << instance.part;
  }
}

TEST(RenderCheck, ASymmetryIsUnseenAHiddenDetailIsNot) {
  const auto truth = twoParts();
  const core::eval::TruthRenderer renderer(truth);
  const auto& cup = truth.instances[0];
  const auto& pump = truth.instances[1];
  // The connector's four bolt holes repeat every quarter turn about its axis (part z).
  const auto quarter = renderer.difference(pump.id, pump.T_scene_part * pose({0, 0, 0}, 90), 1.0);
  EXPECT_LT(quarter.fraction(), 0.01);
  // Half of that moves the holes, and a quarter turn moves the cup's handle.
  EXPECT_GT(renderer.difference(pump.id, pump.T_scene_part * pose({0, 0, 0}, 45), 1.0).fraction(),
            quarter.fraction() + 0.05);
  EXPECT_GT(renderer.difference(cup.id, cup.T_scene_part * pose({0, 0, 0}, 90), 1.0).fraction(),
            0.04);
}

TEST(RenderCheck, FindsTheInstanceADetectionLiesOnAndRejectsBadInput) {
  const auto truth = twoParts();
  const core::eval::TruthRenderer renderer(truth);
  const auto& cup = truth.instances[0];
  // The cup end over end about a line through its middle: still the same cup.
  const Eigen::Vector3d middle = core::builtInPart("cup").center_mm();
  const Eigen::Isometry3d flipped = cup.T_scene_part * Eigen::Translation3d(middle) *
                                    pose({0, 0, 0}, 180, Eigen::Vector3d::UnitX()) *
                                    Eigen::Translation3d(-middle);
  EXPECT_EQ(renderer.instanceAt("cup", flipped), cup.id);
  EXPECT_EQ(renderer.instanceAt("pump-connector", flipped), truth.instances[1].id);
  EXPECT_EQ(renderer.instanceAt("support", flipped), -1);

  EXPECT_THROW((void)renderer.difference(42, cup.T_scene_part, 1.0), core::Error);
  EXPECT_THROW((void)renderer.difference(cup.id, cup.T_scene_part, 0.0), core::Error);
  auto unnamed = truth;
  unnamed.sensor_preset.clear();
  EXPECT_THROW(core::eval::TruthRenderer{unnamed}, core::Error);
  auto unknown = truth;
  unknown.instances[0].part = "teapot";
  try {
    core::eval::TruthRenderer{unknown};
    ADD_FAILURE() << "a part that is not built in is refused";
  } catch (const core::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'teapot'"), std::string::npos) << message;
    EXPECT_NE(message.find("without --render-check"), std::string::npos) << message;
  }
}

TEST(RenderCheck, TheBinsWallShadowsWhatTheProjectorCannotReach) {
  // A cup lying on the bin's floor (the camera 850 mm above its middle, as the simulator puts it)
  // with its handle towards the wall on the projector's side, 1.5 mm from it: the wall keeps the
  // projector's light off the handle, so the scan cannot tell the cup's turn while the handle stays
  // there. Rendered alone, the parts would show the handle and its turn.
  core::eval::GroundTruth truth;
  truth.source = "bin-wall";
  truth.sensor_preset = "phoxi-m-1032";
  truth.kind = "bin";
  Eigen::Isometry3d T_world_scene = Eigen::Isometry3d::Identity();
  T_world_scene.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  T_world_scene.translation() = Eigen::Vector3d(0, 0, 850);
  truth.T_scene_world = T_world_scene.inverse();
  truth.parts["cup"] = test::makePart("cup", 165);
  // Part x (the handle) along the world's x, its axis (part z) along the world's y, lying on the
  // floor (z = 0) with its handle's outside 1.5 mm from the wall at x = 180.
  Eigen::Isometry3d T_world_cup = Eigen::Isometry3d::Identity();
  T_world_cup.linear().col(0) = Eigen::Vector3d::UnitX();
  T_world_cup.linear().col(1) = -Eigen::Vector3d::UnitZ();
  T_world_cup.linear().col(2) = Eigen::Vector3d::UnitY();
  T_world_cup.translation() = Eigen::Vector3d(110, -47.5, 40);
  truth.instances.push_back({1, "cup", *truth.T_scene_world * T_world_cup, 1.0, 1000});
  const auto& cup = truth.instances[0];
  const Eigen::Isometry3d turned = cup.T_scene_part * pose({0, 0, 0}, 40);
  auto alone = truth;
  alone.T_scene_world.reset();
  const double in_bin = core::eval::TruthRenderer(truth).difference(cup.id, turned, 3.0).fraction();
  const double parts_alone =
      core::eval::TruthRenderer(alone).difference(cup.id, turned, 3.0).fraction();
  std::printf("turned 40°: %.3f of the cup's pixels differ in the bin, %.3f rendered alone\n",
              in_bin, parts_alone);
  EXPECT_LT(in_bin, 0.05) << "the handle stays in the wall's shadow";
  EXPECT_GT(parts_alone, 0.08) << "alone, the handle shows elsewhere";
  EXPECT_EQ(core::eval::TruthRenderer(truth).difference(cup.id, cup.T_scene_part, 3.0).differing,
            0u);
}

// The alternatives a true positive reports: a quarter turn of the 4-fold pump-connector is an
// ambiguity no scan tells; a quarter turn of the lying cup moves its handle, which a scan shows.
TEST(RenderCheck, TellsWhetherTheAlternativesADetectionReportsAreAmbiguitiesAScanCannotTell) {
  const auto truth = std::make_shared<const core::eval::GroundTruth>(twoParts());
  const auto outcome = [&](const core::eval::TruthInstance& instance, double turn_deg) {
    core::eval::DetectionOutcome o;
    o.true_positive = true;
    o.instance_id = instance.id;
    o.error = core::eval::PoseError{};
    o.T_scene_part = instance.T_scene_part;
    o.alternatives_scene_part = {instance.T_scene_part * pose({0, 0, 0}, turn_deg)};
    return o;
  };
  core::eval::EvalReport report;
  for (const auto& instance : truth->instances) {
    core::eval::SceneEvaluation scene;
    scene.name = instance.part;
    scene.part = instance.part;
    scene.truth = truth;
    scene.outcomes = {outcome(instance, 90)};
    // A detection without alternatives gets no ambiguity check.
    scene.outcomes.push_back(outcome(instance, 90));
    scene.outcomes.back().alternatives_scene_part.clear();
    report.scenes.push_back(std::move(scene));
  }
  report = core::eval::withRenderCheck(std::move(report), 1.0);
  const auto& cup = report.scenes[0].outcomes;
  const auto& pump = report.scenes[1].outcomes;
  ASSERT_TRUE(cup[0].ambiguity_render_difference && pump[0].ambiguity_render_difference);
  EXPECT_FALSE(cup[1].ambiguity_render_difference || pump[1].ambiguity_render_difference);
  EXPECT_LT(*pump[0].ambiguity_render_difference, 0.01);
  EXPECT_GT(*cup[0].ambiguity_render_difference, 0.04);
  EXPECT_EQ(report.overall.render_difference_ambiguous.count, 2u);
  EXPECT_DOUBLE_EQ(report.overall.render_difference_ambiguous.max,
                   *cup[0].ambiguity_render_difference);
}
