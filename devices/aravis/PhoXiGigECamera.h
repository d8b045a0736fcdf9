#pragma once
/// @file PhoXiGigECamera.h
/// Photoneo PhoXi scanners (firmware >= 1.13) over GigE Vision with Aravis (id
/// "phoxi:<serial|ip>").

#include "devices/Camera.h"

#include <memory>
#include <string>
#include <vector>

namespace scanpick::devices {

/// A GigE Vision 3D scanner driven the way Photoneo documents for PhoXi: continuous
/// acquisition with software trigger (one TriggerSoftware per capture), components Range
/// (Coord3D_ABC32f, or Coord3D_C32f + Scan3d parameters), Intensity, Confidence and Normal,
/// multipart transport when the device supports it. Features a device lacks are skipped, so a
/// single-part camera that streams Coord3D_ABC32f works too (that is how it is tested, against
/// Aravis's fake GigE Vision camera).
class PhoXiGigECamera final : public Camera {
public:
  /// Connects to `name` (Aravis device id, serial number or IP address). Throws DeviceError
  /// NotFound (nothing answers), Busy (another application has control), Unsupported (no 3D
  /// pixel format), Protocol (configuration refused).
  explicit PhoXiGigECamera(const std::string& name);
  ~PhoXiGigECamera() override;

  [[nodiscard]] DeviceInfo info() const override;
  void close() override;

  /// GigE Vision devices on the network (any vendor; PhoXi scanners report vendor "Photoneo").
  static std::vector<DeviceInfo> enumerate();

protected:
  Frame grabFrame(std::chrono::milliseconds timeout) override;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

} // namespace scanpick::devices
