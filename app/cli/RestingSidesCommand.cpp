// scanpick-cli resting-sides: the distinct sides a part rests on when dropped on a table, with the
// probability of each, so an operator knows which sides to teach (docs/simulation.md).
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/RestingPoses.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

namespace scanpick::cli {
namespace {

using nlohmann::json;

struct Options {
  std::string part, mesh, json_path;
  bool close_holes = false;
  core::RestingPoseParams params;
};

constexpr double kDegPerRad = 57.29577951308232;
/// Share of drops the advice's sides should cover together.
constexpr double kAdviceCoverage = 0.95;

json rowsJson(const Eigen::Matrix3d& m) {
  json rows = json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back({m(r, 0), m(r, 1), m(r, 2)});
  return rows;
}

json sidesJson(const core::Part& part, const Options& o,
               const std::vector<core::RestingPose>& poses) {
  json sides = json::array();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const core::RestingPose& p = poses[i];
    const Eigen::AngleAxisd aa(p.R_table_part);
    sides.push_back({{"index", i},
                     {"probability", p.probability},
                     {"face_area_mm2", p.face_area_mm2},
                     {"symmetric_copies", p.symmetric_copies},
                     {"down_normal_part",
                      {p.down_normal_part.x(), p.down_normal_part.y(), p.down_normal_part.z()}},
                     {"R_table_part", rowsJson(p.R_table_part)},
                     {"axis", {aa.axis().x(), aa.axis().y(), aa.axis().z()}},
                     {"angle_deg", aa.angle() * kDegPerRad}});
  }
  return {{"format", "scanpick-resting-sides"},
          {"version", 1},
          {"part", part.name},
          {"seed", o.params.seed},
          {"drops", o.params.drops},
          {"sides", sides}};
}

/// How many of the most probable sides cover kAdviceCoverage of the drops.
std::size_t sidesToTeach(const std::vector<core::RestingPose>& poses) {
  double covered = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    covered += poses[i].probability;
    if (covered >= kAdviceCoverage - 1e-9)
      return i + 1;
  }
  return poses.size();
}

void printSides(const core::Part& part, const Options& o,
                const std::vector<core::RestingPose>& poses) {
  const bool symmetry_known =
      part.symmetry.continuous_axis.has_value() || !part.symmetry.discrete.empty();
  std::printf("%s: %zu distinct resting side%s (%d drops, seed %llu; %s)\n", part.name.c_str(),
              poses.size(), poses.size() == 1 ? "" : "s", o.params.drops,
              static_cast<unsigned long long>(o.params.seed),
              symmetry_known ? "up to the part's symmetries"
                             : "no symmetry known: symmetric sides are listed apart");
  std::printf("%5s %11s %14s %6s  %-26s %s\n", "side", "probability", "face area mm2", "copies",
              "down normal (part frame)", "rotation: axis, angle deg");
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const core::RestingPose& p = poses[i];
    const Eigen::AngleAxisd aa(p.R_table_part);
    // Round-off below the printed precision would show as "-0.000".
    const auto clean = [](double v) { return std::abs(v) < 5e-4 ? 0.0 : v; };
    const Eigen::Vector3d n = p.down_normal_part.unaryExpr(clean);
    const Eigen::Vector3d axis = aa.axis().unaryExpr(clean);
    std::printf("%5zu %11.3f %14.1f %6d  (%6.3f, %6.3f, %6.3f)   (%6.3f, %6.3f, %6.3f), %6.1f\n", i,
                p.probability, p.face_area_mm2, p.symmetric_copies, n.x(), n.y(), n.z(), axis.x(),
                axis.y(), axis.z(), aa.angle() * kDegPerRad);
  }
  if (o.params.drops > 0 && !poses.empty()) {
    const std::size_t k = sidesToTeach(poses);
    const std::string which =
        k == 1 ? std::string("side 0 (one view)")
               : std::string("sides 0 to ") + std::to_string(k - 1) + " (one view each)";
    std::printf("teach %s to cover %.0f %% of the ways it lands; in simulation: synth --layout "
                "teach --resting-side N\n",
                which.c_str(), 100 * kAdviceCoverage);
  }
}

int run(const Options& o) {
  if (o.part.empty() == o.mesh.empty())
    throw core::Error("give either --part NAME or --mesh FILE");
  if (o.close_holes && o.mesh.empty())
    throw core::Error("--close-holes caps the holes of a --mesh FILE: give one, or drop it");
  const core::Part part =
      o.mesh.empty() ? core::builtInPart(o.part) : core::partFromMeshFile(o.mesh, o.close_holes);
  if (!o.json_path.empty())
    core::checkWritable(o.json_path);
  const auto poses = core::restingPoses(part, o.params);
  printSides(part, o, poses);
  if (!o.json_path.empty()) {
    core::writeFileAtomic(o.json_path, core::dumpJsonText(sidesJson(part, o, poses), 2) + "\n");
    std::printf("wrote %s\n", o.json_path.c_str());
  }
  return kOk;
}

} // namespace

void registerRestingSidesCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* cmd = addCommand(
      app, "resting-sides",
      "Which sides to teach: lists the distinct sides a part comes to rest on when it is dropped "
      "on a table (faces of its convex hull that hold its centre of mass, merged up to its "
      "symmetries), with how often each occurs in simulated drops, most probable first, and how "
      "many of them to teach (one view each) to cover most of the ways it lands. Works from a "
      "built-in part or a part's closed mesh in mm (e.g. a CAD export).",
      [o] { return run(*o); });
  cmd->add_option("--part", o->part,
                  "built-in part: support, cup, pump-connector, coat-rack, random-<seed>");
  cmd->add_option("--mesh", o->mesh,
                  "closed triangle mesh in mm (.ply, .stl, .obj, .vtk) instead of --part");
  cmd->add_flag("--close-holes", o->close_holes,
                "cap the --mesh file's holes (a scanned part's open base) with triangles");
  cmd->add_option("--seed", o->params.seed, "random seed of the drops: same seed, same list")
      ->capture_default_str();
  cmd->add_option("--drops", o->params.drops,
                  "simulated drops that estimate the probabilities (0 = only list the sides)")
      ->capture_default_str();
  cmd->add_option("--json", o->json_path, "also write the list to this JSON file");
}

} // namespace scanpick::cli
