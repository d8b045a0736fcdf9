#include "core/grasp/PointGrid.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>

namespace scanpick::core::grasp {
namespace {
// Cell coordinates are kept within ±2^20 cells, so that a key packs three of them in 63 bits.
constexpr std::int64_t kCellRange = std::int64_t(1) << 20;

std::int64_t cellOf(double v, double cell_mm) {
  return std::clamp(static_cast<std::int64_t>(std::floor(v / cell_mm)), -kCellRange + 1,
                    kCellRange - 1);
}
} // namespace

PointGrid::PointGrid(const std::vector<Eigen::Vector3f>& points_mm, double cell_mm)
    : m_points(points_mm), m_cell_mm(cell_mm) {
  if (!std::isfinite(cell_mm) || cell_mm <= 0.0)
    throw Error("grid cell size must be a positive number of millimetres");
  std::vector<std::pair<std::int64_t, std::uint32_t>> keyed;
  keyed.reserve(m_points.size());
  bool first = true;
  for (std::uint32_t i = 0; i < m_points.size(); ++i) {
    const Eigen::Vector3f& p = m_points[i];
    if (!p.allFinite())
      continue;
    const Eigen::Vector3i c(int(cellOf(p.x(), cell_mm)), int(cellOf(p.y(), cell_mm)),
                            int(cellOf(p.z(), cell_mm)));
    if (first) {
      m_min_cell = m_max_cell = c;
      first = false;
    }
    m_min_cell = m_min_cell.cwiseMin(c);
    m_max_cell = m_max_cell.cwiseMax(c);
    keyed.emplace_back(key(c.x(), c.y(), c.z()), i);
  }
  std::sort(keyed.begin(), keyed.end());
  m_order.reserve(keyed.size());
  for (std::size_t i = 0; i < keyed.size();) {
    std::size_t j = i;
    while (j < keyed.size() && keyed[j].first == keyed[i].first)
      m_order.push_back(keyed[j++].second);
    m_cells.emplace(keyed[i].first, std::make_pair(std::uint32_t(i), std::uint32_t(j)));
    i = j;
  }
}

std::int64_t PointGrid::key(std::int64_t x, std::int64_t y, std::int64_t z) const {
  return ((x + kCellRange) << 42) | ((y + kCellRange) << 21) | (z + kCellRange);
}

void PointGrid::forEachNear(const Eigen::AlignedBox3d& box_mm,
                            const std::function<bool(std::uint32_t)>& visit) const {
  if (m_order.empty() || box_mm.isEmpty() || !box_mm.min().allFinite() || !box_mm.max().allFinite())
    return;
  Eigen::Vector3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = int(std::max<std::int64_t>(cellOf(box_mm.min()[a], m_cell_mm), m_min_cell[a]));
    hi[a] = int(std::min<std::int64_t>(cellOf(box_mm.max()[a], m_cell_mm), m_max_cell[a]));
    if (lo[a] > hi[a])
      return;
  }
  for (int x = lo.x(); x <= hi.x(); ++x)
    for (int y = lo.y(); y <= hi.y(); ++y)
      for (int z = lo.z(); z <= hi.z(); ++z) {
        const auto it = m_cells.find(key(x, y, z));
        if (it == m_cells.end())
          continue;
        for (std::uint32_t k = it->second.first; k < it->second.second; ++k)
          if (!visit(m_order[k]))
            return;
      }
}

} // namespace scanpick::core::grasp
