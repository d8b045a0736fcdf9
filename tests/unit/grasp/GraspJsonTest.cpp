#include "core/grasp/GraspJson.h"

#include "core/common/Error.h"

#include <gtest/gtest.h>

using namespace scanpick::core;
using namespace scanpick::core::grasp;
using nlohmann::json;

TEST(GraspJson, GripperRoundTripsAndKeepsDefaultsForMissingKeys) {
  Gripper g;
  g.kind = GripperKind::Fingers;
  g.fingers.opening_mm = 42.0;
  g.body.shape = SolidShape::Box;
  EXPECT_EQ(gripperFromJson(toJson(g)), g);
  const Gripper partial = gripperFromJson(json::parse(R"({"suction": {"diameter_mm": 20}})"));
  EXPECT_EQ(partial.kind, GripperKind::Suction);
  EXPECT_EQ(partial.suction.diameter_mm, 20.0);
  EXPECT_EQ(partial.suction.stroke_mm, SuctionCup{}.stroke_mm);
}

TEST(GraspJson, TyposWrongTypesAndBadValuesAreErrorsNamingTheKey) {
  const auto message = [](const char* text) {
    try {
      (void)gripperFromJson(json::parse(text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(R"({"suction": {"diametre_mm": 20}})").find("diametre_mm"), std::string::npos);
  EXPECT_NE(message(R"({"suction": {"diameter_mm": "20"}})").find("diameter_mm"),
            std::string::npos);
  EXPECT_NE(message(R"({"kind": "magnet"})").find("magnet"), std::string::npos);
  EXPECT_NE(message(R"({"suction": {"diameter_mm": -1}})").find("diameter_mm"), std::string::npos);
  EXPECT_NE(message("[1]").find("object"), std::string::npos);
}

TEST(GraspJson, PlanParamsAndGraspSpecs) {
  const GraspPlanParams p = planParamsFromJson(
      json::parse(R"({"order": "least-occluded", "max_tilt_deg": 20, "up": [0, 0, -2]})"));
  EXPECT_EQ(p.order, PickOrder::LeastOccluded);
  EXPECT_EQ(p.max_tilt_deg, 20.0);
  EXPECT_TRUE(p.up.isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(planParamsFromJson(toJson(p)), p);
  EXPECT_THROW((void)planParamsFromJson(json::parse(R"({"order": "random"})")), Error);
  const auto specs =
      graspSpecsFromJson(json::parse(R"([{"grip": "top"}, {"grip": "side", "approach": [1, 0, 0],
                      "closing_axis": [0, 1, 0]}])"));
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].approach, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(specs[1].closing_axis, Eigen::Vector3d::UnitY());
  EXPECT_THROW((void)graspSpecsFromJson(json::parse(R"([{"approach": [0, 0, 1]}])")), Error);
  EXPECT_THROW((void)graspSpecsFromJson(json::parse(R"([{"grip": "a", "approach": [0, 1]}])")),
               Error);
}
