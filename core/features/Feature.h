#pragma once
/// @file Feature.h
/// Second-level features (thesis §3.2): a RANSAC line or circle collapsed to one described point.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scanpick::core {

/// Kind of a second-level feature.
enum class FeatureType { Line, Circle };

/// "line" or "circle".
std::string toString(FeatureType type);

/// A line or circle found among first-level keypoints, described as in the thesis §3.2:
/// - line: centre = midpoint of its two extreme inliers, direction = unit axis (sign is arbitrary),
///   size = length between the extreme inliers;
/// - circle: centre, direction = unit normal of its plane (sign arbitrary), size = radius.
struct Feature {
  FeatureType type = FeatureType::Line;
  Eigen::Vector3f centre_mm = Eigen::Vector3f::Zero();
  Eigen::Vector3f direction = Eigen::Vector3f::UnitZ(); ///< unit vector
  float size_mm = 0.0f;                                 ///< line length or circle radius
  int inlier_count = 0;                                 ///< keypoints supporting it
  bool operator==(const Feature&) const = default;
};

/// The features of one cloud (model or scene cluster), in the cloud's frame.
using FeatureList = std::vector<Feature>;

} // namespace scanpick::core
