#include "core/eval/RenderCheck.h"

#include "core/common/Error.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/Renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace scanpick::core::eval {
namespace {

/// The depth (z, mm) of each pixel of an organized render, NaN where nothing is measured.
std::vector<float> depthOf(const RenderResult& render) {
  std::vector<float> depth(render.cloud.points_mm.size());
  for (std::size_t p = 0; p < depth.size(); ++p)
    depth[p] = isValid(render.cloud.points_mm[p]) ? render.cloud.points_mm[p].z()
                                                  : std::numeric_limits<float>::quiet_NaN();
  return depth;
}

} // namespace

TruthRenderer::TruthRenderer(const GroundTruth& truth) {
  if (truth.sensor_preset.empty())
    throw Error(truth.source + ": names no sensor preset, so its scan cannot be rendered again");
  m_sensor = sensorPreset(truth.sensor_preset);
  // The environment (a bin and the ground, or a table) where the truth places the world: it hides
  // and shadows parts, and shows behind a part moved off its place. Without the world's place, the
  // scene frame is taken for it and the parts are rendered alone.
  if (truth.T_scene_world && !truth.kind.empty()) {
    m_scene.layout = layoutFromName(truth.kind);
    // The simulator's only bin, for ground truth written before scene.bin was.
    m_scene.environment_mm = environmentMesh(m_scene.layout, truth.bin.value_or(BinGeometry{}));
    m_scene.T_camera_world = *truth.T_scene_world;
  }
  const Eigen::Isometry3d T_world_scene = m_scene.T_camera_world.inverse();
  std::map<std::string, std::size_t> part_index;
  for (const auto& instance : truth.instances) {
    auto [it, added] = part_index.try_emplace(instance.part, m_scene.parts.size());
    if (added) {
      try {
        m_scene.parts.push_back(builtInPart(instance.part));
      } catch (const Error& e) {
        throw Error(truth.source + ": " + e.what() +
                    ", and the render check renders built-in parts only: run eval without "
                    "--render-check");
      }
    }
    // The renderer labels instances by their index.
    m_scene.instances.push_back(
        {static_cast<int>(m_truth_ids.size()), it->second, T_world_scene * instance.T_scene_part});
    m_truth_ids.push_back(instance.id);
  }
  const RenderResult render = renderScene(m_scene, m_sensor, SensorNoise{}, 0);
  m_depth_mm = depthOf(render);
  m_labels = render.labels;
}

RenderDifference TruthRenderer::difference(int instance_id, const Eigen::Isometry3d& T_scene_part,
                                           double tolerance_mm) const {
  if (!(tolerance_mm > 0))
    throw Error("the render check's depth tolerance must be > 0 mm");
  const auto it = std::find(m_truth_ids.begin(), m_truth_ids.end(), instance_id);
  if (it == m_truth_ids.end())
    throw Error("render check: the ground truth has no instance " + std::to_string(instance_id));
  const auto label = static_cast<std::int32_t>(it - m_truth_ids.begin());
  Scene moved = m_scene;
  moved.instances[static_cast<std::size_t>(label)].T_world_part =
      m_scene.T_camera_world.inverse() * T_scene_part;
  const RenderResult render = renderScene(moved, m_sensor, SensorNoise{}, 0);
  const std::vector<float> depth = depthOf(render);
  RenderDifference out;
  for (std::size_t p = 0; p < depth.size(); ++p) {
    if (m_labels[p] != label && render.labels[p] != label)
      continue;
    ++out.pixels;
    const bool truth_seen = !std::isnan(m_depth_mm[p]), moved_seen = !std::isnan(depth[p]);
    if (truth_seen != moved_seen ||
        (truth_seen && std::abs(m_depth_mm[p] - depth[p]) > tolerance_mm))
      ++out.differing;
  }
  return out;
}

int TruthRenderer::instanceAt(const std::string& part,
                              const Eigen::Isometry3d& T_scene_part) const {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const auto& instance : m_scene.instances) {
    const Part& p = m_scene.parts[instance.part];
    if (p.name != part)
      continue;
    const double distance =
        (m_scene.T_scene_part(instance) * p.center_mm() - T_scene_part * p.center_mm()).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best = m_truth_ids[static_cast<std::size_t>(instance.id)];
    }
  }
  return best;
}

EvalReport withRenderCheck(EvalReport report, double tolerance_mm, const ProgressFn& progress) {
  for (std::size_t k = 0; k < report.scenes.size(); ++k) {
    reportProgress(progress, static_cast<double>(k) / static_cast<double>(report.scenes.size()));
    SceneEvaluation& scene = report.scenes[k];
    if (!scene.truth)
      throw Error("render check: scene " + scene.name + " keeps no ground truth to render");
    const TruthRenderer renderer(*scene.truth);
    for (auto& o : scene.outcomes) {
      const int instance =
          o.true_positive ? o.instance_id : renderer.instanceAt(scene.part, o.T_scene_part);
      if (instance < 0)
        continue;
      o.render_difference = renderer.difference(instance, o.T_scene_part, tolerance_mm).fraction();
      if (!o.true_positive || o.alternatives_scene_part.empty())
        continue;
      double largest = *o.render_difference;
      for (const auto& T_alternative : o.alternatives_scene_part)
        largest = std::max(largest,
                           renderer.difference(instance, T_alternative, tolerance_mm).fraction());
      o.ambiguity_render_difference = largest;
    }
  }
  reportProgress(progress, 1.0);
  return makeReport(std::move(report.scenes), report.tolerances);
}

} // namespace scanpick::core::eval
