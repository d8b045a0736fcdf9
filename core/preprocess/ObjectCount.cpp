#include "core/preprocess/ObjectCount.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <unordered_map>

namespace scanpick::core {
namespace {

/// Union-find with path halving; union by smaller root keeps the result order-independent.
class DisjointSets {
public:
  explicit DisjointSets(std::size_t n) : m_parent(n) {
    std::iota(m_parent.begin(), m_parent.end(), 0);
  }
  int find(int x) {
    while (m_parent[static_cast<std::size_t>(x)] != x) {
      auto& p = m_parent[static_cast<std::size_t>(x)];
      p = m_parent[static_cast<std::size_t>(p)];
      x = p;
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b)
      m_parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }

private:
  std::vector<int> m_parent;
};

/// Dense cell tables above this many cells would cost too much memory: a hash map takes over.
constexpr std::uint64_t kMaxDenseCells = 16'000'000;

} // namespace

ObjectCount countObjects(const PointCloud& scene_mm, const SensorModel& sensor,
                         const ClusteringParams& params, const ProgressFn& progress) {
  scene_mm.validate();
  if (!(params.count_radius_mm > 0))
    throw Error("object count needs a positive radius (clustering.count_radius_mm), got " +
                std::to_string(params.count_radius_mm));
  ObjectCount result;
  for (std::size_t i = 0; i < scene_mm.size(); ++i)
    if (isValid(scene_mm.points_mm[i]))
      result.source_indices.push_back(static_cast<int>(i));
  const std::size_t n = result.source_indices.size();
  if (n == 0)
    return result;

  // Algorithm 7, lines 2-12: project along the line to the farther source onto z = centroid z.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i : result.source_indices)
    centroid += scene_mm.points_mm[static_cast<std::size_t>(i)].cast<double>();
  const double z0 = centroid.z() / static_cast<double>(n);
  const Eigen::Vector3d camera = sensor.cameraPosition(), projector = sensor.projectorPosition();
  result.projected_mm.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const auto& r) {
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const Eigen::Vector3d p =
          scene_mm.points_mm[static_cast<std::size_t>(result.source_indices[j])].cast<double>();
      const Eigen::Vector3d& source =
          (p - camera).norm() >= (p - projector).norm() ? camera : projector;
      const double dz = p.z() - source.z();
      const Eigen::Vector3d q =
          std::abs(dz) > 1e-9 ? Eigen::Vector3d(source + (z0 - source.z()) / dz * (p - source)) : p;
      result.projected_mm[j] = q.cast<float>();
    }
  });
  reportProgress(progress, 0.2);

  // Single linkage on a grid of cell size r/sqrt(2): a cell's points are all within r of each
  // other, so cells are the union-find nodes and only neighbouring cells need a pair test.
  const double r = params.count_radius_mm, cell = r / std::sqrt(2.0);
  const float r2 = static_cast<float>(r * r);
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const auto& q : result.projected_mm) {
    lo = lo.cwiseMin(q.head<2>().cast<double>());
    hi = hi.cwiseMax(q.head<2>().cast<double>());
  }
  // Cell keys are x * ny + y in 64 bits: a scene whose projection spans more than 2^30 cells
  // along an axis (kilometres; a corrupt coordinate) cannot be keyed and is refused.
  const Eigen::Vector2d span_cells = (hi - lo) / cell;
  if (!span_cells.allFinite() || span_cells.maxCoeff() > 1073741824.0)
    throw Error("the scene's points span " +
                std::to_string(static_cast<long long>((hi - lo).maxCoeff() / 1000.0)) +
                " m across: some coordinates are not measurements (check the scan's units, or "
                "capture it again)");
  const auto nx = static_cast<std::uint64_t>(span_cells.x()) + 1;
  const auto ny = static_cast<std::uint64_t>(span_cells.y()) + 1;
  const auto cellX = [&](const Eigen::Vector3f& q) {
    return static_cast<std::int64_t>((q.x() - lo.x()) / cell);
  };
  const auto cellY = [&](const Eigen::Vector3f& q) {
    return static_cast<std::int64_t>((q.y() - lo.y()) / cell);
  };
  std::vector<std::pair<std::uint64_t, int>> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const auto& rg) {
    for (std::size_t j = rg.begin(); j < rg.end(); ++j) {
      const auto& q = result.projected_mm[j];
      keyed[j] = {static_cast<std::uint64_t>(cellX(q)) * ny + static_cast<std::uint64_t>(cellY(q)),
                  static_cast<int>(j)};
    }
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> cell_start; // occupied cells in key order, [start, next start)
  std::vector<std::uint64_t> cell_key;
  for (std::size_t j = 0; j < n; ++j)
    if (j == 0 || keyed[j].first != keyed[j - 1].first) {
      cell_start.push_back(j);
      cell_key.push_back(keyed[j].first);
    }
  const std::size_t cells = cell_key.size();
  cell_start.push_back(n);

  std::vector<int> dense;
  std::unordered_map<std::uint64_t, int> sparse;
  if (nx * ny <= kMaxDenseCells) {
    dense.assign(nx * ny, -1);
    for (std::size_t c = 0; c < cells; ++c)
      dense[cell_key[c]] = static_cast<int>(c);
  } else {
    sparse.reserve(cells * 2);
    for (std::size_t c = 0; c < cells; ++c)
      sparse.emplace(cell_key[c], static_cast<int>(c));
  }
  const auto findCell = [&](std::int64_t x, std::int64_t y) -> int {
    if (x < 0 || y < 0 || static_cast<std::uint64_t>(x) >= nx ||
        static_cast<std::uint64_t>(y) >= ny)
      return -1;
    const std::uint64_t key = static_cast<std::uint64_t>(x) * ny + static_cast<std::uint64_t>(y);
    if (!dense.empty())
      return dense[key];
    const auto it = sparse.find(key);
    return it == sparse.end() ? -1 : it->second;
  };
  const auto linked = [&](std::size_t a, std::size_t b) {
    for (std::size_t i = cell_start[a]; i < cell_start[a + 1]; ++i) {
      const Eigen::Vector2f p =
          result.projected_mm[static_cast<std::size_t>(keyed[i].second)].head<2>();
      for (std::size_t j = cell_start[b]; j < cell_start[b + 1]; ++j)
        if ((result.projected_mm[static_cast<std::size_t>(keyed[j].second)].head<2>() - p)
                .squaredNorm() <= r2)
          return true;
    }
    return false;
  };

  DisjointSets sets(cells);
  const std::size_t report_every = std::max<std::size_t>(1, cells / 20);
  for (std::size_t c = 0; c < cells; ++c) {
    if (c % report_every == 0)
      reportProgress(progress, 0.3 + 0.6 * static_cast<double>(c) / static_cast<double>(cells));
    const auto x = static_cast<std::int64_t>(cell_key[c] / ny);
    const auto y = static_cast<std::int64_t>(cell_key[c] % ny);
    // Half of the 5x5 neighbourhood (the other half is visited from the other side).
    for (int dx = 0; dx <= 2; ++dx)
      for (int dy = -2; dy <= 2; ++dy) {
        if (dx == 0 && dy <= 0)
          continue;
        const int other = findCell(x + dx, y + dy);
        if (other < 0 || sets.find(static_cast<int>(c)) == sets.find(other))
          continue;
        if (linked(c, static_cast<std::size_t>(other)))
          sets.unite(static_cast<int>(c), other);
      }
  }

  // Clusters: points of cells with the same root, largest first, ties by first index.
  std::vector<int> cluster_of_root(cells, -1);
  for (std::size_t c = 0; c < cells; ++c) {
    const int root = sets.find(static_cast<int>(c));
    if (cluster_of_root[static_cast<std::size_t>(root)] < 0) {
      cluster_of_root[static_cast<std::size_t>(root)] = static_cast<int>(result.clusters.size());
      result.clusters.emplace_back();
    }
    auto& members =
        result.clusters[static_cast<std::size_t>(cluster_of_root[static_cast<std::size_t>(root)])];
    for (std::size_t i = cell_start[c]; i < cell_start[c + 1]; ++i)
      members.push_back(keyed[i].second);
  }
  for (auto& members : result.clusters)
    std::sort(members.begin(), members.end());
  std::sort(result.clusters.begin(), result.clusters.end(), [](const auto& a, const auto& b) {
    return a.size() != b.size() ? a.size() > b.size() : a.front() < b.front();
  });
  for (const auto& members : result.clusters)
    if (static_cast<int>(members.size()) >= params.count_min_points)
      ++result.count;
  reportProgress(progress, 1.0);
  return result;
}

} // namespace scanpick::core
