#pragma once
/// @file DisparityConversion.h
/// Kinect v1 raw 11-bit disparity <-> depth, and depth image -> organized cloud. Pure functions,
/// so the conversion is ours (not libfreenect's registration code, which fakenect lacks) and is
/// tested on its own.
///
/// Model (ROS openni_camera / libfreenect wiki calibration of the Kinect v1 IR camera):
///   z_m = 1 / (raw * kDisparityScale + kDisparityOffset), kDisparityScale = -0.0030711016,
///   kDisparityOffset = 3.3309495161; raw 2047 = no data; raw >= 1084 gives z <= 0 (invalid).
/// One raw step changes z by about 3.07 mm * z_m^2 (3.1 mm at 1 m, 12.3 mm at 2 m); a round trip
/// through raw values moves a depth by at most half of that.

#include "devices/Camera.h"

#include <cstdint>
#include <span>

namespace scanpick::devices {

inline constexpr double kDisparityScale = -0.0030711016; ///< per raw unit, 1/m
inline constexpr double kDisparityOffset = 3.3309495161; ///< 1/m
inline constexpr std::uint16_t kDisparityNoData = 2047;  ///< raw value of "no measurement"

/// Depth (mm) of a raw disparity, or NaN for no data / out of the model's range.
float disparityToDepthMm(std::uint16_t raw);

/// Nearest raw disparity for a depth (mm); kDisparityNoData when z is not finite or outside the
/// representable range (raw 0..1083, i.e. z from 300 mm outwards).
std::uint16_t depthMmToDisparity(float depth_mm);

/// Half of one disparity step at `depth_mm`: the largest |Δz| a round trip through raw values can
/// introduce (mm).
double disparityQuantizationMm(double depth_mm);

/// Intrinsics of the Kinect v1 depth camera: core::sensorPreset("kinect-v1") (640x480,
/// 58°x45° field of view, centre 319.5, 239.5).
Intrinsics kinectDepthIntrinsics();

/// Builds the organized cloud (mm) of a raw disparity image (row-major, width x height) with the
/// pinhole model: x = (u - cx) z / fx, y = (v - cy) z / fy. Throws DeviceError Protocol when the
/// image size does not match the intrinsics.
core::PointCloud disparityToCloud(std::span<const std::uint16_t> raw, const Intrinsics& intrinsics);

} // namespace scanpick::devices
