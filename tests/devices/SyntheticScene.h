#pragma once
// An organized synthetic scene for camera tests: a tilted plane (the bin floor) with a box on it,
// seen by a pinhole camera, in millimetres. Cells without a surface (a shadow strip at the left
// edge) are invalid, as a structured-light scanner reports them.
#include "core/cloud/PointCloud.h"

#include <cmath>

namespace scanpick::test {

/// width x height grid, focal length `f_px`; the plane is 800 mm away, tilted 10° about x; the
/// box (120 x 80 mm footprint, 60 mm tall) sits in the middle. `z_offset_mm` shifts everything
/// (lets a test tell frames apart).
inline core::PointCloud syntheticBinScene(std::uint32_t width, std::uint32_t height,
                                          double f_px = 400.0, float z_offset_mm = 0.0f) {
  core::PointCloud cloud;
  cloud.width = width;
  cloud.height = height;
  cloud.points_mm.resize(static_cast<std::size_t>(width) * height);
  const double cx = (width - 1) / 2.0, cy = (height - 1) / 2.0;
  const double tilt = 10.0 * 3.14159265358979 / 180.0;
  for (std::uint32_t v = 0; v < height; ++v)
    for (std::uint32_t u = 0; u < width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * width + u;
      if (u < width / 20) { // shadow strip: no measurement
        cloud.points_mm[i] = core::invalidPoint();
        continue;
      }
      const double rx = (u - cx) / f_px, ry = (v - cy) / f_px;
      // Plane z = 800 + tan(tilt) * y  ->  z = 800 / (1 - tan(tilt) ry).
      double z = 800.0 / (1.0 - std::tan(tilt) * ry);
      const double x = rx * z, y = ry * z;
      if (std::abs(x) < 60.0 && std::abs(y) < 40.0)
        z -= 60.0; // box top
      cloud.points_mm[i] = {static_cast<float>(rx * z), static_cast<float>(ry * z),
                            static_cast<float>(z) + z_offset_mm};
    }
  return cloud;
}

} // namespace scanpick::test
