#pragma once
/// @file RenderCheck.h
/// Whether a scan could tell a pose from the truth at all: the virtual scanner renders a scene's
/// ground truth, noise-free, once as it is and once with one instance moved to an estimated pose,
/// and the two depth images are compared where that instance is seen in either. A detection whose
/// pose the scan cannot tell from the truth (a turn about an axis whose detail is hidden, a flip
/// whose differing side faces away) changes almost no pixel; a wrong pose changes many.

#include "core/common/Progress.h"
#include "core/eval/Evaluator.h"
#include "core/eval/GroundTruth.h"
#include "core/sim/Scene.h"

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace scanpick::core::eval {

/// Pixels of one instance in either render, and those where the two renders differ.
struct RenderDifference {
  std::size_t pixels = 0;    ///< pixels where the instance is seen in either render
  std::size_t differing = 0; ///< of those, measured in one render only or > tolerance apart
  /// differing / pixels, [0, 1]; 1 when the instance is seen in neither render (nothing to tell).
  [[nodiscard]] double fraction() const {
    return pixels ? static_cast<double>(differing) / static_cast<double>(pixels) : 1.0;
  }
};

/// Renders the instances of a scene's ground truth (built-in parts by name, no sensor noise) with
/// its sensor preset, and compares it with the same scene with one instance moved. Where the truth
/// places the simulated world (sensor.T_scene_world), its environment is rendered too: the bin's
/// walls hide and shadow parts, and its floor shows behind a part moved off its place (a bin of
/// scene.bin's size, or for ground truth written before that was, the simulator's only bin).
/// Otherwise the parts are rendered alone.
class TruthRenderer {
public:
  /// Throws Error when the truth names no sensor preset or a part that is not built in.
  explicit TruthRenderer(const GroundTruth& truth);

  /// The scene rendered with instance `instance_id` at `T_scene_part` (part frame → scene, mm)
  /// compared with the truth: a pixel differs when it is measured in one render only or its depths
  /// differ by more than `tolerance_mm` (> 0). Throws Error for an unknown instance id or a
  /// tolerance <= 0.
  [[nodiscard]] RenderDifference difference(int instance_id, const Eigen::Isometry3d& T_scene_part,
                                            double tolerance_mm) const;

  /// The id of the instance of `part` whose centre (the middle of the part's bounding box) lies
  /// nearest to the centre of a part at `T_scene_part`: the instance a detection lies on, even
  /// one turned end over end; -1 when the scene holds no instance of `part`.
  [[nodiscard]] int instanceAt(const std::string& part,
                               const Eigen::Isometry3d& T_scene_part) const;

  /// The scene as the truth places it: its instance k is the truth's instance truthIds()[k].
  [[nodiscard]] const Scene& scene() const { return m_scene; }
  [[nodiscard]] const std::vector<int>& truthIds() const { return m_truth_ids; }
  [[nodiscard]] const SensorModel& sensor() const { return m_sensor; }

private:
  Scene m_scene; ///< the renderer's instance k is the truth's instance m_truth_ids[k]
  std::vector<int> m_truth_ids;
  SensorModel m_sensor;
  std::vector<float> m_depth_mm;      ///< per pixel, NaN where nothing is measured
  std::vector<std::int32_t> m_labels; ///< per pixel, the instance id seen (RenderResult)
};

/// `report` with the render check run on every detection's own pose against the instance it
/// matched, or for a false positive the instance it lies on (TruthRenderer::instanceAt), and on
/// every alternative pose a true positive reports (DetectionOutcome::ambiguity_render_difference),
/// and its summaries made again. Each scene is rendered from the
/// ground truth it was evaluated against (SceneEvaluation::truth). Throws Error as
/// TruthRenderer does, and for a scene that keeps no ground truth.
EvalReport withRenderCheck(EvalReport report, double tolerance_mm, const ProgressFn& progress = {});

} // namespace scanpick::core::eval
