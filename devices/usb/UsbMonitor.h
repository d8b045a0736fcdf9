#pragma once
/// @file UsbMonitor.h
/// Kinect v1 USB devices (camera 045e:02ae, motor 045e:02b0, audio 045e:02ad) through libusb:
/// listing, access checks and plug/unplug notifications, without opening a stream.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace scanpick::devices {

/// Which function of a Kinect v1 a USB device is.
enum class KinectUsbRole { Camera, Motor, Audio };

inline constexpr std::uint16_t kMicrosoftVendorId = 0x045e;
inline constexpr std::uint16_t kKinectCameraProductId = 0x02ae;
inline constexpr std::uint16_t kKinectMotorProductId = 0x02b0;
inline constexpr std::uint16_t kKinectAudioProductId = 0x02ad;

/// One Kinect v1 USB device.
struct KinectUsbDevice {
  KinectUsbRole role = KinectUsbRole::Camera;
  int bus = 0;           ///< USB bus number
  int address = 0;       ///< device address on the bus (changes on re-plug)
  std::string port_path; ///< e.g. "1-2.3", stable while the cable stays in the same port
  bool operator==(const KinectUsbDevice&) const = default;
};

/// Result of trying to open a device the way libfreenect would.
enum class UsbAccess { Ok, Permission, Busy, Gone, Other };

/// A plug or unplug event.
struct UsbEvent {
  bool arrived = true; ///< true = plugged in, false = unplugged
  KinectUsbDevice device;
};
using UsbEventCallback = std::function<void(const UsbEvent&)>;

/// Lists the attached Kinect v1 USB devices (all three roles), sorted by bus, address. Empty
/// when nothing is plugged in (not an error). Throws core::Error only when libusb itself cannot
/// start.
std::vector<KinectUsbDevice> listKinectUsbDevices();

/// Tries to open `device` and claim interface 0, then releases it: tells whether a capture
/// would be refused by permissions (no udev rule) or because another program holds it.
UsbAccess probeAccess(const KinectUsbDevice& device);

/// Differences between two listings (pure): devices only in `after` arrive, only in `before`
/// leave. Used by the polling fallback and tested on its own.
std::vector<UsbEvent> diffUsbDevices(const std::vector<KinectUsbDevice>& before,
                                     const std::vector<KinectUsbDevice>& after);

/// Reports Kinect v1 plug/unplug while running, on its own thread: libusb hotplug callbacks when
/// the platform supports them, else polling every `poll_interval_ms`.
class UsbMonitor {
public:
  /// Starts watching; `callback` runs on the monitor thread. Devices present at start are not
  /// reported (call listKinectUsbDevices() for them). Throws core::Error if libusb cannot start.
  explicit UsbMonitor(UsbEventCallback callback, int poll_interval_ms = 500);
  ~UsbMonitor();
  UsbMonitor(const UsbMonitor&) = delete;
  UsbMonitor& operator=(const UsbMonitor&) = delete;

  /// Stops the thread (also done by the destructor).
  void stop();

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

} // namespace scanpick::devices
