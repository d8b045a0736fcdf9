#pragma once
/// @file PickJudge.h
/// Judging a pick against the ground truth of a simulated bin: did the gripper land on a real
/// grasp of a real instance, and did it (on its way there) touch any other instance or the bin?

#include "core/grasp/BinBox.h"
#include "core/grasp/Gripper.h"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::grasp {

/// One instance as it truly is (scene frame, mm).
struct TruthInstance {
  int id = 0;
  /// Every tool pose that truly grasps it: each grasp point of the part at the instance's true
  /// pose, under each of the part's symmetries (the scan cannot tell them apart, and each is as
  /// good a grasp).
  std::vector<Eigen::Isometry3d> T_scene_tool;
  /// Points on its true surface, about one per mm² (sampled mesh), scene frame.
  std::vector<Eigen::Vector3d> surface_mm;
  Eigen::AlignedBox3d bounds_mm; ///< bounds of surface_mm
};

/// Tolerances of judgePick.
struct PickJudgeParams {
  double position_tol_mm = 3.0;  ///< the tool centre point within this of a true grasp
  double approach_tol_deg = 5.0; ///< the approach (tool z) within this of the true grasp's
  /// The straight approach path the solids are swept along (GraspPlanParams::approach_length_mm).
  double approach_length_mm = 100.0;
  /// Surface points of another instance inside the swept solids that make a collision (> this).
  int max_collision_points = 0;
  double bin_sample_mm = 2.0; ///< spacing of the solids' surface points tested on the bin
};

/// The verdict on one pick.
struct PickVerdict {
  int instance = -1; ///< the instance the grasp lands on (nearest true grasp); -1: none
  double position_error_mm = 0.0; ///< to the nearest true grasp (of `instance` when one)
  double approach_error_deg = 0.0;
  bool wrong = false; ///< no true grasp within the tolerances
  /// What the gripper hits: "finger +x hits instance 3 (41 points)", "body hits the bin wall +x".
  std::vector<std::string> collisions;
  [[nodiscard]] bool success() const { return !wrong && collisions.empty(); }
};

/// Judges a pick at T_scene_tool (tool frame as Gripper.h) made with `gripper`: it lands on the
/// instance with a true grasp within the tolerances (the nearest by position among those); it is
/// wrong when there is none. Every solid, swept along the approach, is then checked against the
/// surface points of every other instance (all of them when the pick is wrong) and, when `bin`
/// is given, against the bin's floor and walls (binCollision, its surface sampled). The picked
/// instance itself is not checked: the gripper is meant to touch it, and a part's grip point may
/// lie inside it (a pipe's axis). Pure and deterministic.
PickVerdict judgePick(const Eigen::Isometry3d& T_scene_tool, const Gripper& gripper,
                      const std::vector<TruthInstance>& instances, const std::optional<BinBox>& bin,
                      const PickJudgeParams& params = {});

} // namespace scanpick::core::grasp
