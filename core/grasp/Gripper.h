#pragma once
/// @file Gripper.h
/// The gripper as simple solids in the tool frame: a suction cup or a parallel two-finger
/// gripper, plus the flange / tool body behind it.
///
/// The tool frame: origin at the tool centre point (TCP), which is put on the grip point; +z is
/// the approach direction (from the robot towards the part); for fingers, +x is the closing axis
/// (the fingers move along ±x). The gripper lies behind the TCP (z <= 0), except for fingertips
/// that reach past the grip point by ParallelGripper::grip_depth_mm.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scanpick::core::grasp {

/// Kind of solid.
enum class SolidShape {
  Box,      ///< axis-aligned box in the tool frame
  Cylinder, ///< cylinder whose axis is the tool z axis direction
};

/// One solid of the gripper, in the tool frame (mm).
struct ToolSolid {
  std::string name; ///< named in rejection reasons ("cup", "flange", "finger +x", ...)
  SolidShape shape = SolidShape::Box;
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero(); ///< tool frame
  /// Box: half sizes along tool x, y, z. Cylinder: (radius, radius, half length along z).
  Eigen::Vector3d half_extents_mm = Eigen::Vector3d::Zero();
  /// False for the region between open fingers, where the part itself belongs: only other
  /// points count there. True for solids that must not touch the picked part either (fingers).
  bool checks_part = false;
  bool operator==(const ToolSolid&) const = default;
};

/// A suction cup on the tool axis: a cylinder from the TCP back to z = -stroke_mm.
struct SuctionCup {
  double diameter_mm = 30.0; ///< outer diameter of the cup (mm), > 0
  double stroke_mm = 15.0;   ///< cup and bellows length along the approach (mm), > 0
  bool operator==(const SuctionCup&) const = default;
};

/// A parallel two-finger gripper: two box fingers at ±x, open by opening_mm between their inner
/// faces, reaching grip_depth_mm past the grip point along the approach.
struct ParallelGripper {
  double finger_thickness_mm = 10.0; ///< along the closing axis (x), > 0
  double finger_width_mm = 20.0;     ///< across (y), > 0
  double finger_length_mm = 50.0;    ///< along the approach (z), > 0
  double opening_mm = 60.0;          ///< distance between the open fingers' inner faces, > 0
  /// How far the fingertips reach past the grip point along the approach (mm), >= 0; the grip
  /// point is then between the fingers, grip_depth_mm above their tips.
  double grip_depth_mm = 10.0;
  bool operator==(const ParallelGripper&) const = default;
};

/// Kind of gripper.
enum class GripperKind { Suction, Fingers };

/// The flange / tool body behind the cup or the fingers: a cylinder (diameter x length) or a box
/// (width x, depth y, length z), on the tool axis, starting where the cup or fingers end.
struct ToolBody {
  SolidShape shape = SolidShape::Cylinder;
  double diameter_mm = 63.0; ///< cylinder diameter; box size along x (mm), > 0
  double depth_mm = 63.0;    ///< box size along y (mm); unused for a cylinder
  double length_mm = 80.0;   ///< along the approach (mm), >= 0 (0: no body)
  bool operator==(const ToolBody&) const = default;
};

/// A gripper: the kind, its dimensions and its body. Defaults: a 30 mm suction cup with 15 mm
/// stroke on a 63 mm x 80 mm flange.
struct Gripper {
  GripperKind kind = GripperKind::Suction;
  SuctionCup suction;
  ParallelGripper fingers;
  ToolBody body;
  bool operator==(const Gripper&) const = default;
};

/// The gripper's solids in the tool frame: cup (suction) or "finger +x", "finger -x" and the
/// "closing region" between them (fingers), then "body". Throws Error for a non-positive or
/// non-finite dimension, naming it.
std::vector<ToolSolid> toolSolids(const Gripper& gripper);

/// Name of a gripper kind ("suction", "fingers") and back; parseGripperKind throws Error for
/// another name.
const char* toString(GripperKind kind);
GripperKind parseGripperKind(const std::string& name);

} // namespace scanpick::core::grasp
