#include "core/refine/SceneIndex.h"

#include "core/cloud/PointKdTree.h"
#include "core/common/Error.h"
#include "core/common/PixelRows.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace scanpick::core {

namespace {

/// Keeps the single nearest point; starts with the caller's radius so the search prunes early.
class NearestResult {
public:
  explicit NearestResult(float max_distance_sq) : m_best(max_distance_sq) {}
  [[nodiscard]] std::size_t size() const { return m_index == kNone ? 0 : 1; }
  [[nodiscard]] bool full() const { return true; }
  bool addPoint(float distance_sq, std::uint32_t index) {
    // Equal distances keep the lower index, so the answer does not depend on the visiting order.
    if (distance_sq < m_best || (distance_sq == m_best && index < m_index)) {
      m_best = distance_sq;
      m_index = index;
    }
    return true;
  }
  [[nodiscard]] float worstDist() const { return m_best; }
  [[nodiscard]] std::uint32_t index() const { return m_index; }
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

private:
  float m_best;
  std::uint32_t m_index = kNone;
};

/// Unit normal of the best-fit plane of `points` (PCA), turned to face `viewpoint`; NaN for
/// fewer than 5 points or a degenerate (linear) neighbourhood.
template <typename Gather>
Eigen::Vector3f planeNormal(const Eigen::Vector3f& centre, const Eigen::Vector3d& viewpoint,
                            float& variation, Gather&& gather) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  int count = 0;
  // Offsets from the centre keep the covariance well conditioned far from the origin.
  const Eigen::Vector3d c = centre.cast<double>();
  gather([&](const Eigen::Vector3f& q) {
    const Eigen::Vector3d d = q.cast<double>() - c;
    sum += d;
    outer += d * d.transpose();
    ++count;
  });
  if (count < 5)
    return invalidPoint();
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d cov = outer / count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  // A neighbourhood that is a line (an edge of valid pixels) has no defined plane.
  if (!(eig.eigenvalues()(1) > 1e-3 * eig.eigenvalues()(2)))
    return invalidPoint();
  variation = static_cast<float>(eig.eigenvalues()(0) / std::max(1e-30, eig.eigenvalues().sum()));
  Eigen::Vector3d n = eig.eigenvectors().col(0).normalized();
  if (n.dot(viewpoint - c) < 0)
    n = -n;
  return n.cast<float>();
}

/// Runs body(begin, end) over [0, n) in blocks, reporting progress between blocks.
template <typename Body>
void blockedParallel(std::size_t n, const ProgressFn& progress, Body&& body) {
  constexpr std::size_t kBlock = 1 << 16;
  for (std::size_t start = 0; start < n; start += kBlock) {
    const std::size_t stop = std::min(n, start + kBlock);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(start, stop, 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
    reportProgress(progress, 0.1 + 0.9 * static_cast<double>(stop) / static_cast<double>(n));
  }
}

/// SceneIndex::nearestInWindow's search over the pixels' coordinate arrays (rows of `width`, at
/// least 8 readable values past the last pixel): the index of the nearest point within `best`
/// (squared, lowered to its distance), at equal distances the lowest index; -1 when none. Eight
/// pixels at a time (forEachPixelChunk; built also for AVX2, without fused multiply-add): their
/// squared distances summed as the kd-tree's metric sums them, so that both give the same
/// distances, and only the pixels within `best` looked at one by one, in the window's order.
[[gnu::target_clones("avx2", "default")]] std::int64_t
nearestInPixels(const float* xs, const float* ys, const float* zs, const std::int32_t* index,
                std::size_t width, const PixelWindow& window, const Eigen::Vector3f& query,
                float& best) {
  float best_sq = best;
  std::int64_t best_index = -1;
  forEachPixelChunk(xs, ys, zs, width, window, query,
                    [&](std::size_t at, const Floats8&, const Floats8&, const Floats8&,
                        const Floats8& d_sq, const Ints8& in_window) {
                      const Ints8 within = (d_sq <= best_sq) & in_window;
                      std::uint64_t any[4];
                      std::memcpy(any, &within, sizeof any);
                      if ((any[0] | any[1] | any[2] | any[3]) == 0)
                        return;
                      for (int k = 0; k < 8; ++k) {
                        if (within[k] == 0 || !(d_sq[k] <= best_sq))
                          continue;
                        const std::int32_t i = index[at + std::size_t(k)];
                        if (d_sq[k] < best_sq || best_index < 0 || i < best_index) {
                          best_sq = d_sq[k];
                          best_index = i;
                        }
                      }
                    });
  best = best_sq;
  return best_index;
}

/// Throws Error when `options` are out of range.
void checkOptions(const SceneIndexOptions& options) {
  if (!(options.normal_radius_mm > 0) || options.pixel_half_window < 1 ||
      options.pixel_half_window > 10 || options.neighbours < 5 || options.neighbours > 100 ||
      options.normal_stride < 1 || !options.viewpoint_mm.allFinite())
    throw Error("Scene index options out of range: normal radius must be > 0 mm, pixel half "
                "window 1-10, neighbours 5-100, normal stride at least 1, and the viewpoint "
                "finite.");
}

/// The valid points of a cloud in input order with their indices in it; for an organized cloud
/// also each pixel's index among them (-1: none).
struct ValidPoints {
  std::vector<Eigen::Vector3f> points;
  std::vector<std::size_t> source_index;
  std::vector<std::int32_t> pixel_to_index; ///< empty unless organized
};

ValidPoints validPoints(const PointCloud& scene_mm, bool organized) {
  ValidPoints valid;
  valid.pixel_to_index.assign(organized ? scene_mm.size() : 0, -1);
  valid.points.reserve(scene_mm.size());
  valid.source_index.reserve(scene_mm.size());
  for (std::size_t i = 0; i < scene_mm.size(); ++i)
    if (isValid(scene_mm.points_mm[i])) {
      if (organized)
        valid.pixel_to_index[i] = static_cast<std::int32_t>(valid.points.size());
      valid.points.push_back(scene_mm.points_mm[i]);
      valid.source_index.push_back(i);
    }
  return valid;
}

/// The cloud's own normal `n` at `p` made unit and, with `orient`, turned to face `viewpoint`;
/// none when it is not finite or shorter than 0.5.
std::optional<Eigen::Vector3f> cloudNormal(const Eigen::Vector3f& n, const Eigen::Vector3f& p,
                                           const Eigen::Vector3d& viewpoint, bool orient) {
  if (!(n.allFinite() && n.norm() > 0.5f))
    return std::nullopt;
  Eigen::Vector3f unit = n.normalized();
  if (orient && unit.cast<double>().dot(viewpoint - p.cast<double>()) < 0)
    unit = -unit;
  return unit;
}

/// What the estimated normals of a cloud's indexed points are computed from.
struct NormalSources {
  const PointCloud& scene_mm;
  const std::vector<Eigen::Vector3f>& indexed;  ///< the valid points
  const std::vector<std::int32_t>& pixel_index; ///< organized clouds: each pixel's point
  Eigen::Vector3d viewpoint;
  float radius_sq = 0; ///< neighbours farther than this (mm²) are left out
};

/// planeNormal of the indexed points within the radius in the (2w+1)² pixel window around
/// pixel `src` of an organized cloud.
Eigen::Vector3f windowNormal(const NormalSources& sources, int w, std::size_t src,
                             const Eigen::Vector3f& p, float& variation) {
  const PointCloud& scene_mm = sources.scene_mm;
  const int width = static_cast<int>(scene_mm.width), height = static_cast<int>(scene_mm.height);
  const int row = static_cast<int>(src / scene_mm.width);
  const int col = static_cast<int>(src % scene_mm.width);
  return planeNormal(p, sources.viewpoint, variation, [&](auto&& add) {
    for (int r = std::max(0, row - w); r <= std::min(height - 1, row + w); ++r)
      for (int c = std::max(0, col - w); c <= std::min(width - 1, col + w); ++c) {
        const std::int32_t j = sources.pixel_index[static_cast<std::size_t>(r) * scene_mm.width +
                                                   static_cast<std::size_t>(c)];
        if (j >= 0 &&
            (sources.indexed[static_cast<std::size_t>(j)] - p).squaredNorm() <= sources.radius_sq)
          add(sources.indexed[static_cast<std::size_t>(j)]);
      }
  });
}

/// planeNormal of the first `found` neighbours `ids` (squared distances `dists`) of `p` that lie
/// within the radius.
Eigen::Vector3f neighbourNormal(const NormalSources& sources, const std::vector<std::uint32_t>& ids,
                                const std::vector<float>& dists, std::size_t found,
                                const Eigen::Vector3f& p, float& variation) {
  return planeNormal(p, sources.viewpoint, variation, [&](auto&& add) {
    for (std::size_t j = 0; j < found; ++j)
      if (dists[j] <= sources.radius_sq)
        add(sources.indexed[ids[j]]);
  });
}

/// The median of the positive `values` (the upper middle one of an even count); 0 when none.
float medianOfPositive(const std::vector<float>& values) {
  std::vector<float> positive;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (values[i] > 0.0f)
      positive.push_back(values[i]);
  if (positive.empty())
    return 0.0f;
  const auto middle = positive.begin() + static_cast<std::ptrdiff_t>(positive.size() / 2);
  std::nth_element(positive.begin(), middle, positive.end());
  return *middle;
}

} // namespace

// The points and their kd-tree live on the heap, so the adaptor's pointer survives moves of the
// SceneIndex. The tree is built on its first search: a scan searched in pixel windows only
// never needs it.
struct SceneIndex::Tree {
  std::vector<Eigen::Vector3f> points;
  PointVectorSource source;
  explicit Tree(std::vector<Eigen::Vector3f> points_mm)
      : points(std::move(points_mm)), source{&points} {}
  const PointKdTree& kdTree() {
    std::call_once(m_built, [this] {
      m_tree =
          std::make_unique<PointKdTree>(3, source, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    });
    return *m_tree;
  }

private:
  std::once_flag m_built;
  std::unique_ptr<PointKdTree> m_tree;
};

SceneIndex::SceneIndex(const PointCloud& scene_mm, const SceneIndexOptions& options,
                       const ProgressFn& progress)
    : m_options(options) {
  scene_mm.validate();
  checkOptions(options);
  // Valid points in input order; for an organized cloud (a sensor's image, far fewer than 2^31
  // pixels), where each pixel went.
  const bool organized = scene_mm.isOrganized() &&
                         scene_mm.size() < std::size_t(std::numeric_limits<std::int32_t>::max());
  ValidPoints valid = validPoints(scene_mm, organized);
  if (valid.points.empty())
    throw Error("The cloud to refine against has no valid point (empty or all NaN): check that "
                "the scan loaded and that the crop or floor removal left points.");
  m_tree = std::make_unique<Tree>(std::move(valid.points));
  const std::vector<Eigen::Vector3f>& indexed = m_tree->points;
  const std::vector<std::size_t>& source_index = valid.source_index;
  if (organized) {
    m_width = static_cast<int>(scene_mm.width);
    m_height = static_cast<int>(scene_mm.height);
    m_pixel_index = std::move(valid.pixel_to_index);
    m_pixel_points = PixelCoordinates(m_pixel_index.size());
    for (std::size_t pixel = 0; pixel < m_pixel_index.size(); ++pixel)
      if (m_pixel_index[pixel] >= 0)
        m_pixel_points.set(pixel, indexed[static_cast<std::size_t>(m_pixel_index[pixel])]);
    if (options.sensor)
      m_pixel_slack = measurePixelSlack(*options.sensor);
  }
  reportProgress(progress, 0.1);

  m_normals.assign(indexed.size(), invalidPoint());
  m_variation.assign(indexed.size(), 0.0f);
  const NormalSources sources{
      scene_mm, indexed, m_pixel_index, options.viewpoint_mm,
      static_cast<float>(options.normal_radius_mm * options.normal_radius_mm)};
  const bool own_normals = options.use_cloud_normals && scene_mm.normals.size() == scene_mm.size();
  const std::size_t k = static_cast<std::size_t>(options.neighbours);

  if (!options.estimate_normals) {
    reportProgress(progress, 1.0);
    return;
  }
  blockedParallel(indexed.size(), progress, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> ids(k);
    std::vector<float> dists(k);
    const auto normal_stride = static_cast<std::size_t>(options.normal_stride);
    for (std::size_t i = begin; i < end; ++i) {
      if (i % normal_stride != 0)
        continue;
      const Eigen::Vector3f& p = indexed[i];
      const std::size_t src = source_index[i];
      if (own_normals) {
        if (const auto n = cloudNormal(scene_mm.normals[src], p, sources.viewpoint,
                                       options.orient_cloud_normals)) {
          m_normals[i] = *n;
          continue;
        }
      }
      if (organized) {
        m_normals[i] = windowNormal(sources, options.pixel_half_window, src, p, m_variation[i]);
      } else {
        const std::size_t found = m_tree->kdTree().knnSearch(p.data(), k, ids.data(), dists.data());
        m_normals[i] = neighbourNormal(sources, ids, dists, found, p, m_variation[i]);
      }
    }
  });

  // Most of a scan is locally flat, so the median variation measures the sensor noise.
  m_typical_variation = medianOfPositive(m_variation);
}

const std::vector<Eigen::Vector3f>& SceneIndex::points() const {
  return m_tree->points;
}

SceneIndex::~SceneIndex() = default;
SceneIndex::SceneIndex(SceneIndex&&) noexcept = default;
SceneIndex& SceneIndex::operator=(SceneIndex&&) noexcept = default;

float SceneIndex::measurePixelSlack(const SensorModel& sensor) const {
  if (m_pixel_index.empty() || m_width != sensor.width || m_height != sensor.height ||
      !(sensor.fx > 0) || !(sensor.fy > 0))
    return -1.0f;
  double slack = 0.0;
  for (int v = 0; v < m_height; ++v)
    for (int u = 0; u < m_width; ++u) {
      const std::int32_t i = m_pixel_index[std::size_t(v) * std::size_t(m_width) + std::size_t(u)];
      if (i < 0)
        continue;
      const Eigen::Vector3d p = m_tree->points[std::size_t(i)].cast<double>();
      if (!(p.z() > 0))
        return -1.0f;
      const Eigen::Vector2d uv = sensor.project(p);
      slack = std::max({slack, std::abs(uv.x() - u), std::abs(uv.y() - v)});
    }
  return float(slack);
}

std::int64_t SceneIndex::nearest(const Eigen::Vector3f& query_mm, float max_distance_sq,
                                 float* distance_sq) const {
  if (!m_tree || !(max_distance_sq > 0) || !query_mm.allFinite())
    return -1;
  if (m_pixel_slack >= 0.0f && m_pixel_slack <= kMaxPixelWindowSlack) {
    // A point within the radius projects within `reach` pixels of the query's pixel.
    const SensorModel& sensor = *m_options.sensor;
    const double radius = std::sqrt(double(max_distance_sq)), z = query_mm.z();
    if (z > 2.0 * radius) {
      const double beyond = z - radius;
      const double reach_u =
          sensor.fx * radius * (1.0 + std::abs(query_mm.x()) / z) / beyond + 0.5 + m_pixel_slack;
      const double reach_v =
          sensor.fy * radius * (1.0 + std::abs(query_mm.y()) / z) / beyond + 0.5 + m_pixel_slack;
      if (reach_u < kMaxWindowReach && reach_v < kMaxWindowReach) {
        // (A pixel clamped far outside the image has no point within the radius in reach.)
        if (const auto pixel = sensor.pixelOf(query_mm))
          return nearestInWindow(query_mm, max_distance_sq, pixel->x(), pixel->y(), int(reach_u),
                                 int(reach_v), distance_sq);
      }
    }
  }
  NearestResult result(max_distance_sq);
  m_tree->kdTree().findNeighbors(result, query_mm.data(), nanoflann::SearchParams(32, 0.0f, false));
  if (result.index() == NearestResult::kNone)
    return -1;
  if (distance_sq)
    *distance_sq = result.worstDist();
  return static_cast<std::int64_t>(result.index());
}

std::int64_t SceneIndex::nearestInWindow(const Eigen::Vector3f& query_mm, float max_distance_sq,
                                         int u, int v, int half_u, int half_v,
                                         float* distance_sq) const {
  if (m_pixel_index.empty() || !(max_distance_sq > 0) || !query_mm.allFinite())
    return -1;
  const PixelWindow window{std::max(0, u - half_u), std::min(m_width - 1, u + half_u),
                           std::max(0, v - half_v), std::min(m_height - 1, v + half_v)};
  float best = max_distance_sq;
  const std::int64_t best_index =
      nearestInPixels(m_pixel_points.x.data(), m_pixel_points.y.data(), m_pixel_points.z.data(),
                      m_pixel_index.data(), std::size_t(m_width), window, query_mm, best);
  if (best_index >= 0 && distance_sq)
    *distance_sq = best;
  return best_index;
}

} // namespace scanpick::core
