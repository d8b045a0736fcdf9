// docs/parameters.md is the output of `scanpick-cli params --markdown`: it must match the table.
#include "core/params/ParameterDocs.h"

#include "core/common/AtomicFile.h"

#include <filesystem>
#include <gtest/gtest.h>

using namespace scanpick;

TEST(ParameterDocs, DocsMatchTheParameterTable) {
  const auto path = std::filesystem::path(SCANPICK_SOURCE_DIR) / "docs" / "parameters.md";
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  const std::string generated = core::parametersMarkdown();
  EXPECT_TRUE(core::readFile(path) == generated)
      << "docs/parameters.md is out of date with core/params/ParameterTable.cpp: regenerate it "
         "with `scanpick-cli params --markdown > docs/parameters.md` (from the project folder)";
}

TEST(ParameterDocs, EveryKeyIsDocumentedWithItsDefault) {
  const std::string markdown = core::parametersMarkdown();
  const core::RecognitionParams defaults;
  for (const auto& info : core::parameterTable()) {
    const std::string row = "| `" + info.key + "` |";
    const auto at = markdown.find(row);
    ASSERT_NE(at, std::string::npos) << info.key;
    const std::string line = markdown.substr(at, markdown.find('\n', at) - at);
    EXPECT_NE(line.find("| " + core::formatParamValue(info, info.get(defaults)) + " |"),
              std::string::npos)
        << line;
  }
  EXPECT_EQ(core::formatParamValue(*core::findParameter("features.estimator"), 2), "prosac");
  EXPECT_EQ(core::formatParamValue(*core::findParameter("floor.enabled"), 0), "off");
  EXPECT_EQ(core::formatParamRange(*core::findParameter("features.ransac_size")), "2 – 100000");
}

TEST(ParameterDocs, PresetValuesAppearInTheirOwnColumn) {
  core::RecognitionParams preset;
  preset.matching.position_tolerance_mm = 7.25;
  const std::string markdown = core::parametersMarkdown(preset, "test");
  EXPECT_NE(markdown.find("| 20 | 7.25 |"), std::string::npos); // default 20, preset 7.25
  EXPECT_NE(markdown.find("preset **test**"), std::string::npos);
}
