#include "devices/CaptureWriter.h"

#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/common/JsonText.h"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace scanpick::devices {

std::string frameMetadataJson(const Frame& frame) {
  const FrameMetadata& m = frame.metadata;
  nlohmann::ordered_json j;
  j["format"] = "scanpick-capture";
  j["version"] = 1;
  j["device_id"] = m.device_id;
  j["sensor"] = m.sensor;
  j["serial"] = m.serial;
  j["units"] = "mm";
  j["width"] = frame.cloud.width;
  j["height"] = frame.cloud.height;
  j["timestamp_us"] = m.timestamp_us;
  j["host_time_us"] = m.host_time_us;
  j["frame_index"] = m.frame_index;
  if (m.intrinsics) {
    const Intrinsics& k = *m.intrinsics;
    j["intrinsics"] = {{"width", k.width}, {"height", k.height}, {"fx", k.fx},
                       {"fy", k.fy},       {"cx", k.cx},         {"cy", k.cy}};
  } else {
    j["intrinsics"] = nullptr;
  }
  return core::dumpJsonText(j, 2) + "\n";
}

void saveFrame(const std::filesystem::path& pcd_path, const Frame& frame) {
  core::saveCloudPcd(pcd_path, frame.cloud);
  std::filesystem::path json_path = pcd_path;
  json_path.replace_extension(".json");
  core::writeFileAtomic(json_path, frameMetadataJson(frame));
}

std::filesystem::path framePath(const std::filesystem::path& out, std::size_t index,
                                std::size_t count) {
  if (count == 1)
    return out;
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "-%03zu", index);
  std::filesystem::path p =
      out.parent_path() / (out.stem().string() + suffix + out.extension().string());
  return p;
}

std::vector<std::filesystem::path> captureToFiles(Camera& camera, const std::filesystem::path& out,
                                                  std::size_t count,
                                                  std::chrono::milliseconds timeout) {
  std::vector<std::filesystem::path> written;
  for (std::size_t i = 0; i < count; ++i) {
    Frame frame;
    try {
      frame = camera.capture(timeout);
    } catch (const DeviceError& e) {
      if (written.empty())
        throw;
      throw DeviceError(e.kind(), std::string(e.what()) + " (" + std::to_string(written.size()) +
                                      " of " + std::to_string(count) +
                                      " frame(s) were saved before this)");
    }
    const std::filesystem::path path = framePath(out, i, count);
    saveFrame(path, frame);
    written.push_back(path);
  }
  return written;
}

} // namespace scanpick::devices
