// Repeatability at the command line: two `scanpick-cli recognize` runs on the same scene with the
// same model and preset write the same results file, timings aside.
#include "core/common/AtomicFile.h"
#include "core/model/ModelFile.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/MeshIo.h"
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using scanpick::test::kCli;
using scanpick::test::quoted;
using scanpick::test::readText;
using scanpick::test::runCli;

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
  // Two views (the table side and the side most supports rest on in the bin), searched together.
  for (const char* view : {"support-teach", "support-teach-side1"})
    ASSERT_EQ(
        runCli({"teach", "--scan", quoted(d / (std::string(view) + ".pcd")), "--crop-from-truth",
                quoted(d / (std::string(view) + ".gt.json")), "--remove-floor", "--preset", preset,
                "--name", "support", "--out", quoted(d / (std::string(view) + ".spmodel"))}),
        0);
  // A view's own matching parameters are stored in its model; one out of range writes nothing.
  const std::vector<std::string> teach_own{"teach",
                                           "--scan",
                                           quoted(d / "support-teach.pcd"),
                                           "--crop-from-truth",
                                           quoted(d / "support-teach.gt.json"),
                                           "--preset",
                                           preset,
                                           "--out",
                                           quoted(d / "own.spmodel"),
                                           "--view-set"};
  std::vector<std::string> outside = teach_own;
  outside.push_back("matching.min_coverage=1.5");
  EXPECT_NE(runCli(outside), 0);
  EXPECT_FALSE(fs::exists(d / "own.spmodel"));
  std::vector<std::string> own = teach_own;
  own.insert(own.end(), {"matching.min_coverage=0.6", "--view-set", "matching.refine_all=false"});
  EXPECT_NE(runCli(own), 0) << "an unknown key is an error";
  own.resize(own.size() - 2);
  ASSERT_EQ(runCli(own), 0);
  const scanpick::core::ViewParams stored{{"matching.min_coverage", 0.6}};
  EXPECT_EQ(scanpick::core::loadModel(d / "own.spmodel").view_params, stored);

  // The part's pose in the teach scan places the view in the part: from a teach scene's ground
  // truth, or given (here the part turned a quarter about z, 700 mm in front of the camera).
  EXPECT_TRUE(scanpick::core::loadModel(d / "support-teach.spmodel").T_part_model);
  std::vector<std::string> posed = teach_own;
  posed.back() = "--part-pose";
  posed.push_back("10,20,700,0.70710678,0,0,0.70710678");
  posed[posed.size() - 3] = quoted(d / "posed.spmodel");
  ASSERT_EQ(runCli(posed), 0);
  const scanpick::core::TaughtModel placed = scanpick::core::loadModel(d / "posed.spmodel");
  ASSERT_TRUE(placed.T_part_model);
  Eigen::Isometry3d T_scan_part = Eigen::Isometry3d::Identity();
  T_scan_part.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_scan_part.translation() = Eigen::Vector3d(10, 20, 700);
  EXPECT_TRUE((T_scan_part * *placed.T_part_model).isApprox(placed.T_teach_model, 1e-6));
  posed.back() = "10,20,700,1,0,0,1";
  posed[posed.size() - 3] = quoted(d / "unit.spmodel");
  EXPECT_NE(runCli(posed, d / "unit.txt"), 0) << "a quaternion that is not a unit is an error";
  EXPECT_NE(readText(d / "unit.txt").find("unit quaternion"), std::string::npos);
  EXPECT_FALSE(fs::exists(d / "unit.spmodel"));
  // A teach scene's ground truth whose part pose is not rigid is refused, and nothing written.
  auto sheared = nlohmann::json::parse(readText(d / "support-teach.gt.json"));
  sheared["instances"][0]["T_scene_part"][0][1] = 0.3;
  scanpick::core::writeFileAtomic(d / "sheared.gt.json", sheared.dump());
  std::vector<std::string> from_sheared = teach_own;
  from_sheared.resize(from_sheared.size() - 1);
  from_sheared[4] = quoted(d / "sheared.gt.json");
  from_sheared[from_sheared.size() - 1] = quoted(d / "sheared.spmodel");
  EXPECT_NE(runCli(from_sheared, d / "sheared.txt"), 0);
  EXPECT_NE(readText(d / "sheared.txt").find("T_scene_part"), std::string::npos)
      << readText(d / "sheared.txt");
  EXPECT_FALSE(fs::exists(d / "sheared.spmodel"));

  for (const char* out : {"a.json", "b.json"})
    ASSERT_EQ(runCli({"recognize", "--model", quoted(d / "support-teach.spmodel"), "--model",
                      quoted(d / "support-teach-side1.spmodel"), "--scene",
                      quoted(d / "demo-bin.pcd"), "--preset", preset, "--out", quoted(d / out)},
                     d / (std::string(out) + ".txt")),
              0);
  // Both views were taught knowing their place in the part: recognize joins them.
  EXPECT_NE(readText(d / "a.json.txt").find("2 of them joined"), std::string::npos)
      << readText(d / "a.json.txt");
  const auto a = withoutTimings(d / "a.json"), b = withoutTimings(d / "b.json");
  EXPECT_FALSE(a.at("detections").empty()) << "the demo bin should give detections";
  EXPECT_EQ(a.dump(), b.dump());

  // The benchmark, after a warm-up scene (the views prepared as in a running cell), finds as many.
  const std::vector<std::string> bench{"bench",
                                       "--model",
                                       quoted(d / "support-teach.spmodel"),
                                       "--model",
                                       quoted(d / "support-teach-side1.spmodel"),
                                       "--scene",
                                       quoted(d / "demo-bin.pcd"),
                                       "--preset",
                                       preset,
                                       "--runs",
                                       "1"};
  // Each mode's report names it and finds as many detections as recognize.
  const auto checkBench = [&](const std::vector<std::string>& args, const fs::path& out,
                              const std::string& mode) {
    ASSERT_EQ(runCli(args, out), 0) << readText(out);
    const std::string report = readText(out);
    EXPECT_NE(report.find(mode), std::string::npos) << report;
    EXPECT_NE(report.find(std::to_string(a.at("detections").size()) + " detection(s)"),
              std::string::npos)
        << report;
  };
  std::vector<std::string> warm = bench;
  warm.insert(warm.end(), {"--warm-up", quoted(d / "support-teach.pcd")});
  checkBench(warm, d / "bench.txt", "1 warm runs");
  // Prepared views: the preparation on its own line.
  std::vector<std::string> prepared = bench;
  prepared.push_back("--prepare");
  checkBench(prepared, d / "bench-prepared.txt", "| view preparation");
  warm.back() = quoted(d / "no-such-scan.pcd");
  EXPECT_NE(runCli(warm, d / "bench-missing.txt"), 0) << "a missing warm-up scan is an error";
  EXPECT_NE(readText(d / "bench-missing.txt").find("no-such-scan.pcd"), std::string::npos);
}

// The README's main job headless: `scanpick-cli demo` simulates the scenes, teaches the support,
// recognizes it in the bin and writes the results and the overlay picture.
TEST(CliDemo, TeachesRecognizesAndWritesResultsAndPicture) {
  if (!fs::exists(kCli))
    GTEST_SKIP() << kCli << " is not built (build the scanpick-cli target first)";
  const scanpick::test::TempDir dir;
  const fs::path d = dir.path() / "demo-output";
  ASSERT_EQ(runCli({"demo", "--out", quoted(d)}), 0);
  for (const char* file : {"demo-bin.pcd", "support-teach.pcd", "support.spmodel"})
    EXPECT_TRUE(fs::exists(d / file)) << file;
  ASSERT_TRUE(fs::exists(d / "demo-results.json"));
  std::ifstream in(d / "demo-results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  ASSERT_TRUE(results.at("detections").is_array());
  EXPECT_GE(results.at("detections").size(), 1u) << "the demo bin should give detections";
  for (const auto& detection : results.at("detections"))
    EXPECT_GT(detection.at("score").get<double>(), 0.0);
  // The picture is a real PNG, not an empty file.
  const fs::path picture = d / "demo-overlay.png";
  ASSERT_TRUE(fs::exists(picture));
  EXPECT_GT(fs::file_size(picture), 1000u);
  std::ifstream png(picture, std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  // A bad preset fails with a non-zero exit code instead of writing anything misleading.
  EXPECT_NE(runCli({"demo", "--out", quoted(dir.path() / "bad"), "--preset", "no-such-preset"}), 0);

  // Scored with the render check: each found support lies where the scan cannot tell it from
  // the truth.
  const std::vector<std::string> eval{"eval",
                                      "--truth",
                                      quoted(d / "demo-bin.gt.json"),
                                      "--results",
                                      quoted(d / "demo-results.json"),
                                      "--teach-truth",
                                      quoted(d / "support-teach.gt.json"),
                                      "--teach-truth",
                                      quoted(d / "support-teach-side1.gt.json"),
                                      "--render-check",
                                      "1",
                                      "--json",
                                      quoted(d / "eval.json")};
  ASSERT_EQ(runCli(eval), 0);
  std::ifstream report_in(d / "eval.json");
  const nlohmann::json report = nlohmann::json::parse(report_in);
  const auto& scored = report.at("scenes").at(0).at("detections");
  ASSERT_EQ(scored.size(), results.at("detections").size());
  for (const auto& detection : scored) {
    EXPECT_TRUE(detection.at("true_positive").get<bool>());
    EXPECT_LT(detection.at("render_difference").get<double>(), 0.1);
  }
  EXPECT_EQ(report.at("overall").at("render_difference_true_positives").at("count"), scored.size());
}

TEST(CliSynth, OpenMeshIsRefusedUnlessItsHolesAreClosed) {
  if (!fs::exists(kCli))
    GTEST_SKIP() << kCli << " is not built (build the scanpick-cli target first)";
  const scanpick::test::TempDir dir;
  // A 40 mm box without its top: a scanned part's open base.
  scanpick::core::TriangleMesh open = scanpick::core::boxMesh({0, 0, 0}, {40, 40, 40});
  std::erase_if(open.triangles, [&](const Eigen::Vector3i& t) {
    return open.vertices_mm[t[0]].z() == 40 && open.vertices_mm[t[1]].z() == 40 &&
           open.vertices_mm[t[2]].z() == 40;
  });
  const fs::path mesh = dir.path() / "open.ply", closed = dir.path() / "closed.ply";
  scanpick::core::saveMeshPly(mesh, open);
  const fs::path log = dir.path() / "log.txt";
  EXPECT_NE(runCli({"synth", "--mesh", quoted(mesh), "--out", quoted(dir.path() / "s")}, log), 0);
  EXPECT_NE(readText(log).find("--close-holes"), std::string::npos) << readText(log);
  EXPECT_FALSE(fs::exists(dir.path() / "s.pcd"));
  ASSERT_EQ(runCli({"synth", "--mesh", quoted(mesh), "--close-holes", "--export-mesh", "--out",
                    quoted(closed)}),
            0);
  EXPECT_EQ(scanpick::core::openEdgeCount(scanpick::core::loadMesh(closed)), 0u);
  // --close-holes belongs to a mesh file.
  EXPECT_NE(
      runCli({"synth", "--part", "support", "--close-holes", "--out", quoted(dir.path() / "t")},
             log),
      0);
  EXPECT_NE(readText(log).find("--mesh"), std::string::npos) << readText(log);
}

TEST(CliSynth, ATeachSceneHoldsOnePartUnlessTheCountSaysOtherwise) {
  if (!fs::exists(kCli))
    GTEST_SKIP() << kCli << " is not built (build the scanpick-cli target first)";
  const scanpick::test::TempDir dir;
  const fs::path log = dir.path() / "log.txt";
  ASSERT_EQ(
      runCli({"synth", "--part", "cup", "--layout", "teach", "--out", quoted(dir.path() / "teach")},
             log),
      0)
      << readText(log);
  std::ifstream truth(dir.path() / "teach.gt.json");
  EXPECT_EQ(nlohmann::json::parse(truth).at("instances").size(), 1u);
  // A count other than one is still refused, with what to give instead.
  EXPECT_NE(runCli({"synth", "--part", "cup", "--layout", "teach", "--count", "2", "--out",
                    quoted(dir.path() / "two")},
                   log),
            0);
  EXPECT_NE(readText(log).find("--count 1"), std::string::npos) << readText(log);
}
