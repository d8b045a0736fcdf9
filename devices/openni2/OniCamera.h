#pragma once
/// @file OniCamera.h
/// OpenNI2 depth cameras (PrimeSense Carmine, Asus Xtion ...) and .oni recordings
/// (id "oni:<path.oni or device uri>").

#include "devices/Camera.h"

#include <memory>
#include <string>
#include <vector>

namespace scanpick::devices {

/// An OpenNI2 device or recording; delivers the depth stream as an organized cloud (mm) on the
/// depth camera's pinhole model derived from its fields of view.
///
/// Recordings play in manual mode, frame by frame and without repeat (Debian's libOniFile
/// crashes on seek, so playback is strictly sequential): after the last frame, or at the point
/// where a truncated file stops, capture() throws DeviceError StreamEnded.
class OniCamera final : public Camera {
public:
  /// Opens `uri` (an .oni path or a device URI from enumerate()). Throws DeviceError NotFound
  /// (no such file/device), Busy, Unsupported (no depth stream) or Protocol.
  explicit OniCamera(const std::string& uri);
  ~OniCamera() override;

  [[nodiscard]] DeviceInfo info() const override;
  void close() override;

  /// OpenNI2 devices attached (recordings are not listed).
  static std::vector<DeviceInfo> enumerate();

protected:
  Frame grabFrame(std::chrono::milliseconds timeout) override;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

} // namespace scanpick::devices
