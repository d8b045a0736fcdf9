#include "app/cli/ClearBin.h"

#include "core/common/Error.h"
#include "core/output/OverlayPicture.h"
#include "core/pipeline/Recognizer.h"
#include "core/sim/Renderer.h"
#include "core/sim/SensorNoise.h"
#include "core/sim/Settle.h"
#include "core/sim/Synth.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>

namespace scanpick::cli {
namespace {

using core::grasp::TruthInstance;

constexpr int kContinuousTurnSteps = 360; ///< 1° steps about a part's axis of revolution

/// One simulated PhoXi teach scan of the part resting on `side`, taught as `teach
/// --crop-from-truth --remove-floor` does with no preset.
core::TaughtModel teachSide(const std::string& part, int side, std::uint64_t seed,
                            const std::string& sensor) {
  core::SynthRequest request;
  request.parts = {part};
  request.layout = core::LayoutKind::Teach;
  request.count = 1;
  request.seed = seed;
  request.teach_side = side;
  request.sensor = sensor;
  const core::SynthScene scan = core::synthesize(request);
  const core::Scene& scene = scan.scene;
  const Eigen::Isometry3d T_scan_part = scene.T_scene_part(scene.instances.at(0));
  core::TeachOptions options;
  options.name = part;
  options.sensor = scan.sensor;
  options.remove_floor = true;
  const Eigen::AlignedBox3d box = scene.crop_box_world.value();
  core::OrientedBox crop;
  crop.T_scan_box = (scene.T_camera_world * Eigen::Translation3d(box.center())).cast<float>();
  crop.half_extents_mm = (0.5 * box.sizes()).cast<float>();
  options.crop_oriented = crop;
  options.T_scan_part = T_scan_part;
  for (const auto& g : scan.parts.front().grip_points)
    options.grips_scan.push_back({g.name, T_scan_part * g.position_mm});
  const core::AutoParams derived = core::autoTeachParams(scan.render.cloud, options);
  return core::teach(scan.render.cloud, options, derived.params);
}

/// The part's symmetries as transforms S (part ≡ part · S), identity first; an axis of
/// revolution in 1° steps.
std::vector<Eigen::Isometry3d> symmetries(const core::Part& part) {
  std::vector<Eigen::Isometry3d> discrete{Eigen::Isometry3d::Identity()};
  discrete.insert(discrete.end(), part.symmetry.discrete.begin(), part.symmetry.discrete.end());
  if (!part.symmetry.continuous_axis)
    return discrete;
  const core::SymmetryAxis& axis = *part.symmetry.continuous_axis;
  std::vector<Eigen::Isometry3d> out;
  for (int k = 0; k < kContinuousTurnSteps; ++k) {
    const double turn = 2 * 3.14159265358979323846 * k / kContinuousTurnSteps;
    const Eigen::Isometry3d R = Eigen::Translation3d(axis.point_mm) *
                                Eigen::AngleAxisd(turn, axis.direction.normalized()) *
                                Eigen::Translation3d(-axis.point_mm);
    for (const auto& S : discrete)
      out.push_back(R * S);
  }
  return out;
}

/// Every true tool pose in the part frame: each view's grasps where the view sits in the part,
/// under each symmetry.
std::vector<Eigen::Isometry3d> partToolPoses(const ClearBinSetup& s,
                                             const std::vector<core::grasp::GraspModel>& models) {
  std::vector<Eigen::Isometry3d> out;
  const auto syms = symmetries(s.part);
  for (std::size_t m = 0; m < models.size(); ++m)
    for (const auto& g : models[m].grasps) {
      const Eigen::Isometry3d T_part_tool =
          core::grasp::toolPose(s.models[m]->T_part_model.value(), g);
      for (const auto& S : syms)
        out.push_back(S * T_part_tool);
    }
  return out;
}

/// The instances of `scene` as they truly are, scene frame.
std::vector<TruthInstance> truthInstances(const core::Scene& scene,
                                          const std::vector<Eigen::Isometry3d>& T_part_tool,
                                          const std::vector<Eigen::Vector3d>& surface_part) {
  std::vector<TruthInstance> out;
  for (const auto& inst : scene.instances) {
    const Eigen::Isometry3d T = scene.T_scene_part(inst);
    TruthInstance t;
    t.id = inst.id;
    for (const auto& P : T_part_tool)
      t.T_scene_tool.push_back(T * P);
    for (const auto& p : surface_part) {
      t.surface_mm.push_back(T * p);
      t.bounds_mm.extend(t.surface_mm.back());
    }
    out.push_back(std::move(t));
  }
  return out;
}

/// The bin's true inner box in the scene (camera) frame (core/sim: floor at world z = 0).
core::grasp::BinBox trueBin(const core::Scene& scene) {
  core::grasp::BinBox bin;
  bin.T_scene_bin = scene.T_camera_world;
  bin.half_size_mm = {scene.bin.inner_x_mm / 2, scene.bin.inner_y_mm / 2};
  bin.rim_height_mm = scene.bin.wall_height_mm;
  bin.floor_found = true;
  bin.walls_found = {true, true, true, true};
  return bin;
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// Everything a cycle needs that does not change between cycles.
struct Cell {
  const ClearBinSetup& setup;
  core::SensorModel sensor;
  core::Recognizer recognizer;
  std::vector<core::grasp::GraspModel> models;
  std::vector<const core::PointCloud*> clouds;
  std::vector<Eigen::Isometry3d> T_part_tool;
  std::vector<Eigen::Vector3d> surface_part;
};

/// Recognizes and plans in `scan`, then tries the picks in order until one succeeds.
ClearCycle runCycle(Cell& cell, const core::Scene& scene, const core::PointCloud& scan,
                    const std::vector<int>& first_ids, int index) {
  const ClearBinSetup& s = cell.setup;
  ClearCycle c;
  c.instances = int(scene.instances.size());
  auto t0 = std::chrono::steady_clock::now();
  const auto result = core::recognizeViews(cell.recognizer, s.models, scan, cell.sensor, s.params);
  c.vision_ms = msSince(t0);
  t0 = std::chrono::steady_clock::now();
  std::optional<core::grasp::BinBox> bin;
  if (s.bin)
    bin = core::grasp::estimateBin(scan, *s.bin);
  const auto list =
      core::grasp::planGrasps(scan, result.detections, cell.models, s.gripper, bin, s.planning);
  c.planning_ms = msSince(t0);
  c.detections = int(result.detections.size());
  c.feasible = int(list.picks.size());
  for (const auto& r : list.rejected) {
    std::set<std::string> kinds;
    for (const auto& why : r.rejections)
      kinds.insert(core::grasp::toString(why.kind));
    for (const auto& k : kinds)
      ++c.rejections[k];
  }
  char name[32];
  std::snprintf(name, sizeof name, "cycle-%03d.png", index);
  core::writeOverlayPng(s.out / name, scan, cell.clouds, result.detections, cell.sensor,
                        core::depthOverlayTolerance_mm(s.params));
  const auto truth = truthInstances(scene, cell.T_part_tool, cell.surface_part);
  const auto true_bin = trueBin(scene);
  for (const auto& pick : list.picks) {
    PickAttempt a;
    a.detection = pick.detection;
    a.grip = pick.grip;
    a.T_scene_tool = pick.T_scene_tool;
    a.verdict = core::grasp::judgePick(pick.T_scene_tool, s.gripper, truth, true_bin, s.judge);
    if (a.verdict.instance >= 0)
      a.instance = first_ids[std::size_t(a.verdict.instance)];
    c.attempts.push_back(a);
    if (a.verdict.success()) {
      c.picked = a.verdict.instance; // the scene's own numbering, mapped by the caller
      break;
    }
  }
  return c;
}

} // namespace

std::vector<std::shared_ptr<const core::TaughtModel>>
autoTeachViews(const std::string& part_name, std::uint64_t teach_seed, const std::string& sensor) {
  std::vector<std::shared_ptr<const core::TaughtModel>> views;
  for (int side = 0; side < core::kTeachSides; ++side) {
    try {
      views.push_back(std::make_shared<const core::TaughtModel>(
          teachSide(part_name, side, teach_seed, sensor)));
    } catch (const core::Error& e) {
      std::cerr << "warning: side " << side << " of '" << part_name << "' left out: " << e.what()
                << "\n";
    }
  }
  if (views.empty())
    throw core::Error("no side of '" + part_name + "' could be taught: give --model files");
  return core::joinViews(views);
}

ClearBinReport clearBin(const ClearBinSetup& s) {
  for (const auto& m : s.models)
    if (!m->T_part_model)
      throw core::Error("model '" + m->name +
                        "' does not know its place in the part, so its picks cannot be judged "
                        "against the truth: teach it with --crop-from-truth or --part-pose");
  core::SynthRequest request;
  request.parts = {s.part.name};
  request.count = s.count;
  request.seed = s.seed;
  request.sensor = s.sensor;
  core::SynthScene synth = core::synthesize(request);
  Cell cell{s, synth.sensor, {}, {}, {}, {}, {}};
  for (const auto& m : s.models) {
    core::grasp::GraspModel gm;
    gm.cloud_mm = m->cloud_mm;
    gm.grasps = core::grasp::graspPoints(m->grip_points, s.grasps);
    cell.models.push_back(std::move(gm));
    cell.clouds.push_back(&m->cloud_mm);
  }
  core::prepareViews(cell.recognizer, s.models, s.params);
  cell.T_part_tool = partToolPoses(s, cell.models);
  const core::TriangleMesh mesh = s.part.mesh();
  std::vector<Eigen::Vector3d> normals;
  core::sampleSurface(mesh, std::size_t(std::min(40000.0, core::surfaceArea(mesh))), 1,
                      cell.surface_part, normals);

  ClearBinReport report;
  report.count = s.count;
  core::Scene scene = synth.scene;
  std::vector<int> ids; // the first scan's number of each instance still in the bin
  for (int i = 0; i < s.count; ++i)
    ids.push_back(i);
  const int max_cycles = s.max_cycles > 0 ? s.max_cycles : 2 * s.count + 5;
  core::PointCloud scan = synth.render.cloud;
  report.stop_reason = "cycle limit";
  for (int k = 0; k < max_cycles; ++k) {
    if (scene.instances.empty()) {
      report.stop_reason = "bin empty";
      break;
    }
    if (k > 0)
      scan = core::renderScene(scene, synth.sensor, synth.noise,
                               core::hashMix(s.seed, std::uint64_t(k), 101))
                 .cloud;
    ClearCycle c = runCycle(cell, scene, scan, ids, k);
    for (const auto& a : c.attempts) {
      report.wrong_picks += a.verdict.wrong ? 1 : 0;
      report.collisions += a.verdict.collisions.empty() ? 0 : 1;
    }
    const int local = c.picked;
    if (local >= 0) {
      c.picked = ids[std::size_t(local)];
      ids.erase(ids.begin() + local);
      ++report.picks;
    }
    report.cycles.push_back(c);
    if (local < 0) {
      report.stop_reason = c.attempts.empty() ? "no pickable grasp" : "every grasp failed";
      break;
    }
    scene = core::settleScene(scene, {local});
  }
  if (scene.instances.empty())
    report.stop_reason = "bin empty";
  report.left = int(scene.instances.size());
  return report;
}

} // namespace scanpick::cli
