#include "core/common/JsonText.h"

#include "core/common/Error.h"

#include <gtest/gtest.h>

using namespace scanpick;

TEST(JsonText, NestingDeeperThanTheLimitIsRefusedBeforeParsing) {
  // 60,000 levels exhausted the stack when the message was built; the limit refuses them first.
  const std::string deep = std::string(60000, '[') + std::string(60000, ']');
  try {
    core::parseJsonText(deep, "results.json", ": regenerate it");
    FAIL() << "expected an Error";
  } catch (const core::Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "results.json is not valid JSON (nested deeper than 64 levels): regenerate it");
  }
  const std::string at_limit =
      std::string(core::kMaxJsonDepth, '[') + std::string(core::kMaxJsonDepth, ']');
  EXPECT_TRUE(core::parseJsonText(at_limit, "ok.json", "").is_array());
  // Brackets inside strings do not count.
  EXPECT_EQ(core::parseJsonText("{\"a\":\"" + std::string(1000, '[') + "\"}", "s.json", "")["a"]
                .get<std::string>()
                .size(),
            1000u);
  EXPECT_THROW(core::parseJsonText("{\"a\":", "t.json", ""), core::Error);
}

TEST(JsonText, FileNamesThatAreNotUtf8AreWrittenNotThrown) {
  const nlohmann::json doc = {{"scene", std::string("scan-\xff\xfe.pcd")}};
  const std::string text = core::dumpJsonText(doc);
  EXPECT_NE(text.find("scan-\xef\xbf\xbd\xef\xbf\xbd.pcd"), std::string::npos) << text;
  EXPECT_EQ(core::jsonExcerpt(nlohmann::json(std::string(200, 'a'))).size(), 60u);
}
