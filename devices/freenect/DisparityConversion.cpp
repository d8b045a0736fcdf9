#include "devices/freenect/DisparityConversion.h"

#include "core/cloud/Sensor.h"

#include <cmath>

namespace scanpick::devices {

float disparityToDepthMm(std::uint16_t raw) {
  if (raw >= kDisparityNoData)
    return std::numeric_limits<float>::quiet_NaN();
  const double inverse_m = raw * kDisparityScale + kDisparityOffset;
  if (inverse_m <= 0.0)
    return std::numeric_limits<float>::quiet_NaN();
  return static_cast<float>(1000.0 / inverse_m);
}

std::uint16_t depthMmToDisparity(float depth_mm) {
  if (!std::isfinite(depth_mm) || depth_mm <= 0.0f)
    return kDisparityNoData;
  const double raw = (1000.0 / depth_mm - kDisparityOffset) / kDisparityScale;
  const double rounded = std::round(raw);
  if (rounded < 0.0 || rounded >= kDisparityNoData)
    return kDisparityNoData;
  const auto value = static_cast<std::uint16_t>(rounded);
  // Values whose decoded depth is invalid (denominator <= 0) are no data too.
  return std::isfinite(disparityToDepthMm(value)) ? value : kDisparityNoData;
}

double disparityQuantizationMm(double depth_mm) {
  const double z_m = depth_mm / 1000.0;
  return 0.5 * -kDisparityScale * z_m * z_m * 1000.0;
}

Intrinsics kinectDepthIntrinsics() {
  const core::SensorModel s = core::sensorPreset("kinect-v1");
  return {s.width, s.height, s.fx, s.fy, s.cx, s.cy};
}

core::PointCloud disparityToCloud(std::span<const std::uint16_t> raw, const Intrinsics& k) {
  const auto expected = static_cast<std::size_t>(k.width) * static_cast<std::size_t>(k.height);
  if (raw.size() != expected || expected == 0)
    throw DeviceError(DeviceErrorKind::Protocol,
                      "depth image has " + std::to_string(raw.size()) + " pixels, expected " +
                          std::to_string(expected) +
                          ": the Kinect must run in 640x480 11-bit mode");
  core::PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(k.width);
  cloud.height = static_cast<std::uint32_t>(k.height);
  cloud.points_mm.resize(expected);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * k.width + u;
      const float z = disparityToDepthMm(raw[i]);
      if (!std::isfinite(z)) {
        cloud.points_mm[i] = core::invalidPoint();
        continue;
      }
      cloud.points_mm[i] = {static_cast<float>((u - k.cx) * z / k.fx),
                            static_cast<float>((v - k.cy) * z / k.fy), z};
    }
  return cloud;
}

} // namespace scanpick::devices
