#include "devices/freenect/KinectCamera.h"

#include "devices/freenect/DisparityConversion.h"
#include "devices/usb/UsbMonitor.h"

#include <algorithm>
#include <cstring>
#include <libfreenect.h>
#include <sys/time.h>

namespace scanpick::devices {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 480;

/// A freenect_open_device failure, explained with what libusb says about the device.
DeviceError openFailure(int index) {
  std::vector<KinectUsbDevice> cameras;
  try {
    for (const auto& d : listKinectUsbDevices())
      if (d.role == KinectUsbRole::Camera)
        cameras.push_back(d);
  } catch (const core::Error&) {
  }
  const std::string which = "Kinect " + std::to_string(index);
  if (index < static_cast<int>(cameras.size())) {
    switch (probeAccess(cameras[static_cast<std::size_t>(index)])) {
    case UsbAccess::Permission:
      return DeviceError(
          DeviceErrorKind::Permission,
          which + ": permission denied on USB " +
              cameras[static_cast<std::size_t>(index)].port_path +
              ": install resources/udev/51-kinect.rules into /etc/udev/rules.d, run "
              "'sudo udevadm control --reload && sudo udevadm trigger', re-plug the Kinect "
              "and make sure your user is in the 'plugdev' group");
    case UsbAccess::Busy:
      return DeviceError(
          DeviceErrorKind::Busy,
          which + " is in use by another program or by the gspca_kinect kernel driver: close "
                  "the other program, or run 'sudo modprobe -r gspca_kinect'");
    case UsbAccess::Gone:
      return DeviceError(DeviceErrorKind::NotFound,
                         which + " was unplugged while opening: plug it in again");
    default:
      break;
    }
  }
  return DeviceError(
      DeviceErrorKind::Protocol,
      which + " could not be opened by libfreenect: re-plug it (the Kinect needs its own "
              "power adapter) and try again");
}

} // namespace

int KinectCamera::count() {
  freenect_context* ctx = nullptr;
  if (freenect_init(&ctx, nullptr) < 0 || !ctx)
    return 0;
  freenect_set_log_level(ctx, FREENECT_LOG_FATAL);
  const int n = freenect_num_devices(ctx);
  freenect_shutdown(ctx);
  return std::max(0, n);
}

KinectCamera::KinectCamera(int index, bool with_rgb) : m_index(index), m_with_rgb(with_rgb) {
  if (index < 0)
    throw DeviceError(DeviceErrorKind::NotFound, "Kinect index must be 0 or more, e.g. kinect:0");
  if (freenect_init(&m_ctx, nullptr) < 0 || !m_ctx)
    throw DeviceError(DeviceErrorKind::Permission,
                      "libfreenect could not start libusb: check that /dev/bus/usb is accessible");
  freenect_set_log_level(m_ctx, FREENECT_LOG_ERROR);
  // Camera for depth/RGB, motor for tilt and LED; audio needs firmware upload and is not used.
  freenect_select_subdevices(
      m_ctx, static_cast<freenect_device_flags>(FREENECT_DEVICE_CAMERA | FREENECT_DEVICE_MOTOR));
  const int n = freenect_num_devices(m_ctx);
  if (index >= n) {
    freenect_shutdown(m_ctx);
    m_ctx = nullptr;
    throw DeviceError(
        DeviceErrorKind::NotFound,
        "no Kinect v1 at index " + std::to_string(index) + " (" + std::to_string(std::max(0, n)) +
            " found): plug it in (USB and its power adapter) and check that 'lsusb' lists "
            "045e:02ae; 'scanpick-cli devices' lists what is attached");
  }
  if (freenect_open_device(m_ctx, &m_dev, index) < 0 || !m_dev) {
    freenect_shutdown(m_ctx);
    m_ctx = nullptr;
    m_dev = nullptr;
    throw openFailure(index);
  }
  freenect_set_user(m_dev, this);
  freenect_set_depth_callback(m_dev, &KinectCamera::onDepth);
  if (freenect_set_depth_mode(
          m_dev, freenect_find_depth_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_DEPTH_11BIT)) < 0 ||
      freenect_start_depth(m_dev) < 0) {
    close();
    throw DeviceError(DeviceErrorKind::Protocol,
                      "Kinect " + std::to_string(index) +
                          " refused 640x480 11-bit depth: re-plug it and try again");
  }
  if (m_with_rgb) {
    freenect_set_video_callback(m_dev, &KinectCamera::onVideo);
    if (freenect_set_video_mode(
            m_dev, freenect_find_video_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_VIDEO_RGB)) < 0 ||
        freenect_start_video(m_dev) < 0)
      m_with_rgb = false; // depth still works; colour is optional
  }
}

KinectCamera::~KinectCamera() {
  stopStream();
  close();
}

void KinectCamera::close() {
  if (m_dev) {
    freenect_stop_depth(m_dev);
    if (m_with_rgb)
      freenect_stop_video(m_dev);
    freenect_close_device(m_dev);
    m_dev = nullptr;
  }
  if (m_ctx) {
    freenect_shutdown(m_ctx);
    m_ctx = nullptr;
  }
}

DeviceInfo KinectCamera::info() const {
  return {"kinect:" + std::to_string(m_index), "freenect", "Microsoft Kinect v1", "", ""};
}

void KinectCamera::requireOpen() const {
  if (!m_dev)
    throw DeviceError(DeviceErrorKind::StreamEnded, "the Kinect was closed: open it again");
}

void KinectCamera::onDepth(freenect_device* dev, void* depth, std::uint32_t timestamp) {
  auto* self = static_cast<KinectCamera*>(freenect_get_user(dev));
  const auto* raw = static_cast<const std::uint16_t*>(depth);
  self->m_depth.assign(raw, raw + kWidth * kHeight);
  self->m_depth_timestamp = timestamp;
  self->m_depth_ready = true;
}

void KinectCamera::onVideo(freenect_device* dev, void* video, std::uint32_t /*timestamp*/) {
  auto* self = static_cast<KinectCamera*>(freenect_get_user(dev));
  const auto* rgb = static_cast<const std::uint8_t*>(video);
  self->m_rgb.assign(rgb, rgb + kWidth * kHeight * 3);
  self->m_rgb_ready = true;
}

Frame KinectCamera::grabFrame(std::chrono::milliseconds timeout) {
  requireOpen();
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + timeout;
  m_depth_ready = false;
  m_rgb_ready = false;
  // Depth is required; RGB is attached when it arrives with the same frame. Each
  // freenect_process_events call handles the USB transfers (or one fakenect dump entry).
  auto pump = [&](Clock::time_point until) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(until - Clock::now());
    timeval tv{static_cast<time_t>(std::max<std::int64_t>(0, left.count()) / 1000000),
               static_cast<suseconds_t>(std::max<std::int64_t>(0, left.count()) % 1000000)};
    return freenect_process_events_timeout(m_ctx, &tv);
  };
  while (!m_depth_ready) {
    if (Clock::now() >= deadline)
      throw DeviceError(DeviceErrorKind::Timeout, "no depth frame from Kinect " +
                                                      std::to_string(m_index) + " within " +
                                                      std::to_string(timeout.count()) +
                                                      " ms: check the cable and the power adapter");
    if (pump(deadline) < 0)
      throw DeviceError(
          DeviceErrorKind::StreamEnded,
          "the Kinect " + std::to_string(m_index) +
              " stream ended (device unplugged or recording exhausted): reopen it to continue");
  }
  // The RGB image of the same moment follows within a few milliseconds.
  const auto rgb_deadline = std::min(deadline, Clock::now() + std::chrono::milliseconds(100));
  while (m_with_rgb && !m_rgb_ready && Clock::now() < rgb_deadline)
    if (pump(rgb_deadline) < 0)
      break; // end of stream: deliver the depth we have; the next capture reports the end

  Frame frame;
  frame.cloud = disparityToCloud(m_depth, kinectDepthIntrinsics());
  if (m_rgb_ready && m_rgb.size() == frame.cloud.size() * 3) {
    frame.cloud.colors.resize(frame.cloud.size());
    for (std::size_t i = 0; i < frame.cloud.size(); ++i)
      frame.cloud.colors[i] = {m_rgb[3 * i], m_rgb[3 * i + 1], m_rgb[3 * i + 2]};
  }
  frame.metadata.device_id = "kinect:" + std::to_string(m_index);
  frame.metadata.sensor = "kinect-v1";
  frame.metadata.intrinsics = kinectDepthIntrinsics();
  // The Kinect's frame timestamp counts a 60 MHz clock.
  frame.metadata.timestamp_us = static_cast<std::int64_t>(m_depth_timestamp) / 60;
  frame.metadata.host_time_us = hostTimeMicros();
  frame.metadata.frame_index = m_frame_index++;
  return frame;
}

void KinectCamera::setTiltDegrees(double degrees) {
  requireOpen();
  if (freenect_set_tilt_degs(m_dev, std::clamp(degrees, -27.0, 27.0)) < 0)
    throw DeviceError(DeviceErrorKind::Unsupported,
                      "the Kinect tilt motor did not respond: it needs the Kinect's power adapter");
}

double KinectCamera::tiltDegrees() {
  requireOpen();
  if (freenect_update_tilt_state(m_dev) < 0)
    throw DeviceError(DeviceErrorKind::Unsupported,
                      "cannot read the Kinect tilt state: it needs the Kinect's power adapter");
  return freenect_get_tilt_degs(freenect_get_tilt_state(m_dev));
}

void KinectCamera::setLed(KinectLed led) {
  requireOpen();
  if (freenect_set_led(m_dev, static_cast<freenect_led_options>(led)) < 0)
    throw DeviceError(DeviceErrorKind::Unsupported, "the Kinect LED did not respond");
}

} // namespace scanpick::devices
