// scanpick-cli clear-bin end to end: a small simulated bin of supports is scanned, recognized,
// planned and picked until it is empty, each pick judged against the truth; bad input is refused.
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"

#include <filesystem>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using namespace scanpick;
using test::exitCode;
using test::quoted;
using test::runCli;
using ::testing::HasSubstr;

TEST(CliClearBin, ClearsASmallBinOfSupports) {
  if (!fs::exists(test::kCli))
    GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  const test::TempDir dir;
  const fs::path out = dir / "run";
  ASSERT_EQ(runCli({"clear-bin", "--part", "support", "--count", "5", "--seed", "1", "--out",
                    quoted(out)},
                   dir / "log.txt"),
            0)
      << test::readText(dir / "log.txt");
  const auto doc = nlohmann::json::parse(test::readText(out / "clear-bin.json"));
  // Every support picked, no wrong pick (judged within 3 mm and 5° of a true grasp), no collision
  // (gripper and approach against the true meshes of the other instances and the bin).
  EXPECT_EQ(doc["picks"], 5);
  EXPECT_EQ(doc["wrong_picks"], 0);
  EXPECT_EQ(doc["collisions"], 0);
  EXPECT_EQ(doc["left"], 0);
  EXPECT_EQ(doc["stop"], "bin empty");
  EXPECT_DOUBLE_EQ(doc["cleared"].get<double>(), 1.0);
  ASSERT_EQ(doc["cycles"].size(), 5u);
  for (const auto& c : doc["cycles"])
    EXPECT_TRUE(fs::exists(out / c["picture"].get<std::string>())) << c["picture"];
  EXPECT_THAT(test::readText(dir / "log.txt"), HasSubstr("5 picked, 0 wrong, 0 colliding"));
}

TEST(CliClearBin, RefusesBadInput) {
  if (!fs::exists(test::kCli))
    GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  const test::TempDir dir;
  EXPECT_EQ(exitCode(runCli({"clear-bin", "--part", "no-such-part", "--out", quoted(dir / "a")},
                            dir / "part.txt")),
            1);
  EXPECT_THAT(test::readText(dir / "part.txt"), HasSubstr("no-such-part"));
  EXPECT_EQ(exitCode(runCli(
                {"clear-bin", "--part", "support", "--count", "0", "--out", quoted(dir / "b")},
                dir / "count.txt")),
            1);
  EXPECT_THAT(test::readText(dir / "count.txt"), HasSubstr("--count must be between 1 and 200"));
  EXPECT_EQ(exitCode(runCli({"clear-bin", "--part", "support", "--out", "/proc/no-such/out"},
                            dir / "out.txt")),
            1);
  EXPECT_THAT(test::readText(dir / "out.txt"), HasSubstr("cannot create the output folder"));
  EXPECT_EQ(exitCode(runCli({"clear-bin", "--count", "3"})), 2); // --part and --out missing
}
