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

/// Algorithm 7, lines 2-12: each of `source_indices` (valid points of `scene_mm`) projected along
/// the line to the farther source onto z = centroid z (mm).
std::vector<Eigen::Vector3f> projectToCentroidPlane(const PointCloud& scene_mm,
                                                    const std::vector<int>& source_indices,
                                                    const SensorModel& sensor) {
  const std::size_t n = source_indices.size();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i : source_indices)
    centroid += scene_mm.points_mm[static_cast<std::size_t>(i)].cast<double>();
  const double z0 = centroid.z() / static_cast<double>(n);
  const Eigen::Vector3d camera = sensor.cameraPosition(), projector = sensor.projectorPosition();
  std::vector<Eigen::Vector3f> projected(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const auto& r) {
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const Eigen::Vector3d p =
          scene_mm.points_mm[static_cast<std::size_t>(source_indices[j])].cast<double>();
      const Eigen::Vector3d& source =
          (p - camera).norm() >= (p - projector).norm() ? camera : projector;
      const double dz = p.z() - source.z();
      const Eigen::Vector3d q =
          std::abs(dz) > 1e-9 ? Eigen::Vector3d(source + (z0 - source.z()) / dz * (p - source)) : p;
      projected[j] = q.cast<float>();
    }
  });
  return projected;
}

/// The projected points sorted into square cells of `cell` mm over their bounding rectangle (from
/// `lo`, nx x ny cells), each occupied cell a node of the single linkage.
struct CellGrid {
  Eigen::Vector2d lo;
  double cell = 0;
  std::uint64_t nx = 0, ny = 0;
  /// (cell key x * ny + y, point), sorted.
  std::vector<std::pair<std::uint64_t, int>> keyed;
  /// Occupied cells in key order: their points are keyed[cell_start[c], cell_start[c + 1]).
  std::vector<std::size_t> cell_start;
  std::vector<std::uint64_t> cell_key;
  /// Occupied cell of a key (-1: none): a table of nx x ny cells, or a hash map when that is
  /// too large.
  std::vector<int> dense;
  std::unordered_map<std::uint64_t, int> sparse;

  [[nodiscard]] std::size_t cells() const { return cell_key.size(); }
  /// The occupied cell at grid position (x, y), or -1.
  [[nodiscard]] int find(std::int64_t x, std::int64_t y) const {
    if (x < 0 || y < 0 || static_cast<std::uint64_t>(x) >= nx ||
        static_cast<std::uint64_t>(y) >= ny)
      return -1;
    const std::uint64_t key = static_cast<std::uint64_t>(x) * ny + static_cast<std::uint64_t>(y);
    if (!dense.empty())
      return dense[key];
    const auto it = sparse.find(key);
    return it == sparse.end() ? -1 : it->second;
  }
};

/// Sets the grid's origin and size to the bounding rectangle of `projected`. Cell keys are
/// x * ny + y in 64 bits: a scene whose projection spans more than 2^30 cells along an axis
/// (kilometres; a corrupt coordinate) cannot be keyed and is refused (Error).
void setGridBounds(CellGrid& grid, const std::vector<Eigen::Vector3f>& projected) {
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const auto& q : projected) {
    lo = lo.cwiseMin(q.head<2>().cast<double>());
    hi = hi.cwiseMax(q.head<2>().cast<double>());
  }
  const Eigen::Vector2d span_cells = (hi - lo) / grid.cell;
  if (!span_cells.allFinite() || span_cells.maxCoeff() > 1073741824.0)
    throw Error("the scene's points span " +
                std::to_string(static_cast<long long>((hi - lo).maxCoeff() / 1000.0)) +
                " m across: some coordinates are not measurements (check the scan's units, or "
                "capture it again)");
  grid.lo = lo;
  grid.nx = static_cast<std::uint64_t>(span_cells.x()) + 1;
  grid.ny = static_cast<std::uint64_t>(span_cells.y()) + 1;
}

/// Sorts the points by cell and lists the occupied cells with their lookup table.
void fillCells(CellGrid& grid, const std::vector<Eigen::Vector3f>& projected) {
  const std::size_t n = projected.size();
  const Eigen::Vector2d lo = grid.lo;
  const double cell = grid.cell;
  const std::uint64_t ny = grid.ny;
  const auto cellX = [&](const Eigen::Vector3f& q) {
    return static_cast<std::int64_t>((q.x() - lo.x()) / cell);
  };
  const auto cellY = [&](const Eigen::Vector3f& q) {
    return static_cast<std::int64_t>((q.y() - lo.y()) / cell);
  };
  std::vector<std::pair<std::uint64_t, int>>& keyed = grid.keyed;
  keyed.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const auto& rg) {
    for (std::size_t j = rg.begin(); j < rg.end(); ++j) {
      const auto& q = projected[j];
      keyed[j] = {static_cast<std::uint64_t>(cellX(q)) * ny + static_cast<std::uint64_t>(cellY(q)),
                  static_cast<int>(j)};
    }
  });
  tbb::parallel_sort(keyed.begin(), keyed.end());
  for (std::size_t j = 0; j < n; ++j)
    if (j == 0 || keyed[j].first != keyed[j - 1].first) {
      grid.cell_start.push_back(j);
      grid.cell_key.push_back(keyed[j].first);
    }
  const std::size_t cells = grid.cell_key.size();
  grid.cell_start.push_back(n);
  if (grid.nx * ny <= kMaxDenseCells) {
    grid.dense.assign(grid.nx * ny, -1);
    for (std::size_t c = 0; c < cells; ++c)
      grid.dense[grid.cell_key[c]] = static_cast<int>(c);
  } else {
    grid.sparse.reserve(cells * 2);
    for (std::size_t c = 0; c < cells; ++c)
      grid.sparse.emplace(grid.cell_key[c], static_cast<int>(c));
  }
}

/// Whether cells `a` and `b` hold a pair of points within sqrt(r2) (mm) of each other in x, y.
bool cellsLinked(const CellGrid& grid, const std::vector<Eigen::Vector3f>& projected, std::size_t a,
                 std::size_t b, float r2) {
  for (std::size_t i = grid.cell_start[a]; i < grid.cell_start[a + 1]; ++i) {
    const Eigen::Vector2f p = projected[static_cast<std::size_t>(grid.keyed[i].second)].head<2>();
    for (std::size_t j = grid.cell_start[b]; j < grid.cell_start[b + 1]; ++j)
      if ((projected[static_cast<std::size_t>(grid.keyed[j].second)].head<2>() - p).squaredNorm() <=
          r2)
        return true;
  }
  return false;
}

/// Single linkage of the grid's cells: cells with points within sqrt(r2) of each other (mm) end
/// up in one set. Reports progress from 0.3 to 0.9.
DisjointSets linkCells(const CellGrid& grid, const std::vector<Eigen::Vector3f>& projected,
                       float r2, const ProgressFn& progress) {
  const std::size_t cells = grid.cells();
  DisjointSets sets(cells);
  const std::size_t report_every = std::max<std::size_t>(1, cells / 20);
  for (std::size_t c = 0; c < cells; ++c) {
    if (c % report_every == 0)
      reportProgress(progress, 0.3 + 0.6 * static_cast<double>(c) / static_cast<double>(cells));
    const auto x = static_cast<std::int64_t>(grid.cell_key[c] / grid.ny);
    const auto y = static_cast<std::int64_t>(grid.cell_key[c] % grid.ny);
    // Half of the 5x5 neighbourhood (the other half is visited from the other side).
    for (int dx = 0; dx <= 2; ++dx)
      for (int dy = -2; dy <= 2; ++dy) {
        if (dx == 0 && dy <= 0)
          continue;
        const int other = grid.find(x + dx, y + dy);
        if (other < 0 || sets.find(static_cast<int>(c)) == sets.find(other))
          continue;
        if (cellsLinked(grid, projected, c, static_cast<std::size_t>(other), r2))
          sets.unite(static_cast<int>(c), other);
      }
  }
  return sets;
}

/// Clusters: points of cells with the same root, largest first, ties by first index.
std::vector<std::vector<int>> clustersOf(const CellGrid& grid, DisjointSets& sets) {
  std::vector<std::vector<int>> clusters;
  const std::size_t cells = grid.cells();
  std::vector<int> cluster_of_root(cells, -1);
  for (std::size_t c = 0; c < cells; ++c) {
    const int root = sets.find(static_cast<int>(c));
    if (cluster_of_root[static_cast<std::size_t>(root)] < 0) {
      cluster_of_root[static_cast<std::size_t>(root)] = static_cast<int>(clusters.size());
      clusters.emplace_back();
    }
    auto& members =
        clusters[static_cast<std::size_t>(cluster_of_root[static_cast<std::size_t>(root)])];
    for (std::size_t i = grid.cell_start[c]; i < grid.cell_start[c + 1]; ++i)
      members.push_back(grid.keyed[i].second);
  }
  for (auto& members : clusters)
    std::sort(members.begin(), members.end());
  std::sort(clusters.begin(), clusters.end(), [](const auto& a, const auto& b) {
    return a.size() != b.size() ? a.size() > b.size() : a.front() < b.front();
  });
  return clusters;
}

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
  if (result.source_indices.empty())
    return result;

  result.projected_mm = projectToCentroidPlane(scene_mm, result.source_indices, sensor);
  reportProgress(progress, 0.2);

  // Single linkage on a grid of cell size r/sqrt(2): a cell's points are all within r of each
  // other, so cells are the union-find nodes and only neighbouring cells need a pair test.
  const double r = params.count_radius_mm;
  const float r2 = static_cast<float>(r * r);
  CellGrid grid;
  grid.cell = r / std::sqrt(2.0);
  setGridBounds(grid, result.projected_mm);
  fillCells(grid, result.projected_mm);
  DisjointSets sets = linkCells(grid, result.projected_mm, r2, progress);

  result.clusters = clustersOf(grid, sets);
  for (const auto& members : result.clusters)
    if (static_cast<int>(members.size()) >= params.count_min_points)
      ++result.count;
  reportProgress(progress, 1.0);
  return result;
}

} // namespace scanpick::core
