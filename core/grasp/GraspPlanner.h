#pragma once
/// @file GraspPlanner.h
/// Grasp planning: for each detection and grasp point, the tool pose in the scene, the checks of
/// the gripper and its straight approach path against the scan's points and the bin, the tilt
/// limit, and the pick list that ranks the grasps that pass and says why the others fail.

#include "core/cloud/PointCloud.h"
#include "core/common/Detection.h"
#include "core/grasp/BinBox.h"
#include "core/grasp/GraspPoint.h"
#include "core/grasp/Gripper.h"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::grasp {

/// The order of the pick list.
enum class PickOrder {
  HighestFirst,  ///< grip point highest along up first
  LeastOccluded, ///< smallest occlusion first (then highest)
  BestScore,     ///< best detection score first (then highest)
};
const char* toString(PickOrder order);
/// "highest-first", "least-occluded", "best-score"; throws Error for another name.
PickOrder parsePickOrder(const std::string& name);

/// Parameters of planGrasps. Lengths in mm, angles in degrees.
struct GraspPlanParams {
  /// Length of the straight approach path: the tool comes from this far back along the approach
  /// (the pre-grasp pose) to the grasp pose; the solids are swept over it.
  double approach_length_mm = 100.0;
  /// Largest angle between the approach and straight down (-up) a robot can reach.
  double max_tilt_deg = 30.0;
  /// Up in the scene frame (unit). Default: towards a camera looking down its +z axis (the
  /// camera's -z), as for a scan in its camera frame above the bin.
  Eigen::Vector3d up = -Eigen::Vector3d::UnitZ();
  /// Scene points within this distance of the posed model of the picked part are the part's own.
  double part_tolerance_mm = 3.0;
  /// The solids are grown by this much for every check (a safety margin).
  double clearance_mm = 1.0;
  /// A solid collides when more than this many points lie in it (a few stray sensor points do
  /// not block a grasp).
  int max_collision_points = 3;
  /// Detections scoring below this are not picked.
  double min_score = 0.0;
  PickOrder order = PickOrder::HighestFirst;
  /// The pick list keeps only the best grasp of each part (the others are left out).
  bool one_per_part = true;
  /// Reject grasps that move (by more than part_tolerance_mm) between the poses the scan cannot
  /// tell apart (Detection::alternative_poses, a free turn about Detection::free_turn_axis).
  bool reject_ambiguous = true;
  double grid_cell_mm = 5.0;        ///< cell of the point grid the checks search
  double bin_sample_mm = 2.0;       ///< spacing of the points a solid is tested with on the bin
  double occlusion_radius_mm = 4.0; ///< a point above a part point within this radius covers it
  int max_occlusion_samples = 400;  ///< model points sampled for the occlusion, at most
  bool operator==(const GraspPlanParams&) const = default;
};

/// A taught model as the planner needs it: its cloud (model frame, mm), to tell the picked
/// part's points, and its grasp points.
struct GraspModel {
  PointCloud cloud_mm;
  std::vector<GraspPoint> grasps;
};

/// Why a grasp is not picked.
enum class RejectKind {
  LowScore,       ///< the detection scores below min_score
  Ambiguous,      ///< the grasp moves between poses the scan cannot tell apart
  TiltTooLarge,   ///< the approach is tilted more than max_tilt_deg from straight down
  SceneCollision, ///< gripper or approach path hits scan points that are no detected part
  PartCollision,  ///< ... hits another detected part
  PickedPart,     ///< fingers (or their path) hit the picked part itself: opening too small
  BinCollision,   ///< ... hits the bin's floor or a wall
};
const char* toString(RejectKind kind); ///< "low-score", "ambiguous", "tilt", ...

/// One reason, with a sentence for the operator ("finger +x hits part #2 (31 points)").
struct Rejection {
  RejectKind kind = RejectKind::SceneCollision;
  std::string detail;
  bool operator==(const Rejection&) const = default;
};

/// One (detection, grasp point) pair, evaluated.
struct GraspCandidate {
  int detection = -1; ///< index into the detections given
  int grasp = -1;     ///< index into its model's grasp points
  std::string grip;   ///< the grasp point's name
  /// The tool frame (Gripper.h) at the grasp: tool → scene (mm).
  Eigen::Isometry3d T_scene_tool = Eigen::Isometry3d::Identity();
  /// Where the straight approach begins: T_scene_tool moved back by approach_length_mm.
  Eigen::Isometry3d T_scene_pregrasp = Eigen::Isometry3d::Identity();
  double tilt_deg = 0.0;  ///< angle between the approach and straight down
  double height_mm = 0.0; ///< the grip point along up (scene frame, from the scene origin)
  /// Share of the part's (sampled) model points that have a point of something else above
  /// them, [0, 1].
  double occlusion = 0.0;
  double score = 0.0;                ///< the detection's score
  std::vector<Rejection> rejections; ///< empty: the grasp is feasible
  [[nodiscard]] bool feasible() const { return rejections.empty(); }
};

/// The planner's answer.
struct PickList {
  std::vector<GraspCandidate> picks;    ///< feasible grasps, ranked (best first)
  std::vector<GraspCandidate> rejected; ///< the others, by detection then grasp, with reasons
};

/// The tool pose for a grasp point of a part at T_scene_model: origin at the grip point, +z along
/// the approach, +x along the closing axis; without one, +x is the scene's x axis made
/// perpendicular to the approach (its y axis when the approach is near x), so that the pose is
/// deterministic.
Eigen::Isometry3d toolPose(const Eigen::Isometry3d& T_scene_model, const GraspPoint& grasp);

/// Plans the grasps of `detections` (scene frame, mm; each found by models[model_index]) in
/// `scene_mm` (the scan they were found in, scene frame, mm) with `gripper`, and the bin when
/// given (estimateBin). Each detection's grasps are checked: score, ambiguity, tilt, then each
/// solid of the gripper swept along the approach path (grown by clearance_mm) against the scan's
/// points (those of the picked part excepted, and for fingers also against those: a finger
/// must not pass through the part) and against the bin. Every check runs, so a rejected grasp
/// lists every reason. Pure and deterministic. Throws Error for a detection whose model_index
/// names no model, out-of-range parameters or a bad gripper (toolSolids()).
PickList planGrasps(const PointCloud& scene_mm, const std::vector<Detection>& detections,
                    const std::vector<GraspModel>& models, const Gripper& gripper,
                    const std::optional<BinBox>& bin, const GraspPlanParams& params);

} // namespace scanpick::core::grasp
