// scanpick-cli synth / synth-suite: the virtual structured-light scanner.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "core/common/Error.h"
#include "core/sim/MeshIo.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/RandomPart.h"
#include "core/sim/Suite.h"
#include "core/sim/Synth.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace scanpick::cli {
namespace {

struct SynthOptions {
  std::vector<std::string> parts;
  std::string mesh, layout = "bin", sensor = "phoxi-m-1032", out;
  std::optional<int> count;        ///< default: 1 in a teach scene, else 8
  std::optional<int> teach_side;   ///< default 0
  std::optional<int> resting_side; ///< teach layout: the N-th most probable resting pose
  std::uint64_t seed = 0;
  double noise_sigma_mm = -1;
  double camera_height_mm = 0;
  double deformation = 0;
  bool noiseless = false;
  bool export_mesh = false;
  bool close_holes = false;
};

std::vector<std::string> splitCommas(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const auto& item : items) {
    std::stringstream ss(item);
    std::string name;
    while (std::getline(ss, name, ','))
      if (!name.empty())
        out.push_back(name);
  }
  return out;
}

int runExportMesh(const SynthOptions& o) {
  if (o.out.empty())
    throw core::Error("--export-mesh needs --out FILE.ply");
  const std::filesystem::path out(o.out);
  if (out.extension() != ".ply")
    throw core::Error("--export-mesh writes PLY: give --out a name ending in .ply");
  const auto names = splitCommas(o.parts);
  if (names.size() != 1 && o.mesh.empty())
    throw core::Error("--export-mesh needs exactly one --part NAME (or --mesh FILE)");
  const core::Part part = o.mesh.empty() ? core::builtInPart(names.front())
                                         : core::partFromMeshFile(o.mesh, o.close_holes);
  const core::TriangleMesh mesh = part.mesh();
  core::saveMeshPly(out, mesh);
  std::cout << "wrote " << out.string() << " (" << part.name << ", " << mesh.vertices_mm.size()
            << " vertices, " << mesh.triangles.size() << " triangles, mm)\n";
  return kOk;
}

int runSynth(const SynthOptions& o) {
  if (o.close_holes && o.mesh.empty())
    throw core::Error(
        "--close-holes caps the holes of a --mesh FILE: give one, or drop --close-holes");
  if (o.export_mesh)
    return runExportMesh(o);
  if (o.out.empty())
    throw core::Error("--out PREFIX is required (writes PREFIX.pcd, PREFIX.png, PREFIX.gt.json)");
  core::SynthRequest r;
  r.parts = splitCommas(o.parts);
  if (r.parts.empty() && o.mesh.empty())
    r.parts = {"support"};
  if (!o.mesh.empty()) {
    if (!splitCommas(o.parts).empty())
      throw core::Error("give either --part or --mesh, not both");
    r.mesh_path = o.mesh;
    r.close_holes = o.close_holes;
  }
  r.layout = core::layoutFromName(o.layout);
  if (o.teach_side && o.resting_side)
    throw core::Error("give either --teach-side or --resting-side, not both");
  r.teach_side = o.teach_side.value_or(0);
  r.resting_side = o.resting_side;
  r.count = o.count.value_or(r.layout == core::LayoutKind::Teach ? 1 : 8);
  r.sensor = o.sensor;
  r.seed = o.seed;
  r.noiseless = o.noiseless;
  r.camera_height_mm = o.camera_height_mm;
  r.deformation = o.deformation;
  if (o.noise_sigma_mm >= 0)
    r.noise_sigma_mm = o.noise_sigma_mm;
  core::validateRequest(r);
  const auto t0 = std::chrono::steady_clock::now();
  const core::SynthScene synth = core::synthesize(r);
  const auto files = core::writeSynthScene(o.out, synth);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& f : files)
    std::cout << "wrote " << f.string() << "\n";
  std::printf("%zu instances, %zu valid points, %.2f s\n", synth.scene.instances.size(),
              synth.render.cloud.validCount(), seconds);
  for (const auto& inst : synth.scene.instances)
    std::printf("  instance %d (%s): visible %.2f, %zu points\n", inst.id,
                synth.scene.parts[inst.part].name.c_str(),
                synth.render.visible_fraction[static_cast<std::size_t>(inst.id)],
                synth.render.visible_points[static_cast<std::size_t>(inst.id)]);
  return kOk;
}

} // namespace

void registerSynthCommands(CLI::App& app) {
  auto o = std::make_shared<SynthOptions>();
  CLI::App* synth =
      addCommand(app, "synth",
                 "Simulate a structured-light scan of parts in a bin, scattered on a table, or "
                 "alone (teach), with ground truth; or export a part's mesh (--export-mesh).",
                 [o] { return runSynth(*o); });
  synth->add_option("--part", o->parts,
                    "built-in part: support, cup, pump-connector, coat-rack "
                    "(several, comma-separated, make a mixed scene)");
  synth->add_option("--mesh", o->mesh,
                    "closed triangle mesh in mm (.ply, .stl, .obj, .vtk) instead of --part");
  synth->add_flag("--close-holes", o->close_holes,
                  "cap the --mesh file's holes (a scanned part's open base) with triangles");
  synth->add_option("--layout", o->layout, "bin, scatter or teach")->capture_default_str();
  synth->add_option(
      "--teach-side", o->teach_side,
      "teach layout: side the part rests on, 0 = usual (default), 1 = turned over, 2 = on its "
      "side, 3 = on its end (one taught view per side)");
  synth->add_option("--resting-side", o->resting_side,
                    "teach layout, instead of --teach-side: rest the part on its N-th most "
                    "probable distinct resting side (0 = most probable; `resting-sides` lists "
                    "them), random yaw");
  synth->add_option("--count", o->count, "number of instances (default: 8; teach: 1)");
  synth->add_option("--sensor", o->sensor, "phoxi-m-1032, phoxi-m-2064 or kinect-v1")
      ->capture_default_str();
  synth->add_option("--seed", o->seed, "random seed: same seed, same files")->capture_default_str();
  synth->add_option("--noise-sigma", o->noise_sigma_mm,
                    "depth noise sigma in mm (default: the sensor's)");
  synth
      ->add_option("--deform", o->deformation,
                   "each instance's shape varies by up to this fraction of its size (stretched, "
                   "sheared and bent, like pears of one kind); the ground truth keeps the pose of "
                   "the part as designed. 0 to 0.3")
      ->capture_default_str();
  synth->add_flag("--noiseless", o->noiseless,
                  "exact geometry: no noise, dropouts or flying pixels");
  synth->add_option("--camera-height", o->camera_height_mm,
                    "camera height above the floor, mm (default: sensor's)");
  synth->add_option("--out", o->out,
                    "output prefix (PREFIX.pcd/.png/.gt.json), or FILE.ply with --export-mesh");
  synth->add_flag("--export-mesh", o->export_mesh,
                  "write the part's closed mesh (mm) to --out FILE.ply");

  auto suite_out = std::make_shared<std::string>();
  auto suites = std::make_shared<std::vector<std::string>>();
  auto suite_seed = std::make_shared<std::uint64_t>(core::kDefaultSuiteSeed);
  auto random_parts = std::make_shared<int>(core::kDefaultRandomParts);
  CLI::App* suite = addCommand(
      app, "synth-suite",
      "Write the fixed, seeded evaluation suites: phoxi-bin, kinect-bin, teach; random-parts.",
      [suite_out, suites, suite_seed, random_parts] {
        if (suite_out->empty())
          throw core::Error("--out DIR is required");
        std::vector<core::SuiteScene> scenes;
        for (const auto& name : suites->empty() ? core::suiteNames() : *suites) {
          auto s = core::suiteScenes(name, *suite_seed, *random_parts);
          scenes.insert(scenes.end(), s.begin(), s.end());
        }
        const auto t0 = std::chrono::steady_clock::now();
        std::size_t done = 0;
        const auto files =
            core::writeSuite(*suite_out, scenes, {}, [&](const std::filesystem::path& prefix) {
              std::cout << "[" << ++done << "/" << scenes.size() << "] " << prefix.string() << "\n"
                        << std::flush;
            });
        // Each generated part's mesh beside its scans, for other tools and for the peers.
        std::size_t meshes = 0;
        for (const auto& scene : scenes)
          if (scene.relative_prefix.filename() == "teach" &&
              core::randomPartSeed(scene.request.parts.front())) {
            core::saveMeshPly(std::filesystem::path(*suite_out) /
                                  scene.relative_prefix.parent_path() / "part.ply",
                              core::builtInPart(scene.request.parts.front()).mesh());
            ++meshes;
          }
        std::printf("wrote %zu files (%zu scenes) in %.1f s\n", files.size() + meshes,
                    scenes.size(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        return kOk;
      });
  suite->add_option("--out", *suite_out, "output folder");
  suite->add_option("--suite", *suites,
                    "suite(s) to write (default: phoxi-bin, kinect-bin, teach), or random-parts");
  suite->add_option("--parts", *random_parts, "parts of the random-parts suite")
      ->capture_default_str();
  suite->add_option("--seed", *suite_seed, "suite seed (keep the default to share results)")
      ->capture_default_str();
}

} // namespace scanpick::cli
