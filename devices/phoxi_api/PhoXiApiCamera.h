#pragma once
/// @file PhoXiApiCamera.h
/// Photoneo PhoXi scanners through Photoneo's proprietary PhoXi API (id "phoxi-api:<serial>").
/// Built only with -DSCANPICK_WITH_PHOXI_API=ON and Photoneo's PhoXi CMake package (PhoXi
/// Control installed, PHOXI_CONTROL_PATH set); needs the PhoXi Control daemon running. The open
/// GigE Vision path (PhoXiGigECamera) is the default and needs neither.

#include "devices/Camera.h"

#include <memory>
#include <string>
#include <vector>

namespace scanpick::devices {

/// A PhoXi scanner driven through pho::api with software trigger: one TriggerFrame +
/// GetSpecificFrame per capture; PointCloud (mm, (0,0,0) = invalid), NormalMap, ConfidenceMap
/// and Texture become the frame's points, normals, confidence and intensity.
class PhoXiApiCamera final : public Camera {
public:
  /// Connects to the scanner with hardware identification `serial` (e.g. "1711004").
  /// Throws DeviceError NotFound (PhoXi Control not running or scanner unknown), Busy.
  explicit PhoXiApiCamera(const std::string& serial);
  ~PhoXiApiCamera() override;

  [[nodiscard]] DeviceInfo info() const override;
  void close() override;

  /// Scanners PhoXi Control knows about (empty when it is not running).
  static std::vector<DeviceInfo> enumerate();

protected:
  Frame grabFrame(std::chrono::milliseconds timeout) override;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

} // namespace scanpick::devices
