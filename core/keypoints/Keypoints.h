#pragma once
/// @file Keypoints.h
/// First-level keypoints (thesis §3.1): edges by neighbourhood analysis (Algorithm 2) and
/// curvature peaks by normals gradient analysis (Algorithm 1).

#include "core/cloud/PointCloud.h"
#include "core/common/Progress.h"
#include "core/params/Parameters.h"

#include <Eigen/Core>
#include <vector>

namespace scanpick::core {

/// Keypoints of one cloud, ordered by source index.
struct Keypoints {
  std::vector<Eigen::Vector3f> points_mm; ///< keypoint positions (copies of input points), mm
  std::vector<int> source_indices;        ///< index of each keypoint in the input cloud
};

/// Algorithm 2: a valid point is a keypoint when the centroid of its neighbours within
/// `params.neighbourhood_radius_mm` (the point included) lies at least
/// `params.position_range_mm` away from it; a negative range keeps every valid point.
/// Organized clouds (camera frame) are searched on pixel windows sized from the radius and the
/// depth, others with a kd-tree; both give the exact radius neighbourhood. Deterministic.
/// Throws Error for an inconsistent cloud or a non-positive radius; Cancelled on request.
Keypoints neighbourhoodAnalysis(const PointCloud& cloud_mm, const KeypointParams& params,
                                const ProgressFn& progress = {});

/// Algorithm 1: from every point, walk to the neighbour (among the `params.gradient_neighbours`
/// nearest) whose normal turns most, while that largest turn keeps growing; the point where it
/// stops is a curvature peak and a keypoint (each peak once). A start point whose largest turn is
/// below `params.gradient_sensitivity_rad` is flat and gives nothing. Normals are the cloud's own
/// when every valid point has one, otherwise estimated by PCA of the neighbours within
/// `params.normal_radius_mm` and oriented towards the camera (the origin). Deterministic.
/// Throws Error for an inconsistent cloud or bad parameters; Cancelled on request.
Keypoints normalsGradientAnalysis(const PointCloud& cloud_mm, const KeypointParams& params,
                                  const ProgressFn& progress = {});

/// Runs the method of `params.method`; Both is the union of the two (each source index once),
/// the cooperation of the two extractors the thesis proposes as future work.
Keypoints extractKeypoints(const PointCloud& cloud_mm, const KeypointParams& params,
                           const ProgressFn& progress = {});

} // namespace scanpick::core
