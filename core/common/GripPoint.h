#pragma once
/// @file GripPoint.h
/// A named grip point: where a gripper may take the part.

#include <Eigen/Core>
#include <string>

namespace scanpick::core {

/// A named point on the part where a gripper may take it (millimetres, in the frame the
/// containing object states: part, model or scene).
struct GripPoint {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  bool operator==(const GripPoint&) const = default;
};

} // namespace scanpick::core
