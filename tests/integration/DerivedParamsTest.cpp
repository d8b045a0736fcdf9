// A part nobody has tuned for, at the command line with no preset: teach derives its parameters
// from the part and the scan, says why, keeps the reasons in the model, and recognize finds the
// part in bins with them.
#include "core/model/ModelFile.h"
#include "core/params/ParameterTable.h"
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace scanpick;
using test::quoted;
using test::runCli;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(DerivedParams, ARandomPartIsTaughtAndFoundWithNoPreset) {
  if (!fs::exists(test::kCli))
    GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  const test::TempDir dir;
  const fs::path d = dir.path();
  ASSERT_EQ(runCli({"synth-suite", "--suite", "random-parts", "--parts", "1", "--seed", "7",
                    "--out", quoted(d / "suite")}),
            0);
  const fs::path part = d / "suite" / "random-parts" / "part-000";
  std::vector<std::string> recognize{"recognize", "--suite", quoted(part), "--out",
                                     quoted(d / "results")};
  std::vector<std::string> eval{"eval",
                                "--suite",
                                quoted(part),
                                "--results",
                                quoted(d / "results"),
                                "--json",
                                quoted(d / "eval.json"),
                                "--teach-truth"};
  // Each side's teach names the sides taught before it (--with-view) and prints their coverage.
  std::vector<std::string> earlier_views;
  std::vector<int> coverage_percent;
  for (const std::string view : {"teach", "teach-side1", "teach-side2", "teach-side3"}) {
    const fs::path model = d / (view + ".spmodel");
    std::vector<std::string> teach{"teach",
                                   "--scan",
                                   quoted(part / (view + ".pcd")),
                                   "--crop-from-truth",
                                   quoted(part / (view + ".gt.json")),
                                   "--remove-floor",
                                   "--out",
                                   quoted(model)};
    teach.insert(teach.end(), earlier_views.begin(), earlier_views.end());
    if (runCli(teach, d / (view + ".txt")) != 0)
      continue; // a side whose crop is too small to teach (its error says so)
    const std::string printed = test::readText(d / (view + ".txt"));
    EXPECT_THAT(printed, HasSubstr("parameters derived for this part"));
    std::smatch share;
    ASSERT_TRUE(std::regex_search(printed, share, std::regex("view coverage: ([0-9]+) %")))
        << printed;
    coverage_percent.push_back(std::stoi(share[1]));
    earlier_views.insert(earlier_views.end(), {"--with-view", quoted(model)});
    recognize.insert(recognize.end(), {"--model", quoted(model)});
    eval.push_back(quoted(part / (view + ".gt.json")));
  }
  ASSERT_GE(recognize.size(), 7u) << "fewer than two sides taught";
  // One view covers the directions within 60 degrees of its own (a quarter of the sphere); each
  // side taught after it adds to that.
  EXPECT_EQ(coverage_percent.front(), 25);
  EXPECT_TRUE(std::is_sorted(coverage_percent.begin(), coverage_percent.end()));
  EXPECT_GT(coverage_percent.back(), coverage_percent.front());
  // A view of another part is refused before any work, and no model file is written.
  EXPECT_EQ(test::exitCode(
                runCli({"teach", "--scan", quoted(part / "teach.pcd"), "--crop-from-truth",
                        quoted(part / "teach.gt.json"), "--name", "another-part", "--with-view",
                        quoted(d / "teach.spmodel"), "--out", quoted(d / "other.spmodel")},
                       d / "other.txt")),
            1);
  EXPECT_THAT(test::readText(d / "other.txt"), HasSubstr("--with-view"));
  EXPECT_FALSE(fs::exists(d / "other.spmodel"));

  const core::TaughtModel first = core::loadModel(d / "teach.spmodel");
  EXPECT_TRUE(first.params.refine.enabled);
  EXPECT_GT(first.params.matching.verify_tolerance_mm, 0.0);
  EXPECT_GT(first.params.matching.surface_sampling_mm, 0.0);
  ASSERT_TRUE(first.param_reasons.contains("keypoints.neighbourhood_radius_mm"));
  EXPECT_THAT(first.param_reasons.at("keypoints.neighbourhood_radius_mm"),
              HasSubstr("point spacing"));

  // --set overrides a derived value, which then has no derived reason.
  ASSERT_EQ(runCli({"teach", "--scan", quoted(part / "teach.pcd"), "--crop-from-truth",
                    quoted(part / "teach.gt.json"), "--remove-floor", "--set",
                    "matching.min_coverage=0.5", "--out", quoted(d / "set.spmodel")},
                   d / "set.txt"),
            0);
  EXPECT_THAT(test::readText(d / "set.txt"),
              HasSubstr("matching.min_coverage = 0.5: set by --set"));
  const core::TaughtModel set = core::loadModel(d / "set.spmodel");
  EXPECT_EQ(set.params.matching.min_coverage, 0.5);
  EXPECT_FALSE(set.param_reasons.contains("matching.min_coverage"));
  EXPECT_TRUE(set.param_reasons.contains("matching.verify_tolerance_mm"));

  fs::create_directories(d / "results");
  ASSERT_EQ(runCli(recognize, d / "recognize.txt"), 0) << test::readText(d / "recognize.txt");
  // The table views, joined in the part, cover part of the sphere of viewing directions.
  EXPECT_THAT(test::readText(d / "recognize.txt"),
              testing::ContainsRegex("view coverage: [1-9][0-9] % of the directions"));
  ASSERT_EQ(runCli(eval, d / "eval.txt"), 0) << test::readText(d / "eval.txt");
  std::ifstream in(d / "eval.json");
  const auto report = nlohmann::json::parse(in);
  const double precision = report["overall"]["precision"].get<double>();
  const double recall = report["overall"]["recall"].get<double>();
  std::cout << "random part (seed 7): precision " << precision << ", recall " << recall << "\n";
  EXPECT_GE(precision, 0.8);
  EXPECT_GE(recall, 0.7);
}
