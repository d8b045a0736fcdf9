#pragma once
/// @file PoseRefinement.h
/// Pose refinement beyond the thesis (its §5 names ICP as the way past ~2 mm / 3.5°): robust,
/// coarse-to-fine point-to-plane ICP of the model's visible points against the scene, and a
/// coverage score to verify a detection.

#include "core/cloud/PointCloud.h"
#include "core/common/Progress.h"
#include "core/params/Parameters.h"
#include "core/refine/RefineModel.h"
#include "core/refine/SceneIndex.h"

#include <Eigen/Geometry>

namespace scanpick::core {

/// Outcome of refinePose.
struct RefinementResult {
  /// The refined pose (model frame → scene frame, mm). Equal to the initial pose when no
  /// iteration could run (no correspondences).
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  /// RMS point-to-plane distance of the inlier pairs at the final pose (mm; point-to-point
  /// distance when params.point_to_plane is off); for a good fit about the sensor noise.
  double rmse_mm = 0;
  /// Share of the visible model points (normal facing the camera at the final pose) with a scene
  /// point within params.inlier_distance_mm, [0, 1]. 0 when no model point is visible.
  double inlier_fraction = 0;
  int iterations = 0; ///< ICP iterations run
  /// True when the pose settled before max_iterations (a step below params.convergence_mm, or
  /// three in a row below twice that) AND inlier_fraction >= params.min_inlier_fraction: a
  /// settled, well supported pose. A pose that settled on too few inliers (a local minimum, a
  /// false detection, a heavily occluded part) is not "converged"; T_scene_model is then the
  /// last iterate, which may be worse than the initial pose.
  bool converged = false;
  std::size_t visible_points = 0; ///< visible model points at the final pose
};

/// Point-to-plane ICP leaves directions (of its six: turns and slides) whose curvature is below
/// this share of the strongest as they came, unless told otherwise: on them it would drift on
/// sensor noise.
inline constexpr double kIcpStableShare = 0.001;

/// Refines `T_scene_model_initial` so the model fits the scene (both mm, scene in the frame of
/// `scene`'s viewpoint, usually the camera frame): robust point-to-plane ICP (Tukey weights) on
/// the model points facing the camera, pairs whose normals disagree by more than ~26° or whose
/// scene point lies on an edge rejected, the pair distance shrinking from
/// params.max_correspondence_mm to max(3 x rms, params.min_correspondence_mm), every 4th point
/// until the steps are small, then all. Converges from about the feature matching's error
/// (2 mm / 3.5°: tests/unit/refine); a symmetric part converges to the nearest equivalent pose.
/// Deterministic: the same inputs give bitwise the same result, whatever the thread scheduling.
/// Throws Error when params are out of range; Cancelled when `progress` asks to stop (checked every
/// iteration). Thread-safe: many detections may be refined at once against one SceneIndex.
/// Point-to-plane moves only along directions pinned above `stable_share` of the strongest
/// (kIcpStableShare); a caller that places the others itself may hold more of them.
RefinementResult refinePose(const RefineModel& model, const SceneIndex& scene,
                            const Eigen::Isometry3d& T_scene_model_initial,
                            const RefineParams& params, const ProgressFn& progress = {},
                            double stable_share = kIcpStableShare);

/// Convenience overload: prepares the model (RefineModel with params.model_points) and indexes
/// the scene (default SceneIndexOptions) for this one call. Throws Error for an empty or
/// NaN-only model or scene. To refine many detections, build SceneIndex and RefineModel once.
RefinementResult refinePose(const PointCloud& model_mm, const PointCloud& scene_mm,
                            const Eigen::Isometry3d& T_scene_model_initial,
                            const RefineParams& params, const ProgressFn& progress = {});

/// Same, with a prepared scene index (the model is prepared for this call).
RefinementResult refinePose(const PointCloud& model_mm, const SceneIndex& scene,
                            const Eigen::Isometry3d& T_scene_model_initial,
                            const RefineParams& params, const ProgressFn& progress = {});

/// Verification score: the share of the model points visible at pose `T_scene_model` (normal
/// facing the camera) that have a scene point within `tolerance_mm` (> 0), in [0, 1]; 0 when no
/// point is visible. Like Pickit's "% of model points confirmed within a tolerance". Throws Error
/// for a tolerance <= 0.
double coverageScore(const RefineModel& model, const SceneIndex& scene,
                     const Eigen::Isometry3d& T_scene_model, double tolerance_mm);

} // namespace scanpick::core
