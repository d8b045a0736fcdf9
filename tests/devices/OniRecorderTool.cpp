// scanpick-oni-recorder <cloud.pcd|ply> <m|mm> <out.oni> <frames> <hfov deg> <vfov deg>
// Records the depth of an organized cloud into an .oni file with OpenNI 1.x (OniRecording.h).
// A separate program so the playback test links only the code under test (OpenNI2), not the
// OpenNI 1.x recorder.
#include "core/cloud/CloudIo.h"
#include "tests/devices/OniRecording.h"

#include <cstdlib>
#include <iostream>

int main(int argc, char** argv) {
  if (argc != 7) {
    std::cerr
        << "usage: scanpick-oni-recorder <cloud> <m|mm> <out.oni> <frames> <hfov deg> <vfov deg>\n";
    return 2;
  }
  try {
    const auto cloud =
        scanpick::core::loadCloud(argv[1], scanpick::core::parseLengthUnit(argv[2])).cloud;
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    const std::string err = scanpick::test::recordOni(
        argv[3], cloud, std::atoi(argv[4]), std::atof(argv[5]) * kDeg, std::atof(argv[6]) * kDeg);
    if (!err.empty()) {
      std::cerr << "OpenNI: " << err << "\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
