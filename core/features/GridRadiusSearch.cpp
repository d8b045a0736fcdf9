#include "core/features/GridRadiusSearch.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <pcl/exceptions.h>
#include <tuple>

namespace scanpick::core {

GridRadiusSearch::GridRadiusSearch(double cell_mm)
    : pcl::search::Search<pcl::PointXYZ>("GridRadiusSearch", true), m_cell_mm(cell_mm) {
  if (!(cell_mm > 0) || !std::isfinite(cell_mm))
    throw pcl::PCLException("GridRadiusSearch needs a positive cell edge");
}

GridRadiusSearch::Cell GridRadiusSearch::cellOf(const pcl::PointXYZ& p) const {
  return {static_cast<std::int64_t>(std::floor(p.x / m_cell_mm)),
          static_cast<std::int64_t>(std::floor(p.y / m_cell_mm)),
          static_cast<std::int64_t>(std::floor(p.z / m_cell_mm))};
}

namespace {

/// The positions of `cells` in lexicographic order of (cell, position). Within the cells' bounding
/// box a cell is one number (x, then y, then z), and sorting those is several times faster than
/// comparing arrays; a box too large for 64 bits sorts the arrays.
std::vector<std::uint32_t> sortedByCell(const std::vector<std::array<std::int64_t, 3>>& cells) {
  std::vector<std::uint32_t> order(cells.size());
  if (cells.empty())
    return order;
  std::array<std::int64_t, 3> lo = cells.front(), hi = cells.front();
  for (const auto& c : cells)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], c[a]);
      hi[a] = std::max(hi[a], c[a]);
    }
  // Differences taken unsigned: exact below 2^64, where signed ones could overflow.
  const auto offset = [&](const std::array<std::int64_t, 3>& c, int a) {
    return static_cast<std::uint64_t>(c[a]) - static_cast<std::uint64_t>(lo[a]);
  };
  const long double span_x = static_cast<long double>(offset(hi, 0)) + 1;
  const long double span_y = static_cast<long double>(offset(hi, 1)) + 1;
  const long double span_z = static_cast<long double>(offset(hi, 2)) + 1;
  if (span_x * span_y * span_z < 1.8e19L) {
    const auto sy = static_cast<std::uint64_t>(span_y), sz = static_cast<std::uint64_t>(span_z);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(cells.size());
    for (std::size_t k = 0; k < cells.size(); ++k)
      keyed[k] = {(offset(cells[k], 0) * sy + offset(cells[k], 1)) * sz + offset(cells[k], 2),
                  static_cast<std::uint32_t>(k)};
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k)
      order[k] = keyed[k].second;
    return order;
  }
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tie(cells[a], a) < std::tie(cells[b], b);
  });
  return order;
}

} // namespace

void GridRadiusSearch::setInputCloud(const PointCloudConstPtr& cloud,
                                     const IndicesConstPtr& indices) {
  input_ = cloud;
  m_cells.clear();
  m_cell_of_point.assign(cloud ? cloud->size() : 0, kNoCell);
  m_neighbour_count.clear();
  m_neighbours.clear();
  if (cloud) {
    // Finite points only, as PCL's kd-tree keeps them.
    std::vector<Cell> cells;
    std::vector<std::uint32_t> finite;
    for (std::size_t i = 0; i < cloud->size(); ++i) {
      const pcl::PointXYZ& p = (*cloud)[i];
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
        cells.push_back(cellOf(p));
        finite.push_back(static_cast<std::uint32_t>(i));
      }
    }
    for (const std::uint32_t k : sortedByCell(cells)) {
      if (m_cells.empty() || m_cells.back() != cells[k])
        m_cells.push_back(cells[k]);
      m_cell_of_point[finite[k]] = static_cast<std::uint32_t>(m_cells.size() - 1);
    }
    // Each cell's neighbours along one column (x + dx, y + dy) follow the cells' order: one sweep
    // per column offset instead of binary searches.
    const std::size_t count = m_cells.size();
    m_neighbour_count.assign(count, 0);
    m_neighbours.resize(count * kMaxNeighbours);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::size_t c = 0, from = 0; c < count; ++c) {
          const Cell& cell = m_cells[c];
          const Cell lo{cell[0] + dx, cell[1] + dy, cell[2] - 1};
          const Cell hi{cell[0] + dx, cell[1] + dy, cell[2] + 1};
          while (from < count && m_cells[from] < lo)
            ++from;
          for (std::size_t n = from; n < count && m_cells[n] <= hi; ++n)
            m_neighbours[c * kMaxNeighbours + m_neighbour_count[c]++] = std::uint32_t(n);
        }
  }
  setIndices(indices);
}

void GridRadiusSearch::setIndices(const IndicesConstPtr& indices) {
  indices_ = indices;
  m_points.clear();
  m_position.clear();
  m_kept.clear();
  m_starts.assign(m_cells.size() + 1, 0);
  if (!input_)
    return;
  // A counting sort by cell keeps the order of the indices within each cell.
  const std::size_t n = indices ? indices->size() : input_->size();
  const auto indexAt = [&](std::size_t k) {
    return indices ? (*indices)[k] : static_cast<pcl::index_t>(k);
  };
  for (std::size_t k = 0; k < n; ++k)
    if (const std::uint32_t c = m_cell_of_point[static_cast<std::size_t>(indexAt(k))]; c != kNoCell)
      ++m_starts[c + 1];
  std::partial_sum(m_starts.begin(), m_starts.end(), m_starts.begin());
  std::vector<std::uint32_t> next(m_starts.begin(), m_starts.end() - 1);
  m_points.resize(m_starts.back());
  m_position.resize(m_starts.back());
  m_kept.reserve(m_starts.back());
  for (std::size_t k = 0; k < n; ++k) {
    const pcl::index_t i = indexAt(k);
    const std::uint32_t c = m_cell_of_point[static_cast<std::size_t>(i)];
    if (c == kNoCell)
      continue;
    const std::uint32_t slot = next[c]++;
    m_points[slot] = (*input_)[static_cast<std::size_t>(i)];
    m_position[slot] = static_cast<std::uint32_t>(m_kept.size());
    m_kept.push_back(i);
  }
}

template <typename Visit>
void GridRadiusSearch::forEachCellNear(const Cell& centre, std::int64_t reach,
                                       Visit&& visit) const {
  for (std::int64_t dx = -reach; dx <= reach; ++dx)
    for (std::int64_t dy = -reach; dy <= reach; ++dy) {
      // The cells along z from centre − reach to centre + reach follow each other in the order.
      const Cell last{centre[0] + dx, centre[1] + dy, centre[2] + reach};
      for (auto cell = std::lower_bound(m_cells.begin(), m_cells.end(),
                                        Cell{centre[0] + dx, centre[1] + dy, centre[2] - reach});
           cell != m_cells.end() && *cell <= last; ++cell)
        visit(static_cast<std::uint32_t>(cell - m_cells.begin()));
    }
}

int GridRadiusSearch::radiusSearch(const pcl::PointXYZ& point, double radius,
                                   pcl::Indices& k_indices, std::vector<float>& k_sqr_distances,
                                   unsigned int max_nn) const {
  k_indices.clear();
  k_sqr_distances.clear();
  if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z) ||
      !(radius > 0))
    return 0; // no neighbours (PCL's kd-tree asserts on such a query)
  // As FLANN: the radius squared in double, compared in float; distances summed from x to z.
  const auto radius_sq = static_cast<float>(radius * radius);
  // Found points as (distance bits, position): a non-negative float's bits order as it does, and
  // positions are unique, so sorting these numbers orders by distance, then by position.
  thread_local std::vector<std::uint64_t> found;
  found.clear();
  const auto visit = [&](std::uint32_t c) {
    for (std::uint32_t k = m_starts[c]; k < m_starts[c + 1]; ++k) {
      const pcl::PointXYZ& p = m_points[k];
      const float ex = point.x - p.x, ey = point.y - p.y, ez = point.z - p.z;
      const float distance_sq = ex * ex + ey * ey + ez * ez;
      if (distance_sq < radius_sq)
        found.push_back(std::uint64_t{std::bit_cast<std::uint32_t>(distance_sq)} << 32 |
                        m_position[k]);
    }
  };
  const Cell centre = cellOf(point);
  const auto reach = static_cast<std::int64_t>(std::ceil(radius / m_cell_mm));
  const auto cell = std::lower_bound(m_cells.begin(), m_cells.end(), centre);
  if (reach == 1 && cell != m_cells.end() && *cell == centre) {
    const auto c = static_cast<std::size_t>(cell - m_cells.begin());
    for (std::uint32_t n = 0; n < m_neighbour_count[c]; ++n)
      visit(m_neighbours[c * kMaxNeighbours + n]);
  } else {
    forEachCellNear(centre, reach, visit);
  }
  std::sort(found.begin(), found.end());
  if (max_nn > 0 && found.size() > max_nn)
    found.resize(max_nn);
  k_indices.reserve(found.size());
  k_sqr_distances.reserve(found.size());
  for (const std::uint64_t f : found) {
    k_indices.push_back(m_kept[static_cast<std::uint32_t>(f)]);
    k_sqr_distances.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(f >> 32)));
  }
  return static_cast<int>(found.size());
}

int GridRadiusSearch::nearestKSearch(const pcl::PointXYZ&, int, pcl::Indices&,
                                     std::vector<float>&) const {
  throw pcl::PCLException("GridRadiusSearch offers radius search only");
}

} // namespace scanpick::core
