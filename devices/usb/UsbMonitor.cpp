#include "devices/usb/UsbMonitor.h"

#include "core/common/Error.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <libusb.h>
#include <mutex>
#include <thread>

namespace scanpick::devices {
namespace {

/// RAII libusb context.
struct UsbContext {
  libusb_context* ctx = nullptr;
  UsbContext() {
    const int r = libusb_init(&ctx);
    if (r != 0)
      throw core::Error(std::string("cannot start libusb (") + libusb_error_name(r) +
                        "): is /dev/bus/usb available (in a container, pass it through)?");
  }
  ~UsbContext() { libusb_exit(ctx); }
  UsbContext(const UsbContext&) = delete;
  UsbContext& operator=(const UsbContext&) = delete;
};

bool kinectRole(const libusb_device_descriptor& d, KinectUsbRole& role) {
  if (d.idVendor != kMicrosoftVendorId)
    return false;
  switch (d.idProduct) {
  case kKinectCameraProductId:
    role = KinectUsbRole::Camera;
    return true;
  case kKinectMotorProductId:
    role = KinectUsbRole::Motor;
    return true;
  case kKinectAudioProductId:
    role = KinectUsbRole::Audio;
    return true;
  default:
    return false;
  }
}

KinectUsbDevice describe(libusb_device* dev, KinectUsbRole role) {
  KinectUsbDevice out;
  out.role = role;
  out.bus = libusb_get_bus_number(dev);
  out.address = libusb_get_device_address(dev);
  std::uint8_t ports[8];
  const int n = libusb_get_port_numbers(dev, ports, sizeof ports);
  out.port_path = std::to_string(out.bus);
  for (int i = 0; i < n; ++i) {
    out.port_path.push_back(i == 0 ? '-' : '.');
    out.port_path.append(std::to_string(ports[i]));
  }
  return out;
}

std::vector<KinectUsbDevice> list(libusb_context* ctx) {
  std::vector<KinectUsbDevice> out;
  libusb_device** devs = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &devs);
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor d{};
    KinectUsbRole role{};
    if (libusb_get_device_descriptor(devs[i], &d) == 0 && kinectRole(d, role))
      out.push_back(describe(devs[i], role));
  }
  if (devs)
    libusb_free_device_list(devs, 1);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return std::tie(a.bus, a.address) < std::tie(b.bus, b.address);
  });
  return out;
}

} // namespace

std::vector<KinectUsbDevice> listKinectUsbDevices() {
  UsbContext usb;
  return list(usb.ctx);
}

UsbAccess probeAccess(const KinectUsbDevice& wanted) {
  UsbContext usb;
  libusb_device** devs = nullptr;
  const ssize_t n = libusb_get_device_list(usb.ctx, &devs);
  UsbAccess result = UsbAccess::Gone;
  for (ssize_t i = 0; i < n; ++i) {
    if (libusb_get_bus_number(devs[i]) != wanted.bus ||
        libusb_get_device_address(devs[i]) != wanted.address)
      continue;
    libusb_device_handle* handle = nullptr;
    const int r = libusb_open(devs[i], &handle);
    if (r == LIBUSB_ERROR_ACCESS) {
      result = UsbAccess::Permission;
    } else if (r == LIBUSB_ERROR_NO_DEVICE) {
      result = UsbAccess::Gone;
    } else if (r != 0) {
      result = UsbAccess::Other;
    } else {
      // A kernel driver (gspca_kinect) or another program holding interface 0 makes it busy.
      const bool kernel = libusb_kernel_driver_active(handle, 0) == 1;
      const int c = kernel ? LIBUSB_ERROR_BUSY : libusb_claim_interface(handle, 0);
      if (c == 0)
        libusb_release_interface(handle, 0);
      result = c == 0 ? UsbAccess::Ok : c == LIBUSB_ERROR_BUSY ? UsbAccess::Busy : UsbAccess::Other;
      libusb_close(handle);
    }
    break;
  }
  if (devs)
    libusb_free_device_list(devs, 1);
  return result;
}

std::vector<UsbEvent> diffUsbDevices(const std::vector<KinectUsbDevice>& before,
                                     const std::vector<KinectUsbDevice>& after) {
  std::vector<UsbEvent> events;
  for (const auto& d : before)
    if (std::find(after.begin(), after.end(), d) == after.end())
      events.push_back({false, d});
  for (const auto& d : after)
    if (std::find(before.begin(), before.end(), d) == before.end())
      events.push_back({true, d});
  return events;
}

struct UsbMonitor::Impl {
  UsbContext usb;
  UsbEventCallback callback;
  int poll_interval_ms = 500;
  bool hotplug = false;
  libusb_hotplug_callback_handle handle = 0;
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable wake;
  std::thread thread;

  static int LIBUSB_CALL onHotplug(libusb_context*, libusb_device* dev, libusb_hotplug_event event,
                                   void* user) {
    auto* self = static_cast<Impl*>(user);
    libusb_device_descriptor d{};
    KinectUsbRole role{};
    if (libusb_get_device_descriptor(dev, &d) == 0 && kinectRole(d, role) && self->callback)
      self->callback({event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED, describe(dev, role)});
    return 0; // keep the callback registered
  }

  void runHotplug() {
    while (!stop) {
      timeval tv{0, 200000}; // wake up regularly to notice stop()
      libusb_handle_events_timeout_completed(usb.ctx, &tv, nullptr);
    }
  }

  void runPolling() {
    std::vector<KinectUsbDevice> before = list(usb.ctx);
    std::unique_lock lock(mutex);
    while (!wake.wait_for(lock, std::chrono::milliseconds(poll_interval_ms),
                          [this] { return stop.load(); })) {
      std::vector<KinectUsbDevice> after = list(usb.ctx);
      for (const auto& e : diffUsbDevices(before, after))
        if (callback)
          callback(e);
      before = std::move(after);
    }
  }
};

UsbMonitor::UsbMonitor(UsbEventCallback callback, int poll_interval_ms)
    : m_impl(std::make_unique<Impl>()) {
  m_impl->callback = std::move(callback);
  m_impl->poll_interval_ms = std::max(10, poll_interval_ms);
  if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
    const int r = libusb_hotplug_register_callback(
        m_impl->usb.ctx,
        static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                          LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
        LIBUSB_HOTPLUG_NO_FLAGS, kMicrosoftVendorId, LIBUSB_HOTPLUG_MATCH_ANY,
        LIBUSB_HOTPLUG_MATCH_ANY, &Impl::onHotplug, m_impl.get(), &m_impl->handle);
    m_impl->hotplug = r == LIBUSB_SUCCESS;
  }
  if (m_impl->hotplug)
    m_impl->thread = std::thread([impl = m_impl.get()] { impl->runHotplug(); });
  else
    m_impl->thread = std::thread([impl = m_impl.get()] { impl->runPolling(); });
}

UsbMonitor::~UsbMonitor() {
  stop();
}

void UsbMonitor::stop() {
  if (!m_impl || !m_impl->thread.joinable())
    return;
  {
    std::lock_guard lock(m_impl->mutex);
    m_impl->stop = true;
  }
  m_impl->wake.notify_all();
  if (m_impl->hotplug)
    libusb_hotplug_deregister_callback(m_impl->usb.ctx,
                                       m_impl->handle); // also wakes the event loop
  m_impl->thread.join();
}

} // namespace scanpick::devices
