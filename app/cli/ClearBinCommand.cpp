// scanpick-cli clear-bin: a virtual bin-clearing run (docs/bin-clearing.md). A simulated bin is
// scanned, recognized, planned and picked until it is empty; each pick is judged against the truth.
#include "app/cli/ClearBin.h"
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/ModelViews.h"
#include "app/cli/RecipeOptions.h"
#include "core/common/AtomicFile.h"
#include "core/common/JsonText.h"
#include "core/grasp/GraspJson.h"
#include "core/sim/PartCatalog.h"

#include <algorithm>
#include <cstdio>
#include <set>

namespace scanpick::cli {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct Options {
  RecipeOptions recipe;
  std::string part, out, recipe_file;
  int count = 20, max_cycles = 0;
  std::uint64_t seed = 0, teach_seed = 1;
  std::vector<std::string> models;
};

/// The grasp planning keys of a recipe file (docs/grasping.md) over the setup's defaults; the
/// recipe's models when no --model is given; its preset and settings under --preset / --set.
void applyRecipe(const std::string& path, ClearBinSetup& s, Options& o) {
  const json doc = core::parseJsonText(core::readFile(path), path, ": see docs/grasping.md");
  static const std::set<std::string> kKeys = {"format", "version",  "name",   "models",
                                              "preset", "set",      "sensor", "gripper",
                                              "grasps", "planning", "bin",    "robot_from_camera"};
  if (!doc.is_object() || doc.value("format", std::string()) != "scanpick-recipe")
    throw core::Error(path + ": not a scanpick recipe (\"format\": \"scanpick-recipe\" missing)");
  for (const auto& item : doc.items())
    if (!kKeys.contains(item.key()))
      throw core::Error(path + ": unknown key '" + item.key() + "' (see docs/grasping.md)");
  if (doc.contains("gripper"))
    s.gripper = core::grasp::gripperFromJson(doc["gripper"]);
  if (doc.contains("grasps"))
    s.grasps = core::grasp::graspSpecsFromJson(doc["grasps"]);
  if (doc.contains("planning"))
    s.planning = core::grasp::planParamsFromJson(doc["planning"]);
  if (doc.contains("bin") && doc["bin"].is_boolean() && !doc["bin"].get<bool>())
    s.bin.reset();
  else if (doc.contains("bin"))
    s.bin = core::grasp::binParamsFromJson(doc["bin"], *s.bin);
  if (o.models.empty() && doc.contains("models") && doc["models"].is_array())
    for (const auto& m : doc["models"]) {
      const fs::path p(m.get<std::string>());
      o.models.push_back((p.is_absolute() ? p : fs::path(path).parent_path() / p).string());
    }
  if (o.recipe.preset.empty() && o.recipe.params.empty() && doc.contains("preset"))
    o.recipe.preset = doc["preset"].get<std::string>();
  if (doc.contains("set") && doc["set"].is_object())
    for (const auto& item : doc["set"].items()) // applied before the command line's --set
      o.recipe.overrides.insert(o.recipe.overrides.begin(), item.key() + "=" + item.value().dump());
}

ClearBinSetup makeSetup(Options& o) {
  if (o.count < 1 || o.count > 200)
    throw core::Error("--count must be between 1 and 200 (got " + std::to_string(o.count) + ")");
  ClearBinSetup s;
  s.part = core::builtInPart(o.part); // names the valid parts when unknown
  s.count = o.count;
  s.seed = o.seed;
  s.sensor = o.recipe.sensor.empty() ? "phoxi-m-1032" : o.recipe.sensor;
  (void)core::sensorPreset(s.sensor);
  s.max_cycles = o.max_cycles;
  s.out = o.out;
  s.bin = core::grasp::BinEstimateParams{};
  if (!o.recipe_file.empty())
    applyRecipe(o.recipe_file, s, o);
  s.judge.approach_length_mm = s.planning.approach_length_mm;
  std::error_code ec;
  fs::create_directories(s.out, ec);
  if (ec || !fs::is_directory(s.out))
    throw core::Error("cannot create the output folder '" + o.out + "'");
  core::checkWritable(s.out / "clear-bin.json");
  if (!o.models.empty())
    s.models = loadModelViews(o.models).models;
  else
    s.models = autoTeachViews(o.part, o.teach_seed, s.sensor);
  s.params = resolveParams(o.recipe, core::viewsParams(s.models));
  return s;
}

double median(std::vector<double> v) {
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

json attemptJson(const PickAttempt& a) {
  const Eigen::Vector3d t = a.T_scene_tool.translation();
  const Eigen::Quaterniond q(a.T_scene_tool.linear());
  json collisions = json::array();
  for (const auto& c : a.verdict.collisions)
    collisions.push_back(c);
  return {
      {"detection", a.detection},
      {"grip", a.grip},
      {"tool",
       {{"position_mm", {t.x(), t.y(), t.z()}}, {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}}},
      {"instance", a.instance < 0 ? json(nullptr) : json(a.instance)},
      {"position_error_mm", a.verdict.position_error_mm},
      {"approach_error_deg", a.verdict.approach_error_deg},
      {"wrong", a.verdict.wrong},
      {"collisions", collisions}};
}

json reportJson(const ClearBinSetup& s, const ClearBinReport& r) {
  json cycles = json::array();
  std::vector<double> cycle_ms;
  for (std::size_t k = 0; k < r.cycles.size(); ++k) {
    const ClearCycle& c = r.cycles[k];
    json attempts = json::array();
    for (const auto& a : c.attempts)
      attempts.push_back(attemptJson(a));
    char picture[32];
    std::snprintf(picture, sizeof picture, "cycle-%03zu.png", k);
    cycles.push_back({{"cycle", k},
                      {"instances", c.instances},
                      {"detections", c.detections},
                      {"feasible_grasps", c.feasible},
                      {"vision_ms", c.vision_ms},
                      {"planning_ms", c.planning_ms},
                      {"rejected_grasps", c.rejections},
                      {"attempts", attempts},
                      {"picked", c.picked < 0 ? json(nullptr) : json(c.picked)},
                      {"picture", picture}});
    cycle_ms.push_back(c.vision_ms + c.planning_ms);
  }
  return {{"format", "scanpick-clear-bin"},
          {"version", 1},
          {"part", s.part.name},
          {"count", s.count},
          {"seed", s.seed},
          {"sensor", s.sensor},
          {"views", s.models.size()},
          {"gripper", core::grasp::toJson(s.gripper)},
          {"planning", core::grasp::toJson(s.planning)},
          {"judge",
           {{"position_tol_mm", s.judge.position_tol_mm},
            {"approach_tol_deg", s.judge.approach_tol_deg}}},
          {"picks", r.picks},
          {"wrong_picks", r.wrong_picks},
          {"collisions", r.collisions},
          {"left", r.left},
          {"cleared", double(r.picks) / r.count},
          {"cycle_ms_median", median(cycle_ms)},
          {"cycle_ms_max",
           cycle_ms.empty() ? 0.0 : *std::max_element(cycle_ms.begin(), cycle_ms.end())},
          {"stop", r.stop_reason},
          {"cycles", cycles}};
}

void printTable(const ClearBinReport& r, const json& summary) {
  std::printf("cycle  parts  found  grasps  tried  picked  vision ms  planning ms\n");
  for (std::size_t k = 0; k < r.cycles.size(); ++k) {
    const ClearCycle& c = r.cycles[k];
    std::printf("%5zu  %5d  %5d  %6d  %5zu  %6s  %9.0f  %11.0f\n", k, c.instances, c.detections,
                c.feasible, c.attempts.size(),
                c.picked < 0 ? "-" : std::to_string(c.picked).c_str(), c.vision_ms, c.planning_ms);
  }
  std::printf("\npart %s, %d in the bin: %d picked, %d wrong, %d colliding, %d left, %.0f %% "
              "cleared; vision + planning %.0f ms per cycle (median), %.0f ms (max); stopped: %s\n",
              summary["part"].get<std::string>().c_str(), r.count, r.picks, r.wrong_picks,
              r.collisions, r.left, 100.0 * summary["cleared"].get<double>(),
              summary["cycle_ms_median"].get<double>(), summary["cycle_ms_max"].get<double>(),
              r.stop_reason.c_str());
}

int run(Options& o) {
  const ClearBinSetup setup = makeSetup(o);
  const ClearBinReport report = clearBin(setup);
  const json doc = reportJson(setup, report);
  core::writeFileAtomic(setup.out / "clear-bin.json", core::dumpJsonText(doc, 2) + "\n");
  printTable(report, doc);
  return kOk;
}

} // namespace

void registerClearBinCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = addCommand(app, "clear-bin",
                             "Virtual bin clearing: scan, recognize, plan and pick a simulated bin "
                             "until it is empty, each pick judged against the truth",
                             [o] { return run(*o); });
  sub->add_option("--part", o->part, "Part: a built-in name or random-<seed>")->required();
  sub->add_option("--count", o->count, "Parts dropped into the bin")->capture_default_str();
  sub->add_option("--seed", o->seed, "Seed of the bin (physics and sensor noise)")
      ->capture_default_str();
  sub->add_option("--model", o->models,
                  "Taught views of the part (.spmodel, taught knowing their place in the part); "
                  "default: its four table views taught from simulated scans")
      ->check(CLI::ExistingFile);
  sub->add_option("--teach-seed", o->teach_seed, "Seed of the simulated teach scans")
      ->capture_default_str();
  sub->add_option("--recipe", o->recipe_file,
                  "Recipe file (docs/grasping.md): gripper, grasps, planning, bin, and its models, "
                  "preset and settings unless given here")
      ->check(CLI::ExistingFile);
  sub->add_option("--max-cycles", o->max_cycles, "Stop after this many cycles (0: 2 × count + 5)")
      ->check(CLI::Range(0, 10000));
  sub->add_option("--out", o->out,
                  "Folder for clear-bin.json and the overlay picture of each cycle")
      ->required();
  o->recipe.add(sub);
}

} // namespace scanpick::cli
