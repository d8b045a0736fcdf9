#include "core/features/FeatureExtraction.h"

#include "core/cloud/PointCloud.h"
#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/features/GridRadiusSearch.h"
#include "core/features/Ransac.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/mlesac.h>
#include <pcl/sample_consensus/prosac.h>
#include <pcl/sample_consensus/sac_model_circle3d.h>
#include <pcl/sample_consensus/sac_model_line.h>
#include <random>
#include <string>
#include <tbb/parallel_invoke.h>

namespace scanpick::core {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
constexpr double kTwoPi = 6.283185307179586;
/// Most keypoints a RANSAC search scores its trials on (see extractFeatures).
constexpr std::size_t kMaxSearchPoints = 3000;

/// Whether a point lies within the threshold of a line (PCL's coefficients: point, direction),
/// |(origin − p) × direction|² as PCL's line model computes it, in the order in which Eigen
/// evaluates `(origin - p).cross(direction).squaredNorm()` for 3 floats.
class NearLine {
public:
  using Scalar = float;
  using Tally = std::size_t; // an inlier count the compiler's vectorized loop can keep
  NearLine(const Eigen::VectorXf& c, double threshold)
      : m_origin(c.head<3>()), m_along(c.tail<3>().normalized()),
        m_threshold_sq(static_cast<float>(threshold * threshold)) {}
  [[gnu::always_inline]] bool operator()(float x, float y, float z) const {
    const float dx = m_origin.x() - x, dy = m_origin.y() - y, dz = m_origin.z() - z;
    const float cx = dy * m_along.z() - dz * m_along.y();
    const float cy = dz * m_along.x() - dx * m_along.z();
    const float cz = dx * m_along.y() - dy * m_along.x();
    return cx * cx + (cy * cy + cz * cz) < m_threshold_sq; // Eigen's squaredNorm of 3 floats
  }

private:
  Eigen::Vector3f m_origin, m_along;
  float m_threshold_sq;
};

/// Whether a point lies within the threshold of a circle (centre, radius, normal): at height h
/// above its plane and ρ from its axis, a point lies √(h² + (ρ − r)²) from it, without the
/// nearest circle point that PCL computes first.
class NearCircle {
public:
  using Scalar = double; // the points exactly, in the precision of the test
  // GCC 12 vectorizes comparisons of doubles into a sum of doubles (exact below 2^53), not into
  // an integer one; with -fno-math-errno for the square root (core/features/CMakeLists.txt).
  using Tally = double;
  NearCircle(const Eigen::VectorXf& c, double threshold)
      : m_centre(c.head<3>().cast<double>()), m_normal(c.tail<3>().cast<double>().normalized()),
        m_radius(c[3]), m_threshold_sq(threshold * threshold) {}
  [[gnu::always_inline]] bool operator()(double x, double y, double z) const {
    const double dx = x - m_centre.x(), dy = y - m_centre.y(), dz = z - m_centre.z();
    // Eigen's order for 3 doubles (dot, squaredNorm), so the same inliers as with Eigen.
    const double h = dx * m_normal.x() + dy * m_normal.y() + dz * m_normal.z();
    const double rho = std::sqrt(std::max(0.0, dx * dx + dy * dy + dz * dz - h * h));
    return h * h + (rho - m_radius) * (rho - m_radius) < m_threshold_sq;
  }

private:
  Eigen::Vector3d m_centre, m_normal;
  double m_radius, m_threshold_sq;
};

/// Inlier counts over points laid out one coordinate per array. The loop vectorizes; on a
/// processor with AVX2 a clone with twice the lanes runs (the same operations, no fused
/// multiply-add, so the same counts).
template <typename Near>
[[gnu::always_inline]] inline std::size_t
countNear(const Near& near, const typename Near::Scalar* x, const typename Near::Scalar* y,
          const typename Near::Scalar* z, std::size_t n) {
  typename Near::Tally count = 0;
  for (std::size_t k = 0; k < n; ++k)
    count += near(x[k], y[k], z[k]) ? typename Near::Tally(1) : typename Near::Tally(0);
  return static_cast<std::size_t>(count);
}
[[gnu::target_clones("avx2", "default")]] std::size_t
countNear(const NearLine& near, const float* x, const float* y, const float* z, std::size_t n) {
  return countNear<NearLine>(near, x, y, z, n);
}
[[gnu::target_clones("avx2", "default")]] std::size_t countNear(const NearCircle& near,
                                                                const double* x, const double* y,
                                                                const double* z, std::size_t n) {
  return countNear<NearCircle>(near, x, y, z, n);
}

/// A PCL model seeded by us (PCL seeds its samplers with a constant) whose inliers are counted and
/// selected by `Near`. Every RANSAC trial counts its inliers, and PCL's own loops for that took
/// two thirds of feature extraction (perf). These compute the same distances over a copy of the
/// model's points laid out one coordinate per array, a loop the compiler vectorizes.
template <typename Model, typename Near> class SeededModel : public Model {
public:
  SeededModel(const typename Model::PointCloudConstPtr& cloud, const pcl::Indices& indices)
      : Model(cloud, indices) {
    m_x.reserve(indices.size());
    m_y.reserve(indices.size());
    m_z.reserve(indices.size());
    for (const pcl::index_t i : indices) {
      const pcl::PointXYZ& p = (*cloud)[static_cast<std::size_t>(i)];
      m_x.push_back(p.x);
      m_y.push_back(p.y);
      m_z.push_back(p.z);
    }
  }
  void seed(std::uint64_t s) { this->rng_alg_.seed(static_cast<unsigned>(s ^ (s >> 32))); }
  /// Whether `c` is a model PCL accepts (coefficient count, radius limits).
  [[nodiscard]] bool valid(const Eigen::VectorXf& c) const { return this->isModelValid(c); }
  std::size_t countWithinDistance(const Eigen::VectorXf& c, double threshold) const override {
    if (!this->isModelValid(c))
      return 0;
    return countNear(Near(c, threshold), m_x.data(), m_y.data(), m_z.data(), m_x.size());
  }
  void selectWithinDistance(const Eigen::VectorXf& c, double threshold,
                            pcl::Indices& inliers) override {
    inliers.clear();
    if (!this->isModelValid(c))
      return;
    const Near near(c, threshold);
    for (std::size_t k = 0; k < m_x.size(); ++k)
      if (near(m_x[k], m_y[k], m_z[k]))
        inliers.push_back((*this->indices_)[k]);
  }

private:
  // The points of the model's indices, in their order.
  std::vector<typename Near::Scalar> m_x, m_y, m_z;
};
using LineModel = SeededModel<pcl::SampleConsensusModelLine<pcl::PointXYZ>, NearLine>;
using CircleModel = SeededModel<pcl::SampleConsensusModelCircle3D<pcl::PointXYZ>, NearCircle>;

/// The keypoints not yet in a feature, in ascending order, with their coordinates one per array.
struct Remaining {
  std::vector<int> ids;
  std::vector<float> x, y, z;

  void push_back(int id, const pcl::PointXYZ& p) {
    ids.push_back(id);
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
  }
  [[nodiscard]] std::size_t size() const { return ids.size(); }
  /// Drops `sorted` (a sorted subset of the ids).
  void remove(const std::vector<int>& sorted) {
    std::size_t kept = 0;
    auto drop = sorted.begin();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      while (drop != sorted.end() && *drop < ids[k])
        ++drop;
      if (drop != sorted.end() && *drop == ids[k])
        continue;
      ids[kept] = ids[k];
      x[kept] = x[k];
      y[kept] = y[k];
      z[kept] = z[k];
      ++kept;
    }
    for (auto* v : {&x, &y, &z})
      v->resize(kept);
    ids.resize(kept);
  }
};

/// Flags (1 or 0) of the points within `near`, in a loop that vectorizes as countNear's does.
template <typename Near>
[[gnu::always_inline]] inline void flagNear(const Near& near, const float* x, const float* y,
                                            const float* z, std::size_t n, std::uint8_t* flags) {
  using Scalar = typename Near::Scalar;
  for (std::size_t k = 0; k < n; ++k)
    flags[k] = near(static_cast<Scalar>(x[k]), static_cast<Scalar>(y[k]), static_cast<Scalar>(z[k]))
                   ? 1
                   : 0;
}
[[gnu::target_clones("avx2", "default")]] void flagNear(const NearLine& near, const Remaining& r,
                                                        std::uint8_t* flags) {
  flagNear(near, r.x.data(), r.y.data(), r.z.data(), r.size(), flags);
}
[[gnu::target_clones("avx2", "default")]] void flagNear(const NearCircle& near, const Remaining& r,
                                                        std::uint8_t* flags) {
  flagNear(near, r.x.data(), r.y.data(), r.z.data(), r.size(), flags);
}

/// The remaining keypoints (in their order) within the threshold of `model`'s coefficients `c`,
/// as a SeededModel over them selects them: the winner of a round is checked against every
/// remaining keypoint once or twice, and a model built over them all each round cost a tenth of
/// feature extraction (perf).
template <typename Near, typename Model>
pcl::Indices selectNear(const Model& model, const Remaining& remaining, const Eigen::VectorXf& c,
                        double threshold) {
  pcl::Indices inliers;
  if (!model.valid(c))
    return inliers;
  std::vector<std::uint8_t> flags(remaining.size());
  flagNear(Near(c, threshold), remaining, flags.data());
  for (std::size_t k = 0; k < flags.size(); ++k)
    if (flags[k])
      inliers.push_back(remaining.ids[k]);
  return inliers;
}

using SearchPtr = pcl::search::Search<pcl::PointXYZ>::Ptr;

std::uint64_t mix(std::uint64_t x) { // splitmix64
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Runs the chosen estimator on `model` (whose indices are the candidates); false if no model.
bool runEstimator(const pcl::SampleConsensusModel<pcl::PointXYZ>::Ptr& model,
                  const FeatureParams& params, double threshold, Eigen::VectorXf& coefficients) {
  std::unique_ptr<pcl::SampleConsensus<pcl::PointXYZ>> sac;
  switch (params.estimator) {
  case FeatureParams::Estimator::Ransac:
    return ransacModel(*model, threshold, std::max(1, params.max_iterations), coefficients) &&
           coefficients.allFinite();
  case FeatureParams::Estimator::Mlesac:
    sac = std::make_unique<pcl::MaximumLikelihoodSampleConsensus<pcl::PointXYZ>>(model, threshold);
    break;
  case FeatureParams::Estimator::Prosac:
    sac = std::make_unique<pcl::ProgressiveSampleConsensus<pcl::PointXYZ>>(model, threshold);
    break;
  }
  sac->setMaxIterations(std::max(1, params.max_iterations));
  if (!sac->computeModel())
    return false;
  sac->getModelCoefficients(coefficients);
  return coefficients.allFinite();
}

/// Largest run of `values` (sorted along with `ids`) without a step larger than `gap`;
/// `period` > 0 makes the values circular. Returns the run's ids.
std::vector<int> largestRun(std::vector<std::pair<double, int>> values, double gap, double period) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  std::vector<std::size_t> cuts; // run starts
  for (std::size_t i = 1; i < n; ++i)
    if (values[i].first - values[i - 1].first > gap)
      cuts.push_back(i);
  const bool wraps =
      period > 0 && n > 1 && values.front().first + period - values.back().first <= gap;
  if (cuts.empty()) {
    std::vector<int> ids;
    for (const auto& v : values)
      ids.push_back(v.second);
    std::sort(ids.begin(), ids.end());
    return ids;
  }
  // Runs [cuts[k], cuts[k+1]); with wrap-around the last and first runs are one.
  std::size_t best_start = 0, best_len = 0;
  const std::size_t runs = cuts.size() + (wraps ? 0 : 1);
  for (std::size_t k = 0; k < runs; ++k) {
    std::size_t start, len;
    if (wraps) {
      start = cuts[k];
      const std::size_t end = cuts[(k + 1) % cuts.size()];
      len = (end + n - start) % n;
      if (len == 0)
        len = n;
    } else {
      start = k == 0 ? 0 : cuts[k - 1];
      len = (k < cuts.size() ? cuts[k] : n) - start;
    }
    if (len > best_len) {
      best_len = len;
      best_start = start;
    }
  }
  std::vector<int> ids;
  for (std::size_t k = 0; k < best_len; ++k)
    ids.push_back(values[(best_start + k) % n].second);
  std::sort(ids.begin(), ids.end());
  return ids;
}

struct Candidate {
  Feature feature;
  std::vector<int> inliers;
};

std::optional<Candidate> bestLine(const Cloud::Ptr& cloud, const std::vector<int>& sample,
                                  const Remaining& remaining, const FeatureParams& params,
                                  double gap, std::uint64_t seed, const SearchPtr& near) {
  auto search = std::make_shared<LineModel>(cloud, pcl::Indices(sample.begin(), sample.end()));
  search->seed(seed);
  if (near)
    search->setSamplesMaxDist(params.sample_radius_mm, near);
  Eigen::VectorXf c;
  if (!runEstimator(search, params, params.line_threshold_mm, c))
    return std::nullopt;
  // Inliers and refinement over every remaining keypoint, not only the search sample (PCL's
  // refinement reads the cloud at the inliers given, whatever the model's own indices).
  const auto select = [&] {
    return selectNear<NearLine>(*search, remaining, c, params.line_threshold_mm);
  };
  pcl::Indices inliers = select();
  if (inliers.size() < 2)
    return std::nullopt;
  Eigen::VectorXf refined;
  search->optimizeModelCoefficients(inliers, c, refined);
  if (refined.size() == 6 && refined.allFinite() && refined.tail<3>().norm() > 0) {
    c = refined;
    inliers = select();
  }
  const Eigen::Vector3f origin = c.head<3>(), axis = c.tail<3>().normalized();
  std::vector<std::pair<double, int>> along;
  for (int i : inliers)
    along.emplace_back(static_cast<double>(axis.dot(
                           (*cloud)[static_cast<std::size_t>(i)].getVector3fMap() - origin)),
                       i);
  Candidate out;
  out.inliers = largestRun(std::move(along), gap, 0.0);
  if (out.inliers.size() >= 2) { // the run's own axis, not the one pulled by other runs
    pcl::Indices run(out.inliers.begin(), out.inliers.end());
    search->optimizeModelCoefficients(run, c, refined);
    if (refined.size() == 6 && refined.allFinite() && refined.tail<3>().norm() > 0)
      c = refined;
  }
  const Eigen::Vector3f o = c.head<3>(), d = c.tail<3>().normalized();
  float lo = std::numeric_limits<float>::max(), hi = -lo;
  for (int i : out.inliers) {
    const float t = d.dot((*cloud)[static_cast<std::size_t>(i)].getVector3fMap() - o);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  out.feature.type = FeatureType::Line;
  out.feature.centre_mm = o + d * (0.5f * (lo + hi));
  out.feature.direction = d;
  out.feature.size_mm = hi - lo;
  out.feature.inlier_count = static_cast<int>(out.inliers.size());
  return out;
}

bool circleValid(const Eigen::VectorXf& c, const FeatureParams& params) {
  return c.size() == 7 && c.allFinite() && c[3] >= params.min_circle_radius_mm &&
         c[3] <= params.max_circle_radius_mm && c.tail<3>().norm() > 0;
}

std::optional<Candidate> bestCircle(const Cloud::Ptr& cloud, const std::vector<int>& sample,
                                    const Remaining& remaining, const FeatureParams& params,
                                    double gap, std::uint64_t seed, const SearchPtr& near) {
  auto search = std::make_shared<CircleModel>(cloud, pcl::Indices(sample.begin(), sample.end()));
  search->seed(seed);
  if (near)
    search->setSamplesMaxDist(params.sample_radius_mm, near);
  search->setRadiusLimits(params.min_circle_radius_mm, params.max_circle_radius_mm);
  Eigen::VectorXf c;
  if (!runEstimator(search, params, params.circle_threshold_mm, c) || !circleValid(c, params))
    return std::nullopt;
  const auto select = [&] {
    return selectNear<NearCircle>(*search, remaining, c, params.circle_threshold_mm);
  };
  pcl::Indices inliers = select();
  if (inliers.size() < 3)
    return std::nullopt;
  Eigen::VectorXf refined;
  search->optimizeModelCoefficients(inliers, c, refined);
  if (circleValid(refined, params)) {
    c = refined;
    inliers = select();
  }
  // Angles in the circle's plane; the run gap is measured along the arc.
  const Eigen::Vector3f centre = c.head<3>(), normal = c.tail<3>().normalized();
  const Eigen::Vector3f u = normal.unitOrthogonal(), v = normal.cross(u);
  const double radius = c[3];
  std::vector<std::pair<double, int>> around;
  for (int i : inliers) {
    const Eigen::Vector3f d = (*cloud)[static_cast<std::size_t>(i)].getVector3fMap() - centre;
    around.emplace_back(
        radius * std::atan2(static_cast<double>(d.dot(v)), static_cast<double>(d.dot(u))), i);
  }
  Candidate out;
  out.inliers = largestRun(std::move(around), gap, kTwoPi * radius);
  if (out.inliers.size() < 3)
    return std::nullopt;
  if (out.inliers.size() < inliers.size()) {
    pcl::Indices run(out.inliers.begin(), out.inliers.end());
    search->optimizeModelCoefficients(run, c, refined);
    if (circleValid(refined, params))
      c = refined;
  }
  out.feature.type = FeatureType::Circle;
  out.feature.centre_mm = c.head<3>();
  out.feature.direction = c.tail<3>().normalized();
  out.feature.size_mm = c[3];
  out.feature.inlier_count = static_cast<int>(out.inliers.size());
  return out;
}

/// Median distance from a keypoint to its nearest other keypoint.
double medianSpacing(const Cloud::Ptr& cloud) {
  if (cloud->size() < 2)
    return 0.0;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<float> spacing;
  pcl::Indices ids(2);
  std::vector<float> dist(2);
  const std::size_t step = std::max<std::size_t>(1, cloud->size() / 2000);
  for (std::size_t i = 0; i < cloud->size(); i += step)
    if (tree.nearestKSearch((*cloud)[i], 2, ids, dist) == 2)
      spacing.push_back(std::sqrt(dist[1]));
  if (spacing.empty())
    return 0.0;
  std::nth_element(spacing.begin(), spacing.begin() + static_cast<long>(spacing.size() / 2),
                   spacing.end());
  return spacing[spacing.size() / 2];
}

/// Throws Error for thresholds that are not positive or circle radius limits in the wrong order.
void checkFeatureParams(const FeatureParams& params) {
  if (!(params.line_threshold_mm > 0) || !(params.circle_threshold_mm > 0))
    throw Error("feature extraction needs positive RANSAC thresholds (features.line_threshold_mm, "
                "features.circle_threshold_mm)");
  if (params.min_circle_radius_mm > params.max_circle_radius_mm)
    throw Error("the minimum circle radius is larger than the maximum: check "
                "features.min_circle_radius_mm and features.max_circle_radius_mm");
}

/// The valid keypoints as a cloud, all of them remaining, and the caller's index of each.
struct ValidKeypoints {
  std::shared_ptr<Cloud> cloud = std::make_shared<Cloud>();
  Remaining remaining;
  std::vector<int> original; ///< from the cloud (valid keypoints only) to the caller's indices
};

ValidKeypoints validKeypoints(const std::vector<Eigen::Vector3f>& keypoints_mm) {
  ValidKeypoints valid;
  Cloud& cloud = *valid.cloud;
  for (std::size_t i = 0; i < keypoints_mm.size(); ++i)
    if (isValid(keypoints_mm[i])) {
      cloud.push_back(pcl::PointXYZ(keypoints_mm[i].x(), keypoints_mm[i].y(), keypoints_mm[i].z()));
      valid.remaining.push_back(static_cast<int>(cloud.size() - 1), cloud.back());
    }
  for (std::size_t i = 0; i < keypoints_mm.size(); ++i)
    if (isValid(keypoints_mm[i]))
      valid.original.push_back(static_cast<int>(i));
  return valid;
}

/// The keypoints a round's RANSAC searches score their trials on, drawn from the remaining ones
/// with `round_seed`.
std::vector<int> searchSample(const Remaining& remaining, const FeatureParams& params,
                              std::uint64_t round_seed) {
  // PROSAC draws from a growing prefix; without a quality order a seeded shuffle keeps it fair.
  std::vector<int> candidates = remaining.ids;
  if (params.estimator == FeatureParams::Estimator::Prosac) {
    std::mt19937_64 rng(round_seed);
    std::shuffle(candidates.begin(), candidates.end(), rng);
  }
  // Each RANSAC trial counts its inliers over the candidates, so a large object (or a whole
  // Kinect scene) with tens of thousands of keypoints cost trials x keypoints per round. The
  // trials are therefore scored on a seeded sample of at most kMaxSearchPoints keypoints; the
  // winner's inliers are then selected among all remaining keypoints. Below the bound this is
  // exactly the thesis's search.
  if (candidates.size() > kMaxSearchPoints) {
    std::mt19937_64 rng(mix(round_seed + 3));
    std::vector<int> sample;
    sample.reserve(kMaxSearchPoints);
    std::sample(candidates.begin(), candidates.end(), std::back_inserter(sample), kMaxSearchPoints,
                rng);
    candidates.swap(sample);
  }
  return candidates;
}

/// The round's winner: the line or the circle with at least `min_support` inliers, the circle
/// when it has more than the line; null when neither qualifies.
Candidate* roundWinner(std::optional<Candidate>& line, std::optional<Candidate>& circle,
                       std::size_t min_support) {
  Candidate* best = nullptr;
  if (line && line->inliers.size() >= min_support)
    best = &*line;
  if (circle && circle->inliers.size() >= min_support &&
      (!best || circle->inliers.size() > best->inliers.size()))
    best = &*circle;
  return best;
}

} // namespace

FeatureExtraction extractFeatures(const std::vector<Eigen::Vector3f>& keypoints_mm,
                                  const FeatureParams& params, std::uint64_t seed,
                                  const ProgressFn& progress) {
  checkFeatureParams(params);
  logger(); // PCL's console verbosity follows scanpick's log level (core/common/Log.h)
  FeatureExtraction result;
  ValidKeypoints valid = validKeypoints(keypoints_mm);
  const std::shared_ptr<Cloud>& cloud = valid.cloud;
  Remaining& remaining = valid.remaining;
  const std::size_t total = remaining.size();
  const double spacing = params.run_gap_mm > 0 ? 0.0 : medianSpacing(cloud);
  const auto autoGap = [&](double threshold) {
    return params.run_gap_mm > 0 ? params.run_gap_mm : std::max(3.0 * threshold, 4.0 * spacing);
  };
  const double line_gap = autoGap(params.line_threshold_mm);
  const double circle_gap = autoGap(params.circle_threshold_mm);
  const std::size_t min_support = static_cast<std::size_t>(std::max(2, params.ransac_size));

  // One grid over all keypoints; each round lays out its candidates on it.
  const auto grid = params.sample_radius_mm > 0
                        ? std::make_shared<GridRadiusSearch>(params.sample_radius_mm)
                        : nullptr;
  const SearchPtr near = grid;
  for (int round = 0; round < params.max_features; ++round) {
    reportProgress(progress,
                   total ? 1.0 - static_cast<double>(remaining.size()) / static_cast<double>(total)
                         : 1.0);
    if (remaining.size() < min_support)
      break;
    const std::uint64_t round_seed = mix(seed ^ mix(static_cast<std::uint64_t>(round)));
    const std::vector<int> candidates = searchSample(remaining, params, round_seed);
    // Localized sampling: the sample's other points come from the candidates near its first.
    if (grid) {
      auto ids = std::make_shared<pcl::Indices>(candidates.begin(), candidates.end());
      if (round == 0)
        grid->setInputCloud(cloud, ids);
      else
        grid->setIndices(ids);
    }
    // The two searches are independent (own models and seeds): run them side by side.
    std::optional<Candidate> line, circle;
    tbb::parallel_invoke(
        [&] {
          if (params.lines && candidates.size() >= 2)
            line =
                bestLine(cloud, candidates, remaining, params, line_gap, mix(round_seed + 1), near);
        },
        [&] {
          if (params.circles && candidates.size() >= 3)
            circle = bestCircle(cloud, candidates, remaining, params, circle_gap,
                                mix(round_seed + 2), near);
        });
    Candidate* accepted = roundWinner(line, circle, min_support);
    if (!accepted)
      break;
    remaining.remove(accepted->inliers);
    for (int& i : accepted->inliers)
      i = valid.original[static_cast<std::size_t>(i)];
    result.features.push_back(accepted->feature);
    result.inliers.push_back(std::move(accepted->inliers));
  }
  reportProgress(progress, 1.0);
  return result;
}

} // namespace scanpick::core
