#pragma once
/// @file PointGrid.h
/// Points hashed into a uniform grid of cubic cells, for the box queries of the collision checks.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace scanpick::core::grasp {

/// The points given (their frame, mm) in cubic cells of `cell_mm`. Immutable after construction,
/// so queries are safe from many threads; visiting order is deterministic (by cell, then by
/// point index).
class PointGrid {
public:
  /// Builds the grid; non-finite points are left out. Throws Error for a cell size that is not a
  /// positive finite number.
  PointGrid(const std::vector<Eigen::Vector3f>& points_mm, double cell_mm);

  /// Calls `visit(index)` for each point whose cell overlaps `box_mm` (a superset of the points
  /// inside it: callers test each point). `visit` returns false to stop early. Index = position in
  /// the vector given to the constructor.
  void forEachNear(const Eigen::AlignedBox3d& box_mm,
                   const std::function<bool(std::uint32_t)>& visit) const;

  [[nodiscard]] const std::vector<Eigen::Vector3f>& points() const { return m_points; }

private:
  [[nodiscard]] std::int64_t key(std::int64_t x, std::int64_t y, std::int64_t z) const;
  std::vector<Eigen::Vector3f> m_points;
  double m_cell_mm;
  /// Point indices sorted by cell; each cell's range [first, last) in it.
  std::vector<std::uint32_t> m_order;
  std::unordered_map<std::int64_t, std::pair<std::uint32_t, std::uint32_t>> m_cells;
  Eigen::Vector3i m_min_cell = Eigen::Vector3i::Zero(), m_max_cell = Eigen::Vector3i::Zero();
};

} // namespace scanpick::core::grasp
