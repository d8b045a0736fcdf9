#pragma once
/// @file ObjectCount.h
/// Algorithm 7 of the thesis: how many objects a scene holds, from its projection along the
/// lines of sight of the farther source (which closes most undercuts) and Euclidean clustering.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Progress.h"
#include "core/params/Parameters.h"

#include <Eigen/Core>
#include <vector>

namespace scanpick::core {

/// The object count and the projected clusters behind it.
struct ObjectCount {
  /// Clusters holding at least `count_min_points` points: they are `clusters[0 .. count)`.
  int count = 0;
  /// Every single-linkage cluster, largest first (ties: smallest first index), each one sorted.
  /// Entries are indices into the valid points of the input, i.e. into `source_indices`.
  std::vector<std::vector<int>> clusters;
  /// The projection of every valid point onto the plane z = centroid z, millimetres.
  std::vector<Eigen::Vector3f> projected_mm;
  /// For each valid point, its index in the input cloud.
  std::vector<int> source_indices;
};

/// Projects every valid point of `scene_mm` (camera frame) onto the plane z = centroid.z along
/// the line joining it to the farther of the camera and the projector of `sensor`, then groups
/// the projected points by single linkage with distance `params.count_radius_mm` (grid +
/// union-find, exact) and counts the clusters of at least `params.count_min_points` points.
/// A scene with no valid point gives count 0. Throws Error for an inconsistent cloud or a
/// non-positive radius, Cancelled when `progress` asks to stop.
ObjectCount countObjects(const PointCloud& scene_mm, const SensorModel& sensor,
                         const ClusteringParams& params, const ProgressFn& progress = {});

} // namespace scanpick::core
