#pragma once
/// @file PixelCoordinates.h
/// An organized cloud's points laid out for window scans: one coordinate per array.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <vector>

namespace scanpick::core {

/// Each pixel's point (mm), one coordinate per array, NaN where a pixel has none, and kPadding NaN
/// pixels past the last so that a window row is read eight pixels at a time without a bounds test.
struct PixelCoordinates {
  static constexpr std::size_t kPadding = 8;
  std::vector<float> x, y, z;

  PixelCoordinates() = default;
  /// `pixels` pixels without a point.
  explicit PixelCoordinates(std::size_t pixels)
      : x(pixels + kPadding, kNaN), y(pixels + kPadding, kNaN), z(pixels + kPadding, kNaN) {}
  /// Gives pixel `pixel` the point `p_mm`.
  void set(std::size_t pixel, const Eigen::Vector3f& p_mm) {
    x[pixel] = p_mm.x();
    y[pixel] = p_mm.y();
    z[pixel] = p_mm.z();
  }

private:
  static constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
};

} // namespace scanpick::core
