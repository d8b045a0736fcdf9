#pragma once
/// @file KinectCamera.h
/// Microsoft Kinect v1 through libfreenect (id "kinect:<index>"): depth converted to an
/// organized cloud with our own DisparityConversion, RGB as colour, tilt motor and LED.

#include "devices/Camera.h"

#include <cstdint>
#include <vector>

struct _freenect_context;
struct _freenect_device;

namespace scanpick::devices {

/// Kinect v1 LED states (values of libfreenect's freenect_led_options).
enum class KinectLed {
  Off = 0,
  Green = 1,
  Red = 2,
  Yellow = 3,
  BlinkGreen = 4,
  BlinkRedYellow = 6
};

/// A Kinect v1 opened through libfreenect.
///
/// Depth runs in 640x480 11-bit mode and video in 640x480 RGB (the only modes Debian's fakenect
/// replays too). The colour channel is the RGB camera's image on the same pixel grid, *not*
/// registered to depth (the RGB camera sits about 25 mm beside the IR camera). Only functions
/// present in Debian's fake libfreenect are called, so the same code runs under fakenect.
class KinectCamera final : public Camera {
public:
  /// Opens the `index`-th Kinect (0-based). Throws DeviceError NotFound (no such Kinect),
  /// Permission (no udev rule), Busy (another program or kernel driver holds it).
  explicit KinectCamera(int index, bool with_rgb = true);
  ~KinectCamera() override;

  [[nodiscard]] DeviceInfo info() const override;
  void close() override;

  /// Number of Kinect v1 cameras libfreenect sees (0 when none or when libusb cannot start).
  static int count();

  /// Moves the tilt motor to `degrees` (clamped to the motor's ±27°). Throws DeviceError on
  /// failure.
  void setTiltDegrees(double degrees);
  /// Current tilt angle read from the motor's accelerometer, degrees.
  double tiltDegrees();
  /// Sets the front LED.
  void setLed(KinectLed led);

protected:
  Frame grabFrame(std::chrono::milliseconds timeout) override;

private:
  static void onDepth(_freenect_device* dev, void* depth, std::uint32_t timestamp);
  static void onVideo(_freenect_device* dev, void* video, std::uint32_t timestamp);
  void requireOpen() const;

  int m_index = 0;
  bool m_with_rgb = true;
  _freenect_context* m_ctx = nullptr;
  _freenect_device* m_dev = nullptr;
  std::vector<std::uint16_t> m_depth;
  std::vector<std::uint8_t> m_rgb;
  std::uint32_t m_depth_timestamp = 0;
  bool m_depth_ready = false;
  bool m_rgb_ready = false;
  std::uint64_t m_frame_index = 0;
};

} // namespace scanpick::devices
