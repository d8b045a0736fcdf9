#pragma once
/// @file GripPoint.h
/// A named grip point: where a gripper may take the part, and optionally how it comes in.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace scanpick::core {

/// A named point on the part where a gripper may take it (millimetres, in the frame the
/// containing object states: part, model or scene), with the directions the operator taught for
/// it, in the same frame.
struct GripPoint {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  /// Unit direction the tool moves in to reach the point (towards and into the part). Unset: the
  /// recipe's grasp spec for this point decides, else the model's +z (the teach camera's view).
  std::optional<Eigen::Vector3d> approach = std::nullopt;
  /// Fingers: the unit axis they close along, perpendicular to `approach`. Unset: any axis.
  std::optional<Eigen::Vector3d> closing_axis = std::nullopt;
  bool operator==(const GripPoint&) const = default;
};

/// `grip` moved by `T` (its position transformed, its directions rotated).
GripPoint transformed(const GripPoint& grip, const Eigen::Isometry3d& T);

/// {"name", "position_mm": [x, y, z]} and, when taught, "approach" and "closing_axis" (the model
/// file's and the results file's grip points).
nlohmann::json gripToJson(const GripPoint& grip);

/// A unit direction from `v`. Throws Error "<what> must be a non-zero direction" for a zero or
/// non-finite vector.
Eigen::Vector3d unitDirection(const Eigen::Vector3d& v, const std::string& what);

/// The closing axis `closing` made unit and perpendicular to the unit `approach`. Throws Error for
/// a zero or non-finite axis, or one (nearly) along the approach, naming `grip`.
Eigen::Vector3d closingAcross(const Eigen::Vector3d& closing, const Eigen::Vector3d& approach,
                              const std::string& grip);

/// `grip` with its directions checked and made unit (the closing axis perpendicular to the
/// approach, which it needs). Throws Error as unitDirection and closingAcross, and for a closing
/// axis without an approach.
GripPoint checkedGrip(GripPoint grip);

} // namespace scanpick::core
