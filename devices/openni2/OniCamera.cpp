#include "devices/openni2/OniCamera.h"

#include <OpenNI.h>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <thread>

namespace scanpick::devices {
namespace {

/// How long a stopped recording's player thread is given to reach its idle loop (close()).
constexpr std::chrono::milliseconds kPlayerSettle{30};

/// OpenNI2 is initialized once per process and stays up: shutting it down while another camera
/// (or a later one) uses it is not supported by the library.
void ensureInitialized() {
  static std::once_flag once;
  static openni::Status status = openni::STATUS_OK;
  static std::string message;
  std::call_once(once, [] {
    status = openni::OpenNI::initialize();
    message = openni::OpenNI::getExtendedError();
  });
  if (status != openni::STATUS_OK)
    throw DeviceError(DeviceErrorKind::Unsupported,
                      "OpenNI2 could not start (" + message +
                          "): reinstall libopenni2-0 and its drivers");
}

std::string lastError() {
  return openni::OpenNI::getExtendedError();
}

} // namespace

struct OniCamera::Impl {
  std::string uri;
  openni::Device device;
  openni::VideoStream depth;
  bool is_file = false;
  int frames_in_file = -1; // -1 = unknown / live device
  int frames_read = 0;
  Intrinsics intrinsics;
  std::string serial;
  std::uint64_t frame_index = 0;
};

OniCamera::OniCamera(const std::string& uri) : m_impl(std::make_unique<Impl>()) {
  ensureInitialized();
  m_impl->uri = uri;
  const bool looks_like_file = uri.size() > 4 && uri.substr(uri.size() - 4) == ".oni";
  if (looks_like_file && !std::filesystem::exists(uri))
    throw DeviceError(DeviceErrorKind::NotFound,
                      "no recording '" + uri + "': check the path after oni:");
  if (m_impl->device.open(uri.c_str()) != openni::STATUS_OK) {
    const std::string why = lastError();
    if (looks_like_file)
      throw DeviceError(
          DeviceErrorKind::Protocol,
          "OpenNI2 cannot play '" + uri + "'" + (why.empty() ? "" : " (" + why + ")") +
              ": the recording is truncated or damaged, or already open in this program");
    const bool busy =
        why.find("busy") != std::string::npos || why.find("claim") != std::string::npos;
    throw DeviceError(busy ? DeviceErrorKind::Busy : DeviceErrorKind::NotFound,
                      "OpenNI2 cannot open '" + uri + "' (" + why + "): " +
                          (busy ? "close the other program using it"
                                : "run 'scanpick-cli devices' for the device URIs"));
  }
  m_impl->is_file = m_impl->device.isFile();
  if (!m_impl->device.hasSensor(openni::SENSOR_DEPTH) ||
      m_impl->depth.create(m_impl->device, openni::SENSOR_DEPTH) != openni::STATUS_OK) {
    const std::string why = lastError();
    m_impl->device.close();
    throw DeviceError(DeviceErrorKind::Unsupported,
                      "'" + uri + "' has no depth stream (" + why + ")");
  }
  if (m_impl->depth.start() != openni::STATUS_OK) {
    const std::string why = lastError();
    m_impl->depth.destroy();
    m_impl->device.close();
    throw DeviceError(DeviceErrorKind::Busy, "cannot start the depth stream of '" + uri + "' (" +
                                                 why +
                                                 "): another program may be using the device");
  }
  if (m_impl->is_file) {
    openni::PlaybackControl* playback = m_impl->device.getPlaybackControl();
    // Manual speed: a frame is produced only when asked for, so no frame is skipped.
    playback->setSpeed(-1.0f);
    playback->setRepeatEnabled(false);
    m_impl->frames_in_file = playback->getNumberOfFrames(m_impl->depth);
  }
  const openni::VideoMode mode = m_impl->depth.getVideoMode();
  Intrinsics& k = m_impl->intrinsics;
  k.width = mode.getResolutionX();
  k.height = mode.getResolutionY();
  k.fx = (k.width / 2.0) / std::tan(m_impl->depth.getHorizontalFieldOfView() / 2.0);
  k.fy = (k.height / 2.0) / std::tan(m_impl->depth.getVerticalFieldOfView() / 2.0);
  k.cx = (k.width - 1) / 2.0;
  k.cy = (k.height - 1) / 2.0;
  char serial[64] = {};
  int size = sizeof serial;
  if (!m_impl->is_file && m_impl->device.getProperty(ONI_DEVICE_PROPERTY_SERIAL_NUMBER, serial,
                                                     &size) == openni::STATUS_OK)
    m_impl->serial = serial;
}

OniCamera::~OniCamera() {
  stopStream();
  close();
}

void OniCamera::close() {
  if (m_impl->depth.isValid()) {
    m_impl->depth.stop();
    // OpenNI2's file player walks its list of streams without its lock, continuously once the
    // recording has ended, every 10 ms once no stream is started; destroying a stream while it
    // walks crashes it (libOniFile, PlayerDevice::MainLoop). Stopped, it settles into its 10 ms
    // sleep before the stream goes.
    if (m_impl->is_file)
      std::this_thread::sleep_for(kPlayerSettle);
    m_impl->depth.destroy();
  }
  if (m_impl->device.isValid())
    m_impl->device.close();
}

DeviceInfo OniCamera::info() const {
  return {"oni:" + m_impl->uri, "openni2", m_impl->is_file ? "OpenNI recording" : "OpenNI2 device",
          m_impl->serial, ""};
}

Frame OniCamera::grabFrame(std::chrono::milliseconds timeout) {
  Impl& d = *m_impl;
  if (!d.depth.isValid())
    throw DeviceError(DeviceErrorKind::StreamEnded, "the OpenNI2 camera was closed: open it again");
  if (d.is_file && d.frames_in_file >= 0 && d.frames_read >= d.frames_in_file)
    throw DeviceError(DeviceErrorKind::StreamEnded, "the recording '" + d.uri + "' ended after " +
                                                        std::to_string(d.frames_read) +
                                                        " frame(s): open it again to replay");
  openni::VideoStream* streams[] = {&d.depth};
  int ready = -1;
  // Without this wait, readFrame on a manual-speed recording blocks forever at the end.
  if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, static_cast<int>(timeout.count())) !=
      openni::STATUS_OK) {
    if (d.is_file)
      throw DeviceError(
          DeviceErrorKind::StreamEnded,
          "the recording '" + d.uri + "' stopped after " + std::to_string(d.frames_read) + " of " +
              std::to_string(d.frames_in_file) + " frame(s): the file is truncated or damaged");
    throw DeviceError(DeviceErrorKind::Timeout,
                      "no depth frame from '" + d.uri + "' within " +
                          std::to_string(timeout.count()) +
                          " ms: check the USB cable, or reopen the device");
  }
  openni::VideoFrameRef ref;
  if (d.depth.readFrame(&ref) != openni::STATUS_OK || !ref.isValid())
    throw DeviceError(DeviceErrorKind::StreamEnded, "reading a depth frame of '" + d.uri +
                                                        "' failed (" + lastError() +
                                                        "): reopen it");
  ++d.frames_read;
  const openni::PixelFormat format = ref.getVideoMode().getPixelFormat();
  const float scale_mm = format == openni::PIXEL_FORMAT_DEPTH_100_UM ? 0.1f : 1.0f;
  if (format != openni::PIXEL_FORMAT_DEPTH_1_MM && format != openni::PIXEL_FORMAT_DEPTH_100_UM)
    throw DeviceError(DeviceErrorKind::Unsupported,
                      "'" + d.uri + "' streams depth in an unsupported pixel format (" +
                          std::to_string(static_cast<int>(format)) + ")");
  const int w = ref.getWidth(), h = ref.getHeight();
  if (w != d.intrinsics.width || h != d.intrinsics.height)
    throw DeviceError(DeviceErrorKind::Protocol,
                      "'" + d.uri + "' changed its depth resolution during streaming");
  const auto* base = static_cast<const std::uint8_t*>(ref.getData());
  Frame frame;
  core::PointCloud& cloud = frame.cloud;
  cloud.width = static_cast<std::uint32_t>(w);
  cloud.height = static_cast<std::uint32_t>(h);
  cloud.points_mm.resize(static_cast<std::size_t>(w) * h);
  const Intrinsics& k = d.intrinsics;
  for (int v = 0; v < h; ++v) {
    const auto* row = reinterpret_cast<const std::uint16_t*>(base + static_cast<std::size_t>(v) *
                                                                        ref.getStrideInBytes());
    for (int u = 0; u < w; ++u) {
      const float z = row[u] * scale_mm;
      cloud.points_mm[static_cast<std::size_t>(v) * w + u] =
          row[u] == 0 ? core::invalidPoint()
                      : Eigen::Vector3f(static_cast<float>((u - k.cx) * z / k.fx),
                                        static_cast<float>((v - k.cy) * z / k.fy), z);
    }
  }
  frame.metadata.device_id = "oni:" + d.uri;
  frame.metadata.sensor = "openni2";
  frame.metadata.serial = d.serial;
  frame.metadata.intrinsics = d.intrinsics;
  frame.metadata.timestamp_us = static_cast<std::int64_t>(ref.getTimestamp());
  frame.metadata.host_time_us = hostTimeMicros();
  frame.metadata.frame_index = d.frame_index++;
  return frame;
}

std::vector<DeviceInfo> OniCamera::enumerate() {
  ensureInitialized();
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  std::vector<DeviceInfo> out;
  for (int i = 0; i < list.getSize(); ++i)
    out.push_back({std::string("oni:") + list[i].getUri(), "openni2",
                   std::string(list[i].getVendor()) + " " + list[i].getName(), "", ""});
  return out;
}

} // namespace scanpick::devices
