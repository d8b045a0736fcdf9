#pragma once
/// @file PointCloud.h
/// The core's point cloud: a plain value type in millimetres, organized (a camera grid) or not.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace scanpick::core {

/// A point cloud in millimetres. Invalid points (no measurement) are NaN in all coordinates.
///
/// Organized clouds keep the sensor's grid: `height > 1` and `points_mm.size() == width * height`,
/// row-major (`index = row * width + column`). Unorganized clouds have `height == 1`.
/// Optional channels are either empty or the same size as `points_mm`.
struct PointCloud {
  std::uint32_t width = 0;                ///< columns (organized) or number of points (unorganized)
  std::uint32_t height = 1;               ///< rows; 1 for an unorganized cloud
  std::vector<Eigen::Vector3f> points_mm; ///< positions, millimetres
  std::vector<Eigen::Vector3f> normals;   ///< unit normals, optional
  std::vector<std::array<std::uint8_t, 3>> colors; ///< RGB, optional
  std::vector<float> intensity;                    ///< sensor intensity, optional
  std::vector<std::uint8_t> confidence;            ///< 0 = invalid, optional

  /// True when the cloud keeps a sensor grid (height > 1).
  [[nodiscard]] bool isOrganized() const { return height > 1; }
  /// Number of grid cells / points, valid or not.
  [[nodiscard]] std::size_t size() const { return points_mm.size(); }
  [[nodiscard]] bool empty() const { return points_mm.empty(); }
  /// Number of points with finite coordinates.
  [[nodiscard]] std::size_t validCount() const;
  /// Whether any point is valid: stops at the first one, where validCount() visits them all.
  [[nodiscard]] bool hasValidPoint() const;
  /// Makes an unorganized cloud from `points` (width = size, height = 1).
  static PointCloud fromPoints(std::vector<Eigen::Vector3f> points);
  /// Checks the size invariants; throws Error naming the broken one.
  void validate() const;
};

/// A quiet NaN point, the marker of an invalid measurement.
inline Eigen::Vector3f invalidPoint() {
  return Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
}
/// True when all three coordinates are finite.
inline bool isValid(const Eigen::Vector3f& p) {
  return p.allFinite();
}

/// Axis-aligned bounding box of the valid points (empty box if none).
Eigen::AlignedBox3f boundingBox(const PointCloud& cloud);

/// Copy of the points whose index `keep` accepts, in order, unorganized; other channels follow
/// their points.
PointCloud selectPoints(const PointCloud& cloud, const std::function<bool(std::size_t)>& keep);

/// Copy of the valid points only, unorganized; other channels follow their points.
PointCloud dropInvalid(const PointCloud& cloud);

/// Applies a rigid transform (millimetres) to points and normals; NaN points stay NaN.
PointCloud transformed(const PointCloud& cloud, const Eigen::Isometry3f& T);

} // namespace scanpick::core
