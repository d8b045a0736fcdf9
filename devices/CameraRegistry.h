#pragma once
/// @file CameraRegistry.h
/// Opening cameras by id and listing what is attached, across all backends.
///
/// Ids: "phoxi:<serial|ip|aravis id>" (PhoXi over GigE Vision via Aravis; "phoxi-api:<serial>"
/// with the optional PhoXi API backend), "kinect:<index>" (libfreenect), "oni:<path.oni|uri>"
/// (OpenNI2 recording or device), "file:<path or folder>" (PCD/PLY replay).

#include "devices/Camera.h"

#include <memory>
#include <string>
#include <vector>

namespace scanpick::devices {

/// What enumerate() looks at; all on by default.
struct EnumerateOptions {
  bool aravis = true;           ///< GigE Vision cameras (PhoXi scanners)
  bool kinect = true;           ///< Kinect v1 via libfreenect and libusb
  bool openni2 = true;          ///< OpenNI2 devices
  int aravis_timeout_ms = 1000; ///< GigE Vision discovery wait
};

/// Lists the attached cameras of every backend. A backend that fails (no libusb, no network) is
/// skipped with a note in `warnings` instead of failing the whole list; nothing attached gives
/// an empty list.
std::vector<DeviceInfo> enumerateDevices(const EnumerateOptions& options = {},
                                         std::vector<std::string>* warnings = nullptr);

/// Opens a camera by id. Throws DeviceError NotFound for an unknown prefix or device (the
/// message lists the valid forms), and the backend's errors (Busy, Permission ...).
std::unique_ptr<Camera> openCamera(const std::string& id);

} // namespace scanpick::devices
