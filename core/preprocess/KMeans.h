#pragma once
/// @file KMeans.h
/// Centre-based clustering of §3.3: farthest-first traversal (Algorithm 4), Lloyd's k-means
/// (Algorithm 5) seeded by it or by k-means++.

#include "core/common/Progress.h"
#include "core/params/Parameters.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace scanpick::core {

/// Algorithm 4: picks a start point at random (from `seed`), then repeatedly the point farthest
/// from the points already picked. Returns min(k, points.size()) distinct indices in pick order.
/// Ties go to the lowest index, so the result depends only on the points, k and the seed.
std::vector<int> farthestFirstTraversal(const std::vector<Eigen::Vector3f>& points, int k,
                                        std::uint64_t seed);

/// A k-means partition.
struct KMeansResult {
  std::vector<int> labels;              ///< cluster of each point, in [0, centres.size())
  std::vector<Eigen::Vector3f> centres; ///< centroids, millimetres
  int iterations = 0;                   ///< Lloyd iterations run
  double objective = 0;                 ///< sum of squared distances to the centres, mm²
};

/// Algorithm 5 (Lloyd): initial centres by `params.init` (farthest-first traversal or k-means++,
/// both from `seed`), then partition / recompute centroids until the objective stops
/// decreasing, the partition stops changing or `params.max_iterations` is reached. An empty
/// cluster keeps its previous centre. k is clamped to the number of points; no point gives an
/// empty result. Deterministic (fixed-order parallel sums). Throws Error for k < 1.
KMeansResult kmeans(const std::vector<Eigen::Vector3f>& points, int k,
                    const ClusteringParams& params, std::uint64_t seed,
                    const ProgressFn& progress = {});

} // namespace scanpick::core
