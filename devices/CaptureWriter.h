#pragma once
/// @file CaptureWriter.h
/// Saving captured frames: organized PCD (mm) plus a sidecar JSON of metadata, both atomic.
/// Shared by `scanpick-cli capture` and the GUI.

#include "devices/Camera.h"

#include <filesystem>
#include <string>
#include <vector>

namespace scanpick::devices {

/// Sidecar JSON text of a frame: {"format": "scanpick-capture", "version": 1, "device_id",
/// "sensor", "serial", "units": "mm", "width", "height", "timestamp_us", "host_time_us",
/// "frame_index", "intrinsics": {width, height, fx, fy, cx, cy} or null}.
std::string frameMetadataJson(const Frame& frame);

/// Writes `frame.cloud` to `pcd_path` and the metadata next to it (same name, .json), each
/// atomically. Throws core::Error on I/O failure.
void saveFrame(const std::filesystem::path& pcd_path, const Frame& frame);

/// Output path of frame `index` of `count`: `out` itself when count == 1, else
/// "<stem>-000<ext>", "<stem>-001<ext>" ...
std::filesystem::path framePath(const std::filesystem::path& out, std::size_t index,
                                std::size_t count);

/// Captures `count` frames from `camera` (each within `timeout`) and saves them with saveFrame.
/// Frames are saved as they arrive: on an error the frames already saved stay (each one
/// complete, never a partial file) and the DeviceError propagates, its message extended with
/// how many were saved. Returns the PCD paths written.
std::vector<std::filesystem::path> captureToFiles(Camera& camera, const std::filesystem::path& out,
                                                  std::size_t count,
                                                  std::chrono::milliseconds timeout);

} // namespace scanpick::devices
