#pragma once
/// @file SceneSplit.h
/// The scene split of §3.3: one point cloud per object, so RANSAC never joins collinear edges
/// of different objects.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Progress.h"
#include "core/params/Parameters.h"
#include "core/preprocess/ObjectCount.h"

#include <cstdint>
#include <vector>

namespace scanpick::core {

/// A scene split into objects.
struct SceneSplit {
  /// One cloud per object, largest first. For an organized scene each object is the bounding
  /// pixel window of its points (other pixels NaN), so pixel neighbourhoods still work; for an
  /// unorganized scene it is the object's points. Channels follow their points.
  std::vector<PointCloud> objects;
  ObjectCount count;   ///< Algorithm 7's result (empty when clustering is disabled)
  int kmeans_runs = 0; ///< k-means runs (1 + re-runs after removing small clusters)
  /// For each point of the input, the object it went to, or -1 (invalid or removed as outlier).
  std::vector<int> point_labels;
};

/// Splits `scene_mm` (camera frame, floor already removed) into objects:
/// - `params.enabled == false`: one object, the whole scene;
/// - Method::KMeans (the thesis): count the objects (Algorithm 7), run k-means with k = count on
///   the 3D points, remove the points of clusters smaller than `min_cluster_points` and re-run
///   (at most 10 runs), one object per cluster;
/// - Method::ProjectedClusters: every counted cluster of Algorithm 7 is an object; smaller
///   fragments join the object whose projected point is nearest to the fragment's centroid.
/// A count of 0 gives no object. Deterministic for a given `seed`. Throws Error for an
/// inconsistent cloud, Cancelled when `progress` asks to stop.
SceneSplit splitIntoObjects(const PointCloud& scene_mm, const SensorModel& sensor,
                            const ClusteringParams& params, std::uint64_t seed,
                            const ProgressFn& progress = {});

} // namespace scanpick::core
