// scanpick-cli devices | capture: list attached cameras, save organized clouds from one.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"

#ifdef SCANPICK_WITH_DEVICES
#include "devices/CameraRegistry.h"
#include "devices/CaptureWriter.h"
#endif

#include <iostream>
#include <memory>

namespace scanpick::cli {

#ifdef SCANPICK_WITH_DEVICES
namespace {

struct CaptureOptions {
  std::string device;
  std::string out;
  std::size_t frames = 1;
  int timeout_ms = 5000;
};

int runDevices() {
  std::vector<std::string> warnings;
  const auto found = devices::enumerateDevices({}, &warnings);
  for (const auto& w : warnings)
    std::cerr << "note: " << w << "\n";
  if (found.empty()) {
    std::cout << "no cameras found (PhoXi over GigE Vision, Kinect v1, OpenNI2). Files can be "
                 "replayed with "
                 "--device file:<cloud or folder>, recordings with --device oni:<file.oni>.\n";
    return kOk;
  }
  for (const auto& d : found) {
    std::cout << d.id << "\t" << d.model;
    if (!d.serial.empty())
      std::cout << "\tserial " << d.serial;
    if (!d.note.empty())
      std::cout << "\t(" << d.note << ")";
    std::cout << "\n";
  }
  return kOk;
}

int runCapture(const CaptureOptions& o) {
  auto camera = devices::openCamera(o.device);
  const auto files =
      devices::captureToFiles(*camera, o.out, o.frames, std::chrono::milliseconds(o.timeout_ms));
  for (const auto& f : files)
    std::cout << f.string() << "\n";
  return kOk;
}

} // namespace
#endif

void registerDeviceCommands(CLI::App& app) {
#ifdef SCANPICK_WITH_DEVICES
  addCommand(app, "devices", "List attached cameras of every backend (exit 0 also when none)",
             runDevices);

  auto options = std::make_shared<CaptureOptions>();
  CLI::App* capture =
      addCommand(app, "capture",
                 "Capture organized clouds (mm) from a camera into PCD files with a JSON sidecar",
                 [options] { return runCapture(*options); });
  capture
      ->add_option(
          "--device", options->device,
          "camera id: phoxi:<serial|ip>, kinect:<index>, oni:<file.oni|uri>, file:<cloud|folder>")
      ->required();
  capture
      ->add_option("--out", options->out,
                   "output .pcd; with --frames N > 1: <stem>-000.pcd, <stem>-001.pcd ...")
      ->required();
  capture->add_option("--frames", options->frames, "number of frames")
      ->check(CLI::Range(1, 100000));
  capture
      ->add_option("--timeout-ms", options->timeout_ms, "longest wait for each frame, milliseconds")
      ->check(CLI::Range(1, 3600000));
#else
  (void)app;
#endif
}

} // namespace scanpick::cli
