// scanpick-capture-tool <device id> <out.pcd> <frames> <timeout ms>
// Runs the library's capture path (openCamera + captureToFiles, exactly what
// `scanpick-cli capture` calls) in a child process, so tests can start it with an environment
// prepared before the process starts (fakenect's LD_LIBRARY_PATH and FAKENECT_PATH).
#include "devices/CameraRegistry.h"
#include "devices/CaptureWriter.h"

#include <cstdlib>
#include <iostream>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: scanpick-capture-tool <device id> <out.pcd> <frames> <timeout ms>\n";
    return 2;
  }
  try {
    auto camera = scanpick::devices::openCamera(argv[1]);
    const auto files =
        scanpick::devices::captureToFiles(*camera, argv[2], std::strtoul(argv[3], nullptr, 10),
                                          std::chrono::milliseconds(std::atoi(argv[4])));
    for (const auto& f : files)
      std::cout << f.string() << "\n";
    return 0;
  } catch (const scanpick::devices::DeviceError& e) {
    std::cerr << "error[" << scanpick::devices::toString(e.kind()) << "]: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
