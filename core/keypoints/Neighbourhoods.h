#pragma once
/// @file Neighbourhoods.h
/// Internal to the keypoints module: radius and k-nearest neighbourhoods of the valid points of
/// a cloud, on pixel windows when the cloud is an organized camera grid, on a kd-tree otherwise.

#include "core/cloud/PointCloud.h"

#include <memory>
#include <vector>

namespace scanpick::core::detail {

/// Neighbour queries by input index. Thread-safe for concurrent queries.
class Neighbourhoods {
public:
  /// Builds the search structure for `cloud` (kept by reference: it must outlive this object)
  /// for radius queries up to `max_radius_mm`.
  Neighbourhoods(const PointCloud& cloud, double max_radius_mm);
  ~Neighbourhoods();
  Neighbourhoods(const Neighbourhoods&) = delete;
  Neighbourhoods& operator=(const Neighbourhoods&) = delete;

  /// Valid point indices of the cloud, ascending.
  [[nodiscard]] const std::vector<int>& validIndices() const { return m_valid; }
  /// True when pixel windows are used.
  [[nodiscard]] bool organized() const { return m_organized; }

  /// Appends to `out` the indices of all valid points within `radius_mm` of point `index`
  /// (itself included); `out` is cleared first. `radius_mm` <= the constructor's maximum.
  void radius(int index, double radius_mm, std::vector<int>& out) const;
  /// The `n` nearest valid points to point `index` (itself excluded), nearest first; fewer
  /// when the cloud or the window holds fewer. Organized clouds search a pixel window
  /// holding at least 2n pixels.
  void nearest(int index, int n, std::vector<int>& out) const;

private:
  struct Tree;
  const PointCloud& m_cloud;
  std::vector<int> m_valid;
  bool m_organized = false;
  double m_pixel_angle = 0;  ///< smallest angle between neighbouring pixel rays, radians
  std::unique_ptr<Tree> m_tree;
};

} // namespace scanpick::core::detail
