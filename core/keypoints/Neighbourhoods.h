#pragma once
/// @file Neighbourhoods.h
/// Internal to the keypoints module: radius and k-nearest neighbourhoods of the valid points of
/// a cloud, on pixel windows when the cloud is an organized camera grid, on a kd-tree otherwise.

#include "core/cloud/PixelCoordinates.h"
#include "core/cloud/PointCloud.h"

#include <algorithm>
#include <memory>
#include <utility>
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
  /// Calls `visit(j)` for the indices radius() gives, in the same order, without collecting them.
  template <typename Visit> void forEachWithin(int index, double radius_mm, Visit&& visit) const {
    if (!m_organized) {
      thread_local std::vector<int> found;
      radius(index, radius_mm, found);
      for (const int j : found)
        visit(j);
      return;
    }
    const Eigen::Vector3f p = m_cloud.points_mm[static_cast<std::size_t>(index)];
    const float r2 = static_cast<float>(radius_mm * radius_mm);
    const int half = halfWindow(p, radius_mm);
    const int w = static_cast<int>(m_cloud.width), h = static_cast<int>(m_cloud.height);
    const int row = index / w, col = index % w;
    for (int r = std::max(0, row - half); r <= std::min(h - 1, row + half); ++r) {
      const std::size_t base = static_cast<std::size_t>(r) * static_cast<std::size_t>(w);
      for (int c = std::max(0, col - half); c <= std::min(w - 1, col + half); ++c) {
        const auto& q = m_cloud.points_mm[base + static_cast<std::size_t>(c)];
        if ((q - p).squaredNorm() <= r2) // false for NaN
          visit(static_cast<int>(base) + c);
      }
    }
  }
  /// The sum of the offsets q − p (mm) from point `index` (p) to the valid points q within
  /// `radius_mm` (itself included), and how many there are. The float offsets, at most a few
  /// hundred of a few millimetres, are summed exactly in doubles, so the sum does not depend on the
  /// order the points are visited in. Organized clouds test eight pixels of a window row at a
  /// time.
  [[nodiscard]] std::pair<Eigen::Vector3d, std::size_t> offsetSum(int index,
                                                                  double radius_mm) const;
  /// The `n` nearest valid points to point `index` (itself excluded), nearest first; fewer
  /// when the cloud or the window holds fewer. Organized clouds search a pixel window
  /// holding at least 2n pixels.
  void nearest(int index, int n, std::vector<int>& out) const;

private:
  /// Organized clouds: the half size (pixels) of the window holding the ball of `radius_mm` about
  /// `p`.
  [[nodiscard]] int halfWindow(const Eigen::Vector3f& p, double radius_mm) const;

  struct Tree;
  const PointCloud& m_cloud;
  /// Organized clouds: the valid points by pixel, for window scans.
  PixelCoordinates m_pixels;
  std::vector<int> m_valid;
  bool m_organized = false;
  double m_pixel_angle = 0; ///< smallest angle between neighbouring pixel rays, radians
  std::unique_ptr<Tree> m_tree;
};

} // namespace scanpick::core::detail
