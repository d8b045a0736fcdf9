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
/// the indices. Built by sorting the points by cell, with no tree: feature extraction makes one per
/// round of its search, and building and asking FLANN's tree took two thirds of that search
/// (perf). A radius up to the cell edge looks at 27 cells, found by 9 binary searches. With
/// `max_nn` it keeps the nearest max_nn, at equal distances in the order of the indices, where
/// FLANN keeps whichever its tree met first. Nearest-k search is not offered (throws).
class GridRadiusSearch final : public pcl::search::Search<pcl::PointXYZ> {
public:
  /// `cell_mm` > 0: best the radius the searches will ask for.
  explicit GridRadiusSearch(double cell_mm);

  using pcl::search::Search<pcl::PointXYZ>::nearestKSearch;
  using pcl::search::Search<pcl::PointXYZ>::radiusSearch;

  void setInputCloud(const PointCloudConstPtr& cloud,
                     const IndicesConstPtr& indices = IndicesConstPtr()) override;

  int radiusSearch(const pcl::PointXYZ& point, double radius, pcl::Indices& k_indices,
                   std::vector<float>& k_sqr_distances, unsigned int max_nn = 0) const override;

  /// Not offered: throws pcl::PCLException.
  int nearestKSearch(const pcl::PointXYZ& point, int k, pcl::Indices& k_indices,
                     std::vector<float>& k_sqr_distances) const override;

private:
  using Cell = std::array<std::int64_t, 3>;
  [[nodiscard]] Cell cellOf(const pcl::PointXYZ& p) const;

  double m_cell_mm;
  std::vector<pcl::PointXYZ> m_points;   ///< sorted by cell, then by position in the indices
  std::vector<std::uint32_t> m_position; ///< each point's position in the indices
  std::vector<pcl::index_t> m_index;     ///< each point's index in the cloud
  std::vector<Cell> m_cells;             ///< the occupied cells, sorted
  std::vector<std::uint32_t> m_starts;   ///< each cell's first point; one more at the end
};

} // namespace scanpick::core
