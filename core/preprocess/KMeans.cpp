#include "core/preprocess/KMeans.h"

#include "core/common/Error.h"

#include <algorithm>
#include <limits>
#include <random>
#include <string>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

/// Parallel work is split into fixed chunks whose partial results are combined in chunk order,
/// so sums and arg-max ties never depend on thread scheduling.
constexpr std::size_t kChunk = 8192;

std::size_t chunkCount(std::size_t n) {
  return (n + kChunk - 1) / kChunk;
}

template <typename Body> void forEachChunk(std::size_t n, Body body) {
  tbb::parallel_for(std::size_t{0}, chunkCount(n),
                    [&](std::size_t c) { body(c, c * kChunk, std::min(n, (c + 1) * kChunk)); });
}

/// Lowers min_sq[i] with the distance to `centre`; returns the index of the largest min_sq
/// (lowest index on ties).
std::size_t updateAndFindFarthest(const std::vector<Eigen::Vector3f>& points,
                                  const Eigen::Vector3f& centre, std::vector<float>& min_sq) {
  std::vector<std::size_t> best(chunkCount(points.size()));
  forEachChunk(points.size(), [&](std::size_t c, std::size_t begin, std::size_t end) {
    std::size_t arg = begin;
    for (std::size_t i = begin; i < end; ++i) {
      min_sq[i] = std::min(min_sq[i], (points[i] - centre).squaredNorm());
      if (min_sq[i] > min_sq[arg])
        arg = i;
    }
    best[c] = arg;
  });
  std::size_t arg = best.front();
  for (std::size_t b : best)
    if (min_sq[b] > min_sq[arg])
      arg = b;
  return arg;
}

std::vector<Eigen::Vector3f> kmeansPlusPlus(const std::vector<Eigen::Vector3f>& points, int k,
                                            std::mt19937_64& rng) {
  std::vector<Eigen::Vector3f> centres;
  std::vector<float> min_sq(points.size(), std::numeric_limits<float>::max());
  centres.push_back(points[std::uniform_int_distribution<std::size_t>(0, points.size() - 1)(rng)]);
  while (static_cast<int>(centres.size()) < k) {
    updateAndFindFarthest(points, centres.back(), min_sq);
    double total = 0;
    for (float d : min_sq)
      total += d;
    if (total <= 0)
      break; // fewer distinct points than k
    double pick = std::uniform_real_distribution<double>(0.0, total)(rng);
    std::size_t chosen = points.size() - 1;
    for (std::size_t i = 0; i < points.size(); ++i) {
      pick -= min_sq[i];
      if (pick < 0) {
        chosen = i;
        break;
      }
    }
    centres.push_back(points[chosen]);
  }
  return centres;
}

/// Up to k initial centres (points, mm) chosen by `init`: farthest-first traversal seeded by one
/// draw from `rng`, or k-means++ drawing from `rng` directly.
std::vector<Eigen::Vector3f> initialCentres(const std::vector<Eigen::Vector3f>& points, int k,
                                            ClusteringParams::Init init, std::mt19937_64& rng) {
  if (init != ClusteringParams::Init::FarthestFirst)
    return kmeansPlusPlus(points, k, rng);
  std::vector<Eigen::Vector3f> centres;
  for (int i : farthestFirstTraversal(points, k, rng()))
    centres.push_back(points[static_cast<std::size_t>(i)]);
  return centres;
}

} // namespace

std::vector<int> farthestFirstTraversal(const std::vector<Eigen::Vector3f>& points, int k,
                                        std::uint64_t seed) {
  std::vector<int> picked;
  if (points.empty() || k <= 0)
    return picked;
  std::mt19937_64 rng(seed);
  std::size_t next = std::uniform_int_distribution<std::size_t>(0, points.size() - 1)(rng);
  std::vector<float> min_sq(points.size(), std::numeric_limits<float>::max());
  const auto count = std::min<std::size_t>(static_cast<std::size_t>(k), points.size());
  while (picked.size() < count) {
    picked.push_back(static_cast<int>(next));
    next = updateAndFindFarthest(points, points[next], min_sq);
    if (min_sq[next] <= 0 && picked.size() < count)
      break; // every remaining point coincides with a picked one
  }
  return picked;
}

KMeansResult kmeans(const std::vector<Eigen::Vector3f>& points, int k,
                    const ClusteringParams& params, std::uint64_t seed,
                    const ProgressFn& progress) {
  if (k < 1)
    throw Error("k-means needs at least one cluster, got k = " + std::to_string(k));
  KMeansResult result;
  if (points.empty())
    return result;
  std::mt19937_64 rng(seed);
  result.centres = initialCentres(points, k, params.init, rng);
  const std::size_t kc = result.centres.size(), chunks = chunkCount(points.size());

  struct Partial {
    std::vector<Eigen::Vector3d> sum;
    std::vector<double> sum_sq;
    std::vector<std::size_t> count;
  };
  std::vector<Partial> partial(chunks);
  std::vector<int> labels(points.size());
  double best_objective = std::numeric_limits<double>::infinity();
  const int max_iterations = std::max(1, params.max_iterations);
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    reportProgress(progress, static_cast<double>(iteration - 1) / max_iterations);
    const auto& centres = result.centres;
    // Partition (lowest centre index on ties) and per-chunk sums for the centroids.
    forEachChunk(points.size(), [&](std::size_t c, std::size_t begin, std::size_t end) {
      Partial& part = partial[c];
      part.sum.assign(kc, Eigen::Vector3d::Zero());
      part.sum_sq.assign(kc, 0.0);
      part.count.assign(kc, 0);
      for (std::size_t i = begin; i < end; ++i) {
        std::size_t best = 0;
        float best_sq = (points[i] - centres[0]).squaredNorm();
        for (std::size_t j = 1; j < kc; ++j) {
          const float d = (points[i] - centres[j]).squaredNorm();
          if (d < best_sq) {
            best_sq = d;
            best = j;
          }
        }
        labels[i] = static_cast<int>(best);
        const Eigen::Vector3d p = points[i].cast<double>();
        part.sum[best] += p;
        part.sum_sq[best] += p.squaredNorm();
        ++part.count[best];
      }
    });
    std::vector<Eigen::Vector3d> sum(kc, Eigen::Vector3d::Zero());
    std::vector<double> sum_sq(kc, 0.0);
    std::vector<std::size_t> count(kc, 0);
    for (const auto& part : partial)
      for (std::size_t j = 0; j < kc; ++j) {
        sum[j] += part.sum[j];
        sum_sq[j] += part.sum_sq[j];
        count[j] += part.count[j];
      }
    // Objective of the new partition with its own centroids: sum |p|^2 - |sum p|^2 / n per cluster.
    std::vector<Eigen::Vector3f> next = centres;
    double objective = 0;
    for (std::size_t j = 0; j < kc; ++j)
      if (count[j] > 0) {
        const double n = static_cast<double>(count[j]);
        next[j] = (sum[j] / n).cast<float>();
        objective += std::max(0.0, sum_sq[j] - sum[j].squaredNorm() / n);
      }
    result.iterations = iteration;
    if (!(objective < best_objective))
      break; // Algorithm 5: stop when the objective no longer decreases
    best_objective = objective;
    result.centres = std::move(next);
    result.labels = labels;
  }
  result.objective = best_objective;
  reportProgress(progress, 1.0);
  return result;
}

} // namespace scanpick::core
