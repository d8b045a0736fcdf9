#pragma once
/// @file RigidFit.h
/// Rotations between feature axes and the rigid transform that best maps matched model features
/// onto scene features (§3.4 "Rotation matrix computation").

#include "core/features/Feature.h"

#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace scanpick::core {

/// The smallest rotation taking unit vector `from` onto unit vector `to` (axis from × to, the
/// thesis's computeRotation). Antiparallel vectors turn by π about any axis perpendicular to them.
Eigen::Matrix3d rotationBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// Angle in [0, π/2] between two axes whose sign is arbitrary (line directions, circle normals).
double axisAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Least-squares rigid transform T_scene_model (Umeyama without scale) over matched pairs
/// (model index, scene index). Each pair contributes its centre and the two points at
/// ±arm along its axis (arm = circle radius or half the line length, at least 1 mm), so two pairs
/// already fix all six degrees of freedom unless both axes and the centres are collinear. The
/// sign of each scene axis is chosen to agree with `T_guess` (the transform predicted by the roll
/// search). This replaces the thesis's R = R1·R2 composition, which uses the second pair's
/// direction only and lets the first pair's errors pass into the pose unaveraged.
/// Returns T_guess unchanged when `pairs` is empty.
Eigen::Isometry3d fitFeaturePairs(const FeatureList& model, const FeatureList& scene,
                                  const std::vector<std::pair<int, int>>& pairs,
                                  const Eigen::Isometry3d& T_guess);

/// Beyond the thesis: Gauss-Newton refinement of T_scene_model on the matched features' geometry.
/// Circles pull their centre and axis onto the scene circle's; lines pull their axis and their
/// perpendicular position onto the scene line, while the position along the line (its centre,
/// which moves with occlusion and RANSAC's extreme inliers) keeps 5 % weight. Returns T_init
/// for fewer than two pairs; at most `iterations` steps (default 5).
Eigen::Isometry3d refineOnFeatureGeometry(const FeatureList& model, const FeatureList& scene,
                                          const std::vector<std::pair<int, int>>& pairs,
                                          const Eigen::Isometry3d& T_init, int iterations = 5);

} // namespace scanpick::core
