#include "core/params/ParameterTable.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/params/ParamsJson.h"
#include "core/params/ViewParams.h"
#include "tests/support/TempDir.h"

#include <cmath>
#include <gtest/gtest.h>
#include <set>

using namespace scanpick;

TEST(ParameterTable, KeysAreUniqueAndDefaultsLieInRange) {
  const core::RecognitionParams defaults;
  std::set<std::string> keys;
  for (const auto& info : core::parameterTable()) {
    EXPECT_TRUE(keys.insert(info.key).second) << "duplicate key " << info.key;
    const double v = info.get(defaults);
    EXPECT_GE(v, info.min_value) << info.key;
    EXPECT_LE(v, info.max_value) << info.key;
    EXPECT_FALSE(info.description.empty()) << info.key;
    if (info.type == core::ParamType::Enum) {
      EXPECT_EQ(info.choices.size(), static_cast<std::size_t>(info.max_value) + 1) << info.key;
    }
  }
  EXPECT_GE(keys.size(), 30u);
}

TEST(ParameterTable, AFewParametersAreTunedTheRestAdvanced) {
  std::set<std::string> tuned;
  for (const auto& key : core::kTunedParameters) {
    const core::ParamInfo* info = core::findParameter(key);
    ASSERT_NE(info, nullptr) << key;
    EXPECT_TRUE(info->tuned) << key;
    tuned.insert(info->key);
  }
  std::size_t flagged = 0;
  for (const auto& info : core::parameterTable())
    flagged += info.tuned ? 1 : 0;
  EXPECT_EQ(flagged, tuned.size()) << "only the listed keys are tuned";
  EXPECT_LE(flagged, core::parameterTable().size() / 4) << "a few, not most";
}

TEST(ParameterTable, SetClampsAndChangedStageIsReported) {
  core::RecognitionParams p;
  const auto* info = core::findParameter("matching.position_tolerance_mm");
  ASSERT_NE(info, nullptr);
  info->set(p, 7.5);
  EXPECT_DOUBLE_EQ(p.matching.position_tolerance_mm, 7.5);
  info->set(p, 1e9);
  EXPECT_DOUBLE_EQ(p.matching.position_tolerance_mm, info->max_value);
  EXPECT_EQ(core::firstChangedStage(p, core::RecognitionParams{}), core::Stage::Matching);
  p.keypoints.position_range_mm = 1.0;
  EXPECT_EQ(core::firstChangedStage(p, core::RecognitionParams{}), core::Stage::Keypoints);
  EXPECT_FALSE(core::firstChangedStage(core::RecognitionParams{}, core::RecognitionParams{}));
}

TEST(ParamsJson, PresetRoundTripAndErrors) {
  test::TempDir dir;
  core::Preset preset{"cup", "thesis table 5.4", {}};
  preset.params.features.estimator = core::FeatureParams::Estimator::Prosac;
  preset.params.features.ransac_size = 17;
  core::savePreset(dir / "cup.json", preset);
  const auto loaded = core::loadPreset(dir / "cup.json");
  EXPECT_EQ(loaded.params, preset.params);
  EXPECT_EQ(loaded.name, "cup");

  EXPECT_THROW(core::paramsFromJson(nlohmann::json{{"no.such.key", 1}}), core::Error);
  EXPECT_THROW(core::paramsFromJson(nlohmann::json{{"features.ransac_size", -5}}), core::Error);
  EXPECT_THROW(core::paramsFromJson(nlohmann::json{{"features.estimator", "magic"}}), core::Error);
  // A whole-number parameter given a fraction is refused, not rounded in silence.
  try {
    core::paramsFromJson(nlohmann::json{{"matching.surface_poses", 60.5}});
    FAIL() << "a fractional count was accepted";
  } catch (const core::Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("'matching.surface_poses' = 60.500000 is outside its range"),
        std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("(a whole number)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(
      core::paramsFromJson(nlohmann::json{{"matching.surface_poses", 60}}).matching.surface_poses,
      60);

  core::writeFileAtomic(dir / "future.json",
                        R"({"format":"scanpick-preset","version":99,"params":{}})");
  try {
    core::loadPreset(dir / "future.json");
    FAIL();
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("update scanpick"), std::string::npos);
  }
}

TEST(ViewParams, OnlyMatchingValuesInRangeAndFoldedIntoTheParameters) {
  core::RecognitionParams params;
  core::ViewParams view{{"matching.min_coverage", 0.5},
                        {"matching.surface_reference_stride", 2},
                        {"refine.enabled", 1}};
  EXPECT_THROW(core::withViewParams(params, view), core::Error); // refinement: not per view
  view.erase("refine.enabled");
  const core::RecognitionParams own = core::withViewParams(params, view);
  EXPECT_EQ(own.matching.min_coverage, 0.5);
  EXPECT_EQ(own.matching.surface_reference_stride, 2);
  EXPECT_EQ(own.keypoints, params.keypoints);
  core::foldViewParams(params, view);
  EXPECT_EQ(params, own);
  EXPECT_TRUE(view.empty());
  EXPECT_THROW(core::checkViewParam("matching.surface_reference_stride", 0.0), core::Error);
  EXPECT_THROW(core::checkViewParam("matching.min_coverage", std::nan("")), core::Error);
  EXPECT_NO_THROW(core::checkViewParam("matching.min_coverage", 1.0));
}
