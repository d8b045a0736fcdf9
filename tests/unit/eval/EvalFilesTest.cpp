// The evaluator's file side: reading ground truth and results as docs/file-formats.md describes
// them, rejecting bad input with clear messages, suite mode, and the report formats.
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/eval/Evaluator.h"
#include "core/eval/JsonFields.h"
#include "core/eval/ReportFormat.h"
#include "tests/support/TempDir.h"
#include "tests/unit/eval/EvalTestSupport.h"

#include <gtest/gtest.h>

using namespace scanpick;
using core::eval::transformToJson;
using nlohmann::json;
using test::pose;

namespace {

/// A ground-truth document with the given instances of a 60 mm `part` (4-fold symmetric).
json truthJson(const std::string& kind, const std::vector<Eigen::Isometry3d>& poses,
               const std::string& part = "widget") {
  json instances = json::array();
  for (std::size_t i = 0; i < poses.size(); ++i)
    instances.push_back({{"id", i},
                         {"part", part},
                         {"T_scene_part", transformToJson(poses[i])},
                         {"visible_fraction", 0.8},
                         {"visible_points", 800}});
  return {{"format", "scanpick-ground-truth"},
          {"version", 1},
          {"units", "mm"},
          {"scene", {{"kind", kind}, {"seed", 7}, {"cloud", "scene.pcd"}}},
          {"sensor", {{"preset", "phoxi-m-1032"}}},
          {"parts",
           {{part,
             {{"diameter_mm", 60.0},
              {"grip_points", {{{"name", "top"}, {"position_mm", {0, 0, 20}}}}},
              {"symmetry",
               {{"continuous_axis", nullptr},
                {"discrete", {transformToJson(pose({0, 0, 0}, 90))}}}}}}}},
          {"instances", instances}};
}

/// A results document with one detection per given part pose (score 0.9, 0.8, ...).
json resultsJson(const std::vector<Eigen::Isometry3d>& part_poses, const json& teach_truth,
                 const std::string& model_name = "widget") {
  const Eigen::Isometry3d T_teach_part =
      core::eval::parseGroundTruth(teach_truth, "teach").instances.front().T_scene_part;
  json detections = json::array();
  for (std::size_t i = 0; i < part_poses.size(); ++i) {
    const Eigen::Isometry3d T_scene_model =
        part_poses[i] * T_teach_part.inverse() * test::testTeachModel();
    detections.push_back({{"id", i},
                          {"score", 0.9 - 0.1 * static_cast<double>(i)},
                          {"T_scene_model", transformToJson(T_scene_model)}});
  }
  return {
      {"format", "scanpick-results"},
      {"version", 1},
      {"units", "mm"},
      {"scene", "scene.pcd"},
      {"model", {{"name", model_name}, {"T_teach_model", transformToJson(test::testTeachModel())}}},
      {"detections", detections},
      {"timings_ms", {{"total", 120.0}}}};
}

void write(const std::filesystem::path& path, const json& doc) {
  core::writeFileAtomic(path, doc.dump(2));
}

/// Runs `f`, expects core::Error whose message contains `fragment`.
template <typename F> void expectError(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning '" << fragment << "'";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

struct Fixture {
  test::TempDir dir;
  json teach = truthJson("teach", {pose({0, 0, 700}, 12, Eigen::Vector3d(1, 0, 0))});
  std::vector<Eigen::Isometry3d> poses{pose({0, 0, 800}, 30), pose({80, 0, 800}, -70)};
  json truth = truthJson("bin", poses);
  Fixture() {
    write(dir / "teach.gt.json", teach);
    write(dir / "scene.gt.json", truth);
  }
  std::vector<core::eval::GroundTruth> teachTruths() const {
    return {core::eval::loadGroundTruth(dir / "teach.gt.json")};
  }
  core::eval::EvalReport evalResults(const json& results) const {
    write(dir / "result.json", results);
    return core::eval::evaluateFiles(dir / "scene.gt.json", dir / "result.json", teachTruths(), {});
  }
};

} // namespace

TEST(EvalFiles, SingleModeReadsFilesAndWritesReport) {
  Fixture f;
  // Detection 1 is instance 1 turned by 180° about its symmetry axis: still exact.
  const auto report =
      f.evalResults(resultsJson({f.poses[0], f.poses[1] * pose({0, 0, 0}, 180)}, f.teach));
  EXPECT_DOUBLE_EQ(*report.overall.precision, 1.0);
  EXPECT_DOUBLE_EQ(*report.overall.recall, 1.0);
  EXPECT_NEAR(report.overall.rotation_deg.max, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(report.overall.time_ms.max, 120.0);
  ASSERT_EQ(report.per_part.size(), 1u);
  EXPECT_EQ(report.per_part.front().label, "widget");
  EXPECT_EQ(report.scenes.front().name, "scene");

  core::eval::saveReportJson(f.dir / "eval.json", report);
  const json saved = json::parse(core::readFile(f.dir / "eval.json"));
  EXPECT_EQ(saved["format"], "scanpick-eval");
  EXPECT_DOUBLE_EQ(saved["overall"]["precision"].get<double>(), 1.0);
  EXPECT_EQ(saved["scenes"][0]["detections"].size(), 2u);
  const std::string table = core::eval::reportToTable(report, true);
  EXPECT_NE(table.find("precision"), std::string::npos);
  EXPECT_NE(table.find("translation at origin (mm)"), std::string::npos);
}

TEST(EvalFiles, BadInputThrowsClearErrors) {
  Fixture f;
  const json good = resultsJson({f.poses[0]}, f.teach);
  expectError([&] { core::eval::loadResults(f.dir / "absent.json"); }, "does not exist");
  core::writeFileAtomic(f.dir / "broken.json", "{\"format\": \"scanpick-results\", ");
  expectError([&] { core::eval::loadResults(f.dir / "broken.json"); }, "not valid JSON");
  expectError([&] { core::eval::loadResults(f.dir / "scene.gt.json"); },
              "expected \"scanpick-results\"");

  json future = good;
  future["version"] = 2;
  expectError([&] { f.evalResults(future); }, "update scanpick");
  json missing = good;
  missing["detections"][0].erase("T_scene_model");
  expectError([&] { f.evalResults(missing); }, "missing field 'T_scene_model'");
  json no_teach_model = good;
  no_teach_model["model"].erase("T_teach_model");
  expectError([&] { f.evalResults(no_teach_model); }, "T_teach_model");
  json nan = good; // JSON writers turn NaN into null
  nan["detections"][0]["T_scene_model"][1][2] = nullptr;
  expectError([&] { f.evalResults(nan); }, "NaN");
  json scaled = good;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      scaled["detections"][0]["T_scene_model"][r][c] =
          2.0 * scaled["detections"][0]["T_scene_model"][r][c].get<double>();
  expectError([&] { f.evalResults(scaled); }, "not a rotation");
  json mirrored = good;
  mirrored["model"]["T_teach_model"] = transformToJson(Eigen::Isometry3d::Identity());
  mirrored["model"]["T_teach_model"][2][2] = -1.0;
  expectError([&] { f.evalResults(mirrored); }, "reflection");
  json zero_axis = good;
  zero_axis["detections"][0]["free_turn_axis"] = {{"point_mm", {0, 0, 0}},
                                                  {"direction", {0, 0, 0}}};
  expectError([&] { f.evalResults(zero_axis); }, "free_turn_axis.direction is zero");
  json axis_without_point = good;
  axis_without_point["detections"][0]["free_turn_axis"] = {{"direction", {0, 0, 1}}};
  expectError([&] { f.evalResults(axis_without_point); }, "missing field 'point_mm'");
  json alternatives_not_array = good;
  alternatives_not_array["detections"][0]["alternative_poses"] = 3;
  expectError([&] { f.evalResults(alternatives_not_array); }, "alternative_poses must be an array");
  json alternative_scaled = good;
  alternative_scaled["detections"][0]["alternative_poses"] = {
      scaled["detections"][0]["T_scene_model"]};
  expectError([&] { f.evalResults(alternative_scaled); }, "alternative_poses[0]");
  json axes_unpaired = good;
  axes_unpaired["detections"][0]["alternative_free_turn_axes"] = {nullptr};
  expectError([&] { f.evalResults(axes_unpaired); }, "one entry (an axis or null) per alternative");
  json axis_zero = good;
  axis_zero["detections"][0]["alternative_poses"] = {good["detections"][0]["T_scene_model"]};
  axis_zero["detections"][0]["alternative_free_turn_axes"] = {
      {{"point_mm", {0, 0, 0}}, {"direction", {0, 0, 0}}}};
  expectError([&] { f.evalResults(axis_zero); }, "alternative_free_turn_axes[0].direction is zero");

  json truth_bad = f.truth;
  truth_bad["parts"]["widget"].erase("diameter_mm");
  write(f.dir / "scene.gt.json", truth_bad);
  expectError([&] { f.evalResults(good); }, "diameter_mm");
  truth_bad = f.truth;
  truth_bad["instances"][0]["part"] = "gear";
  write(f.dir / "scene.gt.json", truth_bad);
  expectError([&] { f.evalResults(good); }, "'gear' is not described");
}

// A teach scene's crop box and the grip points of its part where it lies, as `teach
// --crop-from-truth` takes them; a box that is not rigid or is inside out is refused.
TEST(EvalFiles, ATeachScenesCropBoxAndGripPointsAreRead) {
  json teach = truthJson("teach", {pose({0, 0, 700}, 12, Eigen::Vector3d(1, 0, 0))});
  teach["instances"][0]["grip_points"] = {{{"name", "top"}, {"position_mm", {1, 2, 720}}}};
  const Eigen::Isometry3d T_scene_box = pose({5, 0, 690}, 20);
  teach["crop_box"] = {{"T_scene_box", transformToJson(T_scene_box)},
                       {"min_mm", {-40, -40, -30}},
                       {"max_mm", {40, 40, 30}}};
  const core::eval::GroundTruth truth = core::eval::parseGroundTruth(teach, "teach");
  ASSERT_TRUE(truth.crop_box);
  EXPECT_TRUE(truth.crop_box->T_scene_box.isApprox(T_scene_box, 1e-12));
  EXPECT_EQ(truth.crop_box->max_mm, Eigen::Vector3d(40, 40, 30));
  ASSERT_EQ(truth.instances.at(0).grip_points_scene.size(), 1u);
  EXPECT_EQ(truth.instances[0].grip_points_scene[0].position_mm, Eigen::Vector3d(1, 2, 720));
  EXPECT_FALSE(core::eval::parseGroundTruth(truthJson("bin", {}), "bin").crop_box);

  json sheared = teach;
  sheared["crop_box"]["T_scene_box"][0][1] = 0.3;
  expectError([&] { core::eval::parseGroundTruth(sheared, "teach"); }, "crop_box.T_scene_box");
  json inside_out = teach;
  inside_out["crop_box"]["min_mm"][2] = 31;
  expectError([&] { core::eval::parseGroundTruth(inside_out, "teach"); }, "min_mm exceeds max_mm");
}

TEST(EvalFiles, ABinScenesWorldAndBinAreRead) {
  json bin = truthJson("bin", {pose({0, 0, 800})});
  const Eigen::Isometry3d T_scene_world = pose({0, 0, 850}, 180, Eigen::Vector3d::UnitX());
  bin["sensor"] = {{"preset", "phoxi-m-1032"}, {"T_scene_world", transformToJson(T_scene_world)}};
  bin["scene"]["bin"] = {
      {"inner_x_mm", 360}, {"inner_y_mm", 280}, {"wall_height_mm", 150}, {"wall_thickness_mm", 10}};
  const core::eval::GroundTruth truth = core::eval::parseGroundTruth(bin, "bin");
  ASSERT_TRUE(truth.T_scene_world);
  EXPECT_TRUE(truth.T_scene_world->isApprox(T_scene_world, 1e-12));
  ASSERT_TRUE(truth.bin);
  EXPECT_EQ(truth.bin->inner_y_mm, 280.0);
  EXPECT_EQ(truth.bin->wall_thickness_mm, 10.0);
  // Written before the bin was: neither is there.
  const core::eval::GroundTruth older = core::eval::parseGroundTruth(truthJson("bin", {}), "old");
  EXPECT_FALSE(older.T_scene_world);
  EXPECT_FALSE(older.bin);

  json flat = bin;
  flat["scene"]["bin"]["wall_height_mm"] = 0;
  expectError([&] { core::eval::parseGroundTruth(flat, "bin"); }, "scene.bin.wall_height_mm");
  json sheared = bin;
  sheared["sensor"]["T_scene_world"][0][1] = 0.3;
  expectError([&] { core::eval::parseGroundTruth(sheared, "bin"); }, "sensor.T_scene_world");
}

TEST(EvalFiles, SuiteModeAggregatesScenes) {
  test::TempDir suite, results;
  const json teach = truthJson("teach", {pose({0, 0, 700})});
  write(suite / "teach.gt.json", teach);
  // scene-000: two instances, both found. scene-001: one instance, found 9 mm off (> 6 mm).
  const std::vector<Eigen::Isometry3d> scene0{pose({0, 0, 800}, 30), pose({80, 0, 800}, -70)};
  const std::vector<Eigen::Isometry3d> scene1{pose({0, 50, 820}, 5)};
  write(suite / "scene-000.gt.json", truthJson("bin", scene0));
  write(suite / "scene-001.gt.json", truthJson("bin", scene1));
  write(results / "scene-000.json", resultsJson(scene0, teach));
  write(results / "scene-001.json", resultsJson({pose({9, 0, 0}) * scene1[0]}, teach));

  const auto teach_truths = core::eval::findTeachTruths(suite.path());
  ASSERT_EQ(teach_truths.size(), 1u);
  const auto report = core::eval::evaluateSuite(suite.path(), results.path(), teach_truths, {});
  ASSERT_EQ(report.scenes.size(), 2u);
  EXPECT_EQ(report.overall.detections, 3);
  EXPECT_EQ(report.overall.true_positives, 2);
  EXPECT_DOUBLE_EQ(*report.overall.recall, 2.0 / 3.0);
  EXPECT_EQ(report.overall.time_ms.count, 2u);

  std::filesystem::remove(results / "scene-001.json");
  expectError([&] { core::eval::evaluateSuite(suite.path(), results.path(), teach_truths, {}); },
              "no results for scene-001");
}

TEST(EvalFiles, TeachTruthsAreFoundAndChosenPerResults) {
  // synth-suite's layout: out/phoxi-bin/scene-XXX.gt.json and
  // out/teach/phoxi-m-1032/<part>.gt.json.
  test::TempDir out;
  std::filesystem::create_directories(out / "phoxi-bin");
  std::filesystem::create_directories(out.path() / "teach" / "phoxi-m-1032");
  const json widget_teach = truthJson("teach", {pose({0, 0, 700})}, "widget");
  const json gear_teach = truthJson("teach", {pose({5, 0, 700}, 90)}, "gear");
  write(out.path() / "teach" / "phoxi-m-1032" / "widget.gt.json", widget_teach);
  write(out.path() / "teach" / "phoxi-m-1032" / "gear.gt.json", gear_teach);
  const json gears = truthJson("bin", {pose({0, 0, 800})}, "gear");
  write(out.path() / "phoxi-bin" / "scene-000.gt.json", gears);

  // No --teach-truth: found beside the suite via the scene's sensor preset.
  const auto teach = core::eval::loadTeachTruths({}, out.path() / "phoxi-bin/");
  ASSERT_EQ(teach.size(), 2u);
  const auto truth = core::eval::parseGroundTruth(gears, "gears");
  // By model name, and for an operator's own model name by the scene's only part.
  for (const std::string model : {"gear", "my-bracket"}) {
    const auto results =
        core::eval::parseResults(resultsJson({pose({0, 0, 800})}, gear_teach, model), "r");
    EXPECT_EQ(core::eval::selectTeachTruth(teach, results, truth).instances.front().part, "gear");
  }
  const auto widget_results =
      core::eval::parseResults(resultsJson({pose({0, 0, 800})}, widget_teach, "widget"), "r");
  const auto report = core::eval::makeReport(
      {core::eval::evaluateScene(truth, widget_results,
                                 core::eval::selectTeachTruth(teach, widget_results, truth), {},
                                 "scene-000")},
      {});
  EXPECT_EQ(report.overall.instances, 0); // no widget in a bin of gears
  EXPECT_EQ(report.overall.true_positives, 0);

  expectError([&] { core::eval::loadTeachTruths({}, out / "phoxi-bin" / "nowhere"); },
              "no teach ground truth");
  expectError([&] { core::eval::loadTeachTruths({out / "phoxi-bin"}); }, "holds no teach");
}

TEST(EvalFiles, ViewsOfOnePartAreEvaluatedEachAgainstItsOwnTeachScan) {
  Fixture f;
  // A second view: the part taught lying on another side, from its own scan.
  json side = truthJson("teach", {pose({10, 5, 690}, 100, Eigen::Vector3d(0, 1, 0))});
  side["scene"]["cloud"] = "side.pcd";
  f.teach["scene"]["cloud"] = "teach.pcd";
  write(f.dir / "teach.gt.json", f.teach);
  write(f.dir / "side.gt.json", side);
  const std::vector<core::eval::GroundTruth> teach = {
      core::eval::loadGroundTruth(f.dir / "teach.gt.json"),
      core::eval::loadGroundTruth(f.dir / "side.gt.json")};
  // Instance 0 found through view 0, instance 1 through view 1 (whose frame differs).
  json results = resultsJson({f.poses[0]}, f.teach);
  const json side_detection = resultsJson({f.poses[1]}, side)["detections"][0];
  results["detections"].push_back(side_detection);
  results["detections"][1]["id"] = 1;
  results["detections"][1]["model"] = 1;
  const json model = {{"name", "widget"},
                      {"T_teach_model", transformToJson(test::testTeachModel())}};
  results["models"] = json::array({model, model});
  results["models"][0]["teach_scan"] = "teach.pcd";
  results["models"][1]["teach_scan"] = "side.pcd";
  write(f.dir / "result.json", results);
  const auto report =
      core::eval::evaluateFiles(f.dir / "scene.gt.json", f.dir / "result.json", teach, {});
  EXPECT_DOUBLE_EQ(*report.overall.precision, 1.0);
  EXPECT_DOUBLE_EQ(*report.overall.recall, 1.0);
  EXPECT_NEAR(report.overall.translation_mm.max, 0.0, 1e-6);

  // Evaluated against the wrong view's teach scan, detection 1 is off.
  results["models"][1]["teach_scan"] = "teach.pcd";
  write(f.dir / "result.json", results);
  const auto wrong =
      core::eval::evaluateFiles(f.dir / "scene.gt.json", f.dir / "result.json", teach, {});
  EXPECT_DOUBLE_EQ(*wrong.overall.recall, 0.5);

  // A view whose teach scan has no ground truth, or a detection naming no model: clear errors.
  results["models"][1]["teach_scan"] = "other.pcd";
  write(f.dir / "result.json", results);
  expectError(
      [&] { core::eval::evaluateFiles(f.dir / "scene.gt.json", f.dir / "result.json", teach, {}); },
      "other.pcd");
  results["models"][1]["teach_scan"] = "side.pcd";
  results["detections"][1]["model"] = 2;
  write(f.dir / "result.json", results);
  expectError(
      [&] { core::eval::evaluateFiles(f.dir / "scene.gt.json", f.dir / "result.json", teach, {}); },
      "names no entry");
}
