#include "core/sim/Synth.h"

#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/sim/DepthPng.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/PartDeformation.h"

#include <nlohmann/json.hpp>

namespace scanpick::core {
namespace {

using nlohmann::json;

json matrixJson(const Eigen::Matrix4d& m) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r)
    rows.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return rows;
}

json vectorJson(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

std::vector<Part> requestedParts(const SynthRequest& r) {
  if (!r.mesh_path.empty())
    return {partFromMeshFile(r.mesh_path, r.close_holes)};
  std::vector<Part> parts;
  for (const auto& name : r.parts)
    parts.push_back(builtInPart(name));
  return parts;
}

} // namespace

void validateRequest(const SynthRequest& r) {
  (void)sensorPreset(r.sensor); // throws for an unknown sensor
  if (r.mesh_path.empty() && r.parts.empty())
    throw Error("no part given: use --part NAME or --mesh FILE");
  if (r.count < 1)
    throw Error("--count must be at least 1 (got " + std::to_string(r.count) + ")");
  if (r.layout == LayoutKind::Teach && r.count != 1)
    throw Error("a teach scene holds exactly one part: use --count 1");
  if (r.teach_side < 0 || r.teach_side >= kTeachSides)
    throw Error("--teach-side must be between 0 and " + std::to_string(kTeachSides - 1));
  if (r.resting_side && r.layout != LayoutKind::Teach)
    throw Error("--resting-side applies to --layout teach only");
  if (r.resting_side && r.teach_side != 0)
    throw Error("give either --teach-side or --resting-side, not both");
  if (r.resting_side && *r.resting_side < 0)
    throw Error("--resting-side must be 0 or more (0 = the most probable resting side)");
  if (!(r.deformation >= 0 && r.deformation <= kMaxDeformation))
    throw Error("--deform must be between 0 and 0.3 (a fraction of the part's size), got " +
                std::to_string(r.deformation));
  if (r.noise_sigma_mm && !(*r.noise_sigma_mm >= 0 && *r.noise_sigma_mm <= 50))
    throw Error("--noise-sigma must be between 0 and 50 mm");
  for (const auto& name : r.parts)
    if (r.mesh_path.empty()) {
      try {
        (void)builtInPart(name);
      } catch (const Error& e) {
        throw Error(std::string(e.what()) + "; or give a part's mesh with --mesh FILE");
      }
    }
}

SynthScene synthesize(const SynthRequest& request, const ProgressFn& progress) {
  validateRequest(request);
  SynthScene out;
  out.sensor = sensorPreset(request.sensor);
  out.seed = request.seed;
  out.noise = request.noiseless        ? SensorNoise::none()
              : request.noise_sigma_mm ? SensorNoise::withSigma(out.sensor, *request.noise_sigma_mm)
                                       : SensorNoise::typical(out.sensor);
  SceneSpec spec;
  spec.layout = request.layout;
  out.parts = requestedParts(request);
  spec.parts = out.parts;
  if (request.deformation > 0) {
    // One deformed copy per instance (instance k uses spec.parts[k % size]).
    spec.parts.clear();
    for (int k = 0; k < request.count; ++k)
      spec.parts.push_back(deformedPart(out.parts[static_cast<std::size_t>(k) % out.parts.size()],
                                        request.deformation,
                                        hashMix(request.seed, static_cast<std::uint64_t>(k), 102)));
  }
  spec.count = request.count;
  spec.seed = hashMix(request.seed, 0, 100); // physics and rendering draw from separate streams
  spec.camera_height_mm = request.camera_height_mm;
  spec.teach_side = request.teach_side;
  spec.resting_side = request.resting_side;
  spec.bin = request.bin;
  out.scene = buildScene(spec, out.sensor, subProgress(progress, 0.0, 0.4));
  out.render = renderScene(out.scene, out.sensor, out.noise, hashMix(request.seed, 0, 101),
                           subProgress(progress, 0.4, 1.0));
  return out;
}

std::string groundTruthJson(const SynthScene& s, const std::string& cloud_file,
                            const std::string& picture_file) {
  const Scene& scene = s.scene;
  json j;
  j["format"] = "scanpick-ground-truth";
  j["version"] = 1;
  j["units"] = "mm";
  j["scene"] = {{"kind", layoutName(scene.layout)},
                {"seed", s.seed},
                {"cloud", cloud_file},
                {"picture", picture_file}};
  if (scene.layout == LayoutKind::Bin)
    j["scene"]["bin"] = {{"inner_x_mm", scene.bin.inner_x_mm},
                         {"inner_y_mm", scene.bin.inner_y_mm},
                         {"wall_height_mm", scene.bin.wall_height_mm},
                         {"wall_thickness_mm", scene.bin.wall_thickness_mm}};
  Eigen::Isometry3d T_camera_projector = s.sensor.T_camera_projector;
  j["sensor"] = {{"preset", s.sensor.preset},
                 {"width", s.sensor.width},
                 {"height", s.sensor.height},
                 {"fx", s.sensor.fx},
                 {"fy", s.sensor.fy},
                 {"cx", s.sensor.cx},
                 {"cy", s.sensor.cy},
                 {"T_scene_camera", matrixJson(Eigen::Matrix4d::Identity())},
                 {"T_scene_projector", matrixJson(T_camera_projector.matrix())},
                 {"T_scene_world", matrixJson(scene.T_camera_world.matrix())},
                 {"min_range_mm", s.sensor.min_range_mm},
                 {"max_range_mm", s.sensor.max_range_mm},
                 {"noise_sigma_mm", s.noise.z_sigma_mm},
                 {"disparity_step_px", s.noise.disparity_step_px},
                 {"disparity_sigma_px", s.noise.disparity_sigma_px},
                 {"dropout_probability", s.noise.dropout_probability},
                 {"flying_probability", s.noise.flying_probability}};
  json parts = json::object();
  for (const auto& p : s.parts) {
    json grips = json::array();
    for (const auto& g : p.grip_points)
      grips.push_back({{"name", g.name}, {"position_mm", vectorJson(g.position_mm)}});
    json discrete = json::array();
    for (const auto& S : p.symmetry.discrete)
      discrete.push_back(matrixJson(S.matrix()));
    json axis = nullptr;
    if (p.symmetry.continuous_axis)
      axis = {{"point_mm", vectorJson(p.symmetry.continuous_axis->point_mm)},
              {"direction", vectorJson(p.symmetry.continuous_axis->direction)}};
    parts[p.name] = {{"diameter_mm", p.diameter_mm()},
                     {"center_mm", vectorJson(p.center_mm())},
                     {"grip_points", grips},
                     {"symmetry", {{"continuous_axis", axis}, {"discrete", discrete}}}};
  }
  j["parts"] = parts;
  json instances = json::array();
  for (const auto& inst : scene.instances) {
    const Part& p = scene.parts[inst.part];
    const Eigen::Isometry3d T = scene.T_scene_part(inst);
    json grips = json::array();
    for (const auto& g : p.grip_points)
      grips.push_back({{"name", g.name}, {"position_mm", vectorJson(T * g.position_mm)}});
    const auto id = static_cast<std::size_t>(inst.id);
    instances.push_back({{"id", inst.id},
                         {"part", p.name},
                         {"T_scene_part", matrixJson(T.matrix())},
                         {"visible_fraction", s.render.visible_fraction[id]},
                         {"visible_points", s.render.visible_points[id]},
                         {"lit_pixels", s.render.lit_pixels[id]},
                         {"lit_pixels_alone", s.render.lit_pixels_alone[id]},
                         {"grip_points", grips}});
  }
  j["instances"] = instances;
  if (scene.crop_box_world) {
    j["crop_box"] = {{"T_scene_box", matrixJson(scene.T_camera_world.matrix())},
                     {"min_mm", vectorJson(scene.crop_box_world->min())},
                     {"max_mm", vectorJson(scene.crop_box_world->max())}};
  }
  return dumpJsonText(j, 2) + "\n";
}

std::vector<std::filesystem::path> writeSynthScene(const std::filesystem::path& prefix,
                                                   const SynthScene& s) {
  namespace fs = std::filesystem;
  if (prefix.filename().empty())
    throw Error("the output prefix '" + prefix.string() +
                "' names a folder: add a file name, e.g. out/scene");
  const std::string base = prefix.filename().string();
  const std::vector<fs::path> finals = {fs::path(prefix.string() + ".pcd"),
                                        fs::path(prefix.string() + ".png"),
                                        fs::path(prefix.string() + ".gt.json")};
  // Encode in memory first: nothing touches the disk until all content exists.
  const std::string png = depthPngBytes(s.render.cloud);
  const std::string gt = groundTruthJson(s, base + ".pcd", base + ".png");
  std::vector<fs::path> temps;
  for (const auto& f : finals)
    temps.push_back(fs::path(f.string() + ".partial"));
  auto cleanup = [&temps] {
    std::error_code ec;
    for (const auto& t : temps)
      fs::remove(t, ec);
  };
  std::size_t renamed = 0;
  try {
    if (prefix.has_parent_path()) {
      std::error_code ec;
      fs::create_directories(prefix.parent_path(), ec);
      if (ec)
        throw Error("cannot create the folder '" + prefix.parent_path().string() +
                    "': " + ec.message());
    }
    saveCloudPcd(temps[0], s.render.cloud);
    writeFileAtomic(temps[1], png);
    writeFileAtomic(temps[2], gt);
    for (std::size_t i = 0; i < finals.size(); ++i) {
      std::error_code ec;
      fs::rename(temps[i], finals[i], ec);
      if (ec)
        throw Error("cannot write '" + finals[i].string() + "': " + ec.message());
      ++renamed;
    }
  } catch (...) {
    cleanup();
    std::error_code ec;
    for (std::size_t i = 0; i < renamed; ++i) // a failed rename must not leave half a scene
      fs::remove(finals[i], ec);
    throw;
  }
  return finals;
}

} // namespace scanpick::core
