#include "devices/file/FileCamera.h"

#include "core/cloud/CloudIo.h"
#include "core/cloud/Units.h"

#include <algorithm>

namespace scanpick::devices {
namespace {

bool isCloudFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".pcd" || ext == ".ply";
}

} // namespace

FileCamera::FileCamera(const std::filesystem::path& path, bool loop,
                       std::optional<core::LengthUnit> units)
    : m_path(path), m_loop(loop), m_units(units) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(path, ec))
      if (entry.is_regular_file() && isCloudFile(entry.path()))
        m_files.push_back(entry.path());
    std::sort(m_files.begin(), m_files.end());
    if (m_files.empty())
      throw DeviceError(
          DeviceErrorKind::NotFound,
          "folder '" + path.string() +
              "' holds no .pcd or .ply file: point file: at a cloud file or a folder of them");
  } else if (std::filesystem::is_regular_file(path, ec)) {
    if (!isCloudFile(path))
      throw DeviceError(DeviceErrorKind::Unsupported,
                        "'" + path.string() + "' is not a .pcd or .ply file");
    m_files.push_back(path);
  } else {
    throw DeviceError(DeviceErrorKind::NotFound,
                      "no file or folder '" + path.string() + "': check the path after file:");
  }
}

FileCamera::~FileCamera() {
  stopStream();
  close();
}

DeviceInfo FileCamera::info() const {
  return {"file:" + m_path.string(), "file", "cloud files (" + std::to_string(m_files.size()) + ")",
          "", ""};
}

void FileCamera::close() {
  m_closed = true;
}

Frame FileCamera::grabFrame(std::chrono::milliseconds /*timeout*/) {
  if (m_closed)
    throw DeviceError(DeviceErrorKind::StreamEnded, "the file camera was closed: open it again");
  if (m_next >= m_files.size()) {
    if (!m_loop)
      throw DeviceError(DeviceErrorKind::StreamEnded,
                        "all " + std::to_string(m_files.size()) + " file(s) of '" +
                            m_path.string() + "' were replayed: open the camera again to restart");
    m_next = 0;
  }
  const std::filesystem::path file = m_files[m_next++];
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw DeviceError(DeviceErrorKind::StreamEnded,
                      "file '" + file.string() +
                          "' vanished during replay: restore it or reopen the folder");
  Frame frame;
  try {
    // Read as millimetres first, then decide the unit from the extent unless forced.
    core::LoadedCloud loaded = core::loadCloud(file, core::LengthUnit::Millimetres);
    const core::LengthUnit unit =
        m_units ? *m_units
                : core::guessLengthUnit(loaded.cloud).value_or(core::LengthUnit::Millimetres);
    if (unit == core::LengthUnit::Metres)
      for (auto& p : loaded.cloud.points_mm)
        p *= 1000.0f;
    frame.cloud = std::move(loaded.cloud);
  } catch (const core::Error& e) {
    throw DeviceError(DeviceErrorKind::Protocol,
                      std::string("cannot replay '") + file.string() + "': " + e.what());
  }
  frame.metadata.device_id = "file:" + m_path.string();
  frame.metadata.sensor = "file";
  frame.metadata.serial = file.filename().string();
  frame.metadata.frame_index = m_frame_index++;
  // A replayed file has no device clock: use the index at a nominal 30 Hz so timestamps are
  // deterministic and increasing.
  frame.metadata.timestamp_us = static_cast<std::int64_t>(frame.metadata.frame_index) * 33333;
  frame.metadata.host_time_us = hostTimeMicros();
  return frame;
}

} // namespace scanpick::devices
