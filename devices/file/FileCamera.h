#pragma once
/// @file FileCamera.h
/// A PCD/PLY file, or a folder of them, replayed as a camera (id "file:<path>").

#include "core/cloud/Units.h"
#include "devices/Camera.h"

#include <filesystem>
#include <optional>
#include <vector>

namespace scanpick::devices {

/// Replays one cloud file or every .pcd/.ply in a folder (sorted by name), one per capture.
///
/// Units: files are read as millimetres unless the extent says metres
/// (core::guessLengthUnit), or `units` forces one. After the last file, capture() throws
/// DeviceError StreamEnded unless `loop` is set. A file that vanished or is unreadable gives
/// StreamEnded / Protocol naming the file.
class FileCamera final : public Camera {
public:
  /// Opens `path`; throws DeviceError NotFound when it does not exist or holds no cloud file.
  explicit FileCamera(const std::filesystem::path& path, bool loop = false,
                      std::optional<core::LengthUnit> units = std::nullopt);
  ~FileCamera() override;

  [[nodiscard]] DeviceInfo info() const override;
  void close() override;
  /// The files replayed, in order.
  [[nodiscard]] const std::vector<std::filesystem::path>& files() const { return m_files; }

protected:
  Frame grabFrame(std::chrono::milliseconds timeout) override;

private:
  std::filesystem::path m_path;
  std::vector<std::filesystem::path> m_files;
  std::size_t m_next = 0;
  std::uint64_t m_frame_index = 0;
  bool m_loop = false;
  bool m_closed = false;
  std::optional<core::LengthUnit> m_units;
};

} // namespace scanpick::devices
