#pragma once
/// @file Detection.h
/// What recognition reports for each found instance of the taught part. A plain value in
/// core/common: the resolution of turns (core/ambiguity), the Recognizer (core/pipeline), what is
/// made from a result (core/output), grasp planning and the robot link all take it.

#include "core/common/GripPoint.h"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace scanpick::core {

/// A line in the scene frame about which a detection's turn is not known (Detection).
struct FreeTurnAxis {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();   ///< a point on the axis, scene frame (mm)
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ(); ///< unit, scene frame
};

/// One recognized instance.
struct Detection {
  /// Maps model coordinates (the taught model's frame, mm) into the scene frame (mm).
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  /// Confidence in [0, 1]: the share of model features confirmed in the scene (the thesis), or,
  /// with point-level verification on (matching.verify_tolerance_mm > 0), `coverage`.
  double score = 0.0;
  double feature_score = 0.0; ///< share of model features confirmed in the scene, [0, 1]
  /// Share of the model points visible at this pose with a scene point within
  /// matching.verify_tolerance_mm (after refinement, if on), [0, 1]; -1 when not verified.
  double coverage = -1.0;
  /// The pose was refined by ICP: refine.enabled, or a surface-voting pose that ICP polished.
  bool refined = false;
  /// Matched (model feature index, scene feature index) pairs behind the pose.
  std::vector<std::pair<int, int>> matched_features;
  std::vector<GripPoint> grip_points_scene; ///< the model's grip points mapped into the scene
  int cluster = -1;                         ///< scene cluster it was found in (-1: whole scene)
  /// Which model found it, when several views of a part are searched (recognizeViews); else 0.
  int model_index = 0;
  /// Where the instance lies, for telling instances apart (scene frame, mm): the model origin, or
  /// for a view that is a surface of revolution but for a detail, the point of its axis nearest
  /// the origin, which a turn about the axis leaves in place. Set by Recognizer::recognize with the
  /// final pose; recognizeViews merges views by it.
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  /// Set when the view that found it is a surface of revolution about this axis (RevolutionAxis.h,
  /// such as a flanged pipe taught from the side), or one but for a detail that the scan does not
  /// confirm at this pose (a cup whose handle is hidden): the part's turn about the axis is not
  /// seen, and T_scene_model is one of the poses turned about it that fit equally well. Grip points
  /// on the axis are unaffected; a grip that depends on the turn must not trust it.
  std::optional<FreeTurnAxis> free_turn_axis;
  /// Other poses of the part (model frame → scene frame, mm) that this scan cannot tell apart
  /// from T_scene_model: the view has a near symmetry (NearSymmetry.h, such as a hook plate seen
  /// from below, turned 180° about its normal) whose differing points are hidden here, and the
  /// turned pose verifies too. Grip points that move between them must not be trusted.
  std::vector<Eigen::Isometry3d> alternative_poses;
  /// Empty, or one entry per alternative pose: the axis about which that pose's turn is not seen,
  /// as free_turn_axis is for T_scene_model (a cup turned end over end whose handle would be
  /// hidden there), or nothing where it is seen.
  std::vector<std::optional<FreeTurnAxis>> alternative_free_turn_axes;
};

} // namespace scanpick::core
