#include "devices/CameraRegistry.h"

#include "devices/aravis/PhoXiGigECamera.h"
#include "devices/file/FileCamera.h"
#include "devices/freenect/KinectCamera.h"
#include "devices/openni2/OniCamera.h"
#include "devices/usb/UsbMonitor.h"
#ifdef SCANPICK_WITH_PHOXI_API
#include "devices/phoxi_api/PhoXiApiCamera.h"
#endif

#include <charconv>

namespace scanpick::devices {
namespace {

std::string validForms() {
  std::string s = "use phoxi:<serial or IP>, kinect:<index>, oni:<file.oni or URI>, file:<cloud "
                  "file or folder>";
#ifdef SCANPICK_WITH_PHOXI_API
  s += ", phoxi-api:<serial>";
#endif
  return s + " ('scanpick-cli devices' lists the attached ones)";
}

template <typename F> void tryBackend(const char* name, std::vector<std::string>* warnings, F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    if (warnings)
      warnings->push_back(std::string(name) + ": " + e.what());
  }
}

} // namespace

std::vector<DeviceInfo> enumerateDevices(const EnumerateOptions& options,
                                         std::vector<std::string>* warnings) {
  std::vector<DeviceInfo> out;
  if (options.aravis)
    tryBackend("GigE Vision", warnings, [&] {
      for (auto& d : PhoXiGigECamera::enumerate())
        out.push_back(std::move(d));
    });
  if (options.kinect)
    tryBackend("Kinect", warnings, [&] {
      // libfreenect counts the cameras; libusb tells whether we may open them.
      const int n = KinectCamera::count();
      std::vector<KinectUsbDevice> cameras;
      for (const auto& d : listKinectUsbDevices())
        if (d.role == KinectUsbRole::Camera)
          cameras.push_back(d);
      for (int i = 0; i < n; ++i) {
        DeviceInfo d{"kinect:" + std::to_string(i), "freenect", "Microsoft Kinect v1", "", ""};
        if (i < static_cast<int>(cameras.size())) {
          const auto& usb = cameras[static_cast<std::size_t>(i)];
          d.note = "USB " + usb.port_path;
          const UsbAccess access = probeAccess(usb);
          if (access == UsbAccess::Permission)
            d.note +=
                ", no permission: install resources/udev/51-kinect.rules (see docs/devices.md)";
          else if (access == UsbAccess::Busy)
            d.note += ", busy: another program or the gspca_kinect driver holds it";
        }
        out.push_back(std::move(d));
      }
    });
#ifdef SCANPICK_WITH_PHOXI_API
  if (options.aravis)
    tryBackend("PhoXi API", warnings, [&] {
      for (auto& d : PhoXiApiCamera::enumerate())
        out.push_back(std::move(d));
    });
#endif
  if (options.openni2)
    tryBackend("OpenNI2", warnings, [&] {
      for (auto& d : OniCamera::enumerate())
        out.push_back(std::move(d));
    });
  return out;
}

std::unique_ptr<Camera> openCamera(const std::string& id) {
  const auto colon = id.find(':');
  if (colon == std::string::npos || colon + 1 >= id.size())
    throw DeviceError(DeviceErrorKind::NotFound,
                      "camera id '" + id +
                          "' is not of the form <kind>:<address>: " + validForms());
  const std::string kind = id.substr(0, colon);
  const std::string rest = id.substr(colon + 1);
  if (kind == "phoxi")
    return std::make_unique<PhoXiGigECamera>(rest);
  if (kind == "kinect") {
    int index = -1;
    const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), index);
    if (ec != std::errc() || end != rest.data() + rest.size() || index < 0)
      throw DeviceError(DeviceErrorKind::NotFound,
                        "Kinect id '" + id + "' needs a number: kinect:0 is the first Kinect");
    return std::make_unique<KinectCamera>(index);
  }
  if (kind == "oni")
    return std::make_unique<OniCamera>(rest);
  if (kind == "file")
    return std::make_unique<FileCamera>(rest);
#ifdef SCANPICK_WITH_PHOXI_API
  if (kind == "phoxi-api")
    return std::make_unique<PhoXiApiCamera>(rest);
#endif
  throw DeviceError(DeviceErrorKind::NotFound,
                    "unknown camera kind '" + kind + "' in '" + id + "': " + validForms());
}

} // namespace scanpick::devices
