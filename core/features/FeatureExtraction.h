#pragma once
/// @file FeatureExtraction.h
/// Second-level features (thesis §3.1-3.2): lines and circles found among first-level keypoints
/// by repeated sample consensus, each collapsed to one described feature.

#include "core/common/Progress.h"
#include "core/features/Feature.h"
#include "core/params/Parameters.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace scanpick::core {

/// The features of one keypoint set and the keypoints behind each.
struct FeatureExtraction {
  FeatureList features;                  ///< in acceptance order (larger support first, roughly)
  std::vector<std::vector<int>> inliers; ///< per feature: keypoint indices, ascending
};

/// Repeatedly searches the best line and the best circle among the keypoints not used yet
/// (PCL's line and 3D-circle models with RANSAC, MLESAC or PROSAC per `params.estimator`,
/// at most `params.max_iterations` trials each) and accepts the one with more inliers if it has
/// at least `params.ransac_size`; its inliers are then used up. Stops when neither qualifies or
/// after `params.max_features` features.
///
/// Beyond the thesis (its §3.3 names the problem): a line's inliers are cut where consecutive
/// ones along the line are farther apart than the run gap (`params.run_gap_mm`, or automatic),
/// and only the largest connected run is kept, so collinear edges of separate objects give
/// separate lines with their real lengths; circles are cut the same way along the arc.
/// Lines: centre = midpoint of the extreme inliers, direction = unit axis, size = length.
/// Circles: least-squares refined centre, unit normal, radius; radii outside
/// [min_circle_radius_mm, max_circle_radius_mm] are never accepted.
/// Each search scores its trials on at most 3000 of the remaining keypoints (a seeded sample;
/// all of them below that) and then selects the winner's inliers among all remaining keypoints,
/// which bounds the cost of large objects and whole Kinect scenes.
/// Same keypoints, parameters and `seed` give the same features. Throws Error for non-positive
/// thresholds or an inverted radius range, Cancelled when `progress` asks to stop.
FeatureExtraction extractFeatures(const std::vector<Eigen::Vector3f>& keypoints_mm,
                                  const FeatureParams& params, std::uint64_t seed,
                                  const ProgressFn& progress = {});

} // namespace scanpick::core
