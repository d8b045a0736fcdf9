#pragma once
/// @file Sensor.h
/// Structured-light sensor geometry: pinhole camera intrinsics and where the projector sits.
/// The scene frame is the camera frame (see docs/file-formats.md).

#include "core/common/Rounding.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core {

/// A structured-light sensor: a pinhole camera and a projector offset by a baseline.
struct SensorModel {
  std::string preset;        ///< preset name ("phoxi-m-1032", "kinect-v1", ...) or "custom"
  int width = 0, height = 0; ///< image size, pixels
  double fx = 0, fy = 0, cx = 0, cy = 0; ///< pinhole intrinsics, pixels
  /// Projector pose in the camera (= scene) frame. Its origin is the projector's optical centre.
  Eigen::Isometry3d T_camera_projector = Eigen::Isometry3d::Identity();
  double min_range_mm = 0, max_range_mm = 0; ///< working range along the optical axis
  double nominal_distance_mm = 0;            ///< focus / sweet-spot distance
  double noise_sigma_mm = 0;                 ///< z-noise (PhoXi); Kinect noise is in sim/

  /// Camera centre in the scene frame (the origin).
  [[nodiscard]] Eigen::Vector3d cameraPosition() const { return Eigen::Vector3d::Zero(); }
  /// Projector centre in the scene frame.
  [[nodiscard]] Eigen::Vector3d projectorPosition() const {
    return T_camera_projector.translation();
  }
  /// Projects a camera-frame point (mm, z > 0) to pixel coordinates.
  [[nodiscard]] Eigen::Vector2d project(const Eigen::Vector3d& p_camera_mm) const {
    return {fx * p_camera_mm.x() / p_camera_mm.z() + cx,
            fy * p_camera_mm.y() / p_camera_mm.z() + cy};
  }
  /// The pixel (column, row) where a camera-frame point (mm) projects, halves rounded away from
  /// zero, each coordinate first clamped to ±1e6 (far outside any image, so that points near the
  /// camera's plane cannot overflow); none for z ≤ 0 or a projection that is not a number. It may
  /// lie outside the image (inImage()).
  [[nodiscard]] std::optional<Eigen::Vector2i> pixelOf(const Eigen::Vector3f& p_camera_mm) const {
    if (!(p_camera_mm.z() > 0.0f))
      return std::nullopt;
    const Eigen::Vector2d uv = project(p_camera_mm.cast<double>());
    if (!uv.allFinite())
      return std::nullopt;
    return Eigen::Vector2i(int(roundHalfAway(std::clamp(uv.x(), -1e6, 1e6))),
                           int(roundHalfAway(std::clamp(uv.y(), -1e6, 1e6))));
  }
  /// Whether `pixel` (column, row) lies in the image.
  [[nodiscard]] bool inImage(const Eigen::Vector2i& pixel) const {
    return pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() < width && pixel.y() < height;
  }
  /// The index of `pixel` (column, row; inImage()) in a row-major image of the sensor's width.
  [[nodiscard]] std::size_t pixelIndex(const Eigen::Vector2i& pixel) const {
    return std::size_t(pixel.y()) * std::size_t(width) + std::size_t(pixel.x());
  }
};

/// Sensor presets: "phoxi-m-1032" (PhoXi 3D Scanner M, 1032x772), "phoxi-m-2064" (2064x1544),
/// "kinect-v1" (640x480, 58°x45°). Throws Error listing the known names for an unknown one.
SensorModel sensorPreset(const std::string& name);

/// Names of all presets.
std::vector<std::string> sensorPresetNames();

} // namespace scanpick::core
