#include "core/features/GridRadiusSearch.h"

#include <algorithm>
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
  indices_ = indices;
  m_points.clear();
  m_position.clear();
  m_index.clear();
  m_cells.clear();
  m_starts.clear();
  if (!cloud)
    return;
  // Finite points only, as PCL's kd-tree keeps them; position = rank among those kept.
  std::vector<Cell> cells;
  std::vector<pcl::index_t> kept;
  const std::size_t n = indices ? indices->size() : cloud->size();
  cells.reserve(n);
  kept.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const pcl::index_t i = indices ? (*indices)[k] : static_cast<pcl::index_t>(k);
    const pcl::PointXYZ& p = (*cloud)[static_cast<std::size_t>(i)];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      continue;
    cells.push_back(cellOf(p));
    kept.push_back(i);
  }
  const std::vector<std::uint32_t> order = sortedByCell(cells);
  m_points.reserve(order.size());
  m_position.reserve(order.size());
  m_index.reserve(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t position = order[k];
    const pcl::index_t i = kept[position];
    m_points.push_back((*cloud)[static_cast<std::size_t>(i)]);
    m_position.push_back(position);
    m_index.push_back(i);
    if (m_cells.empty() || m_cells.back() != cells[position]) {
      m_cells.push_back(cells[position]);
      m_starts.push_back(static_cast<std::uint32_t>(k));
    }
  }
  m_starts.push_back(static_cast<std::uint32_t>(order.size()));
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
  const Cell centre = cellOf(point);
  const auto reach = static_cast<std::int64_t>(std::ceil(radius / m_cell_mm));
  std::vector<std::tuple<float, std::uint32_t, pcl::index_t>> found;
  for (std::int64_t dx = -reach; dx <= reach; ++dx)
    for (std::int64_t dy = -reach; dy <= reach; ++dy) {
      // The cells along z from centre − reach to centre + reach follow each other in the order.
      const Cell last{centre[0] + dx, centre[1] + dy, centre[2] + reach};
      for (auto cell = std::lower_bound(m_cells.begin(), m_cells.end(),
                                        Cell{centre[0] + dx, centre[1] + dy, centre[2] - reach});
           cell != m_cells.end() && *cell <= last; ++cell) {
        const auto c = static_cast<std::size_t>(cell - m_cells.begin());
        for (std::uint32_t k = m_starts[c]; k < m_starts[c + 1]; ++k) {
          const pcl::PointXYZ& p = m_points[k];
          const float ex = point.x - p.x, ey = point.y - p.y, ez = point.z - p.z;
          const float distance_sq = ex * ex + ey * ey + ez * ez;
          if (distance_sq < radius_sq)
            found.emplace_back(distance_sq, m_position[k], m_index[k]);
        }
      }
    }
  std::sort(found.begin(), found.end());
  if (max_nn > 0 && found.size() > max_nn)
    found.resize(max_nn);
  k_indices.reserve(found.size());
  k_sqr_distances.reserve(found.size());
  for (const auto& [distance_sq, position, index] : found) {
    k_indices.push_back(index);
    k_sqr_distances.push_back(distance_sq);
  }
  return static_cast<int>(found.size());
}

int GridRadiusSearch::nearestKSearch(const pcl::PointXYZ&, int, pcl::Indices&,
                                     std::vector<float>&) const {
  throw pcl::PCLException("GridRadiusSearch offers radius search only");
}

} // namespace scanpick::core
