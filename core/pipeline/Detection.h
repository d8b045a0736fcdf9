#pragma once
/// @file Detection.h
/// What recognition reports for each found instance of the taught part.

#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

namespace scanpick::core {

/// A named point on the part where a gripper may take it (millimetres).
struct GripPoint {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  bool operator==(const GripPoint&) const = default;
};

/// One recognized instance.
struct Detection {
  /// Maps model coordinates (the taught model's frame, mm) into the scene frame (mm).
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  double score = 0.0;  ///< share of model features confirmed in the scene, [0, 1]
  /// Matched (model feature index, scene feature index) pairs behind the pose.
  std::vector<std::pair<int, int>> matched_features;
  std::vector<GripPoint> grip_points_scene;  ///< the model's grip points mapped into the scene
  int cluster = -1;                          ///< scene cluster it was found in (-1: whole scene)
};

} // namespace scanpick::core
