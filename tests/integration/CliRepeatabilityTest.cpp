// Repeatability at the command line: two `scanpick-cli recognize` runs on the same scene with the
// same model and preset write the same results file, timings aside.
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kCli = fs::path(SCANPICK_BINARY_DIR) / "bin" / "scanpick-cli";

/// `path` in double quotes, for the shell. (Built with append: GCC 12 warns wrongly about
/// `"literal" + std::string` under -O3.)
std::string quoted(const fs::path& path) {
  std::string out(1, '"');
  out.append(path.string());
  out.push_back('"');
  return out;
}

/// Runs scanpick-cli with `args` (already quoted), output discarded; returns the exit status.
int runCli(const std::vector<std::string>& args) {
  std::string command = quoted(kCli);
  for (const auto& a : args) {
    command.push_back(' ');
    command.append(a);
  }
  command.append(" > /dev/null 2>&1");
  return std::system(command.c_str());
}

nlohmann::json withoutTimings(const fs::path& path) {
  std::ifstream in(path);
  nlohmann::json doc = nlohmann::json::parse(in);
  doc.erase("timings_ms");
  return doc;
}

} // namespace

TEST(CliRepeatability, TwoRecognizeRunsWriteTheSameResults) {
  if (!fs::exists(kCli))
    GTEST_SKIP() << kCli << " is not built (build the scanpick-cli target first)";
  const scanpick::test::TempDir dir;
  const fs::path d = dir.path();
  const std::string preset =
      quoted(fs::path(SCANPICK_SOURCE_DIR) / "resources" / "presets" / "phoxi-bin.json");
  ASSERT_EQ(runCli({"demo", "--out", quoted(d)}), 0);
  ASSERT_EQ(runCli({"teach", "--scan", quoted(d / "support-teach.pcd"), "--crop-from-truth",
                    quoted(d / "support-teach.gt.json"), "--remove-floor", "--preset", preset,
                    "--name", "support", "--out", quoted(d / "support.spmodel")}),
            0);
  for (const char* out : {"a.json", "b.json"})
    ASSERT_EQ(runCli({"recognize", "--model", quoted(d / "support.spmodel"), "--scene",
                      quoted(d / "demo-bin.pcd"), "--preset", preset, "--out", quoted(d / out)}),
              0);
  const auto a = withoutTimings(d / "a.json"), b = withoutTimings(d / "b.json");
  EXPECT_FALSE(a.at("detections").empty()) << "the demo bin should give detections";
  EXPECT_EQ(a.dump(), b.dump());
}
