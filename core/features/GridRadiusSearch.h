#pragma once
/// @file GridRadiusSearch.h
/// Radius search over a uniform grid, answering as PCL's sorted kd-tree search does, for the
/// localized sampling of feature extraction.

#include <array>
#include <cstdint>
#include <pcl/point_types.h>
#include <pcl/search/search.h>
#include <vector>

namespace scanpick::core {

/// The points of a cloud's indices binned into cubes of edge `cell_mm`. Its radius search gives
/// what `pcl::search::KdTree` (sorted results) gives over the same cloud and indices, bit for bit
/// and in the same order: the points whose float squared distance, summed as FLANN sums it, is
/// below the float square of the radius, nearest first and, at equal distances, in the order of
/// the indices. Built by sorting the points by cell, with no tree: feature extraction asks for a
/// new subset of its keypoints each round of its search, and building and asking FLANN's tree took
/// two thirds of that search (perf). `setInputCloud` bins the whole cloud once; `setIndices` then
/// lays out another subset of it by a counting sort over those cells. A radius up to the cell edge
/// looks at the query cell's occupied neighbours, listed when the cloud is binned. With `max_nn`
/// it keeps the nearest max_nn, at equal distances in the order of the indices, where FLANN keeps
/// whichever its tree met first. Nearest-k search is not offered (throws). Radius searches may run
/// on several threads at once; setting the cloud or the indices may not run beside them.
class GridRadiusSearch final : public pcl::search::Search<pcl::PointXYZ> {
public:
  /// `cell_mm` > 0: best the radius the searches will ask for.
  explicit GridRadiusSearch(double cell_mm);

  using pcl::search::Search<pcl::PointXYZ>::nearestKSearch;
  using pcl::search::Search<pcl::PointXYZ>::radiusSearch;

  /// Bins every finite point of `cloud`, then sets `indices` (all points when null).
  void setInputCloud(const PointCloudConstPtr& cloud,
                     const IndicesConstPtr& indices = IndicesConstPtr()) override;

  /// Searches another subset of the cloud last set, whose points must not have changed since.
  void setIndices(const IndicesConstPtr& indices);

  int radiusSearch(const pcl::PointXYZ& point, double radius, pcl::Indices& k_indices,
                   std::vector<float>& k_sqr_distances, unsigned int max_nn = 0) const override;

  /// Not offered: throws pcl::PCLException.
  int nearestKSearch(const pcl::PointXYZ& point, int k, pcl::Indices& k_indices,
                     std::vector<float>& k_sqr_distances) const override;

private:
  using Cell = std::array<std::int64_t, 3>;
  static constexpr std::uint32_t kNoCell = ~std::uint32_t{0};
  [[nodiscard]] Cell cellOf(const pcl::PointXYZ& p) const;
  /// Calls `visit(cell)` for each occupied cell within `reach` cells of `centre` along each axis.
  template <typename Visit>
  void forEachCellNear(const Cell& centre, std::int64_t reach, Visit&& visit) const;

  double m_cell_mm;
  // The cloud binned: the occupied cells sorted, each point's cell (kNoCell if not finite), and
  // each cell's occupied neighbours (those within one cell along each axis, itself included).
  std::vector<Cell> m_cells;
  std::vector<std::uint32_t> m_cell_of_point;
  static constexpr std::size_t kMaxNeighbours = 27;
  std::vector<std::uint32_t> m_neighbours; ///< kMaxNeighbours slots per cell
  std::vector<std::uint8_t> m_neighbour_count;
  // The finite points of the indices (their positions are their ranks among them), laid out by
  // cell and, within a cell, by position.
  std::vector<pcl::index_t> m_kept;      ///< each position's index in the cloud
  std::vector<pcl::PointXYZ> m_points;   ///< the laid-out points
  std::vector<std::uint32_t> m_position; ///< each laid-out point's position
  std::vector<std::uint32_t> m_starts;   ///< each cell's first laid-out point; one more at the end
};

} // namespace scanpick::core
