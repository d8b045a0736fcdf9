// OniCamera plays .oni recordings through OpenNI2. The recordings are made here from a real
// organized Kinect scene with OpenNI 1.x's mock depth node (see OniRecording.h); the decoded
// cloud must have the recorded depth exactly (whole millimetres) on the pinhole model of the
// recorded fields of view.
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "devices/CameraRegistry.h"
#include "devices/openni2/OniCamera.h"
#include "tests/devices/SyntheticScene.h"
#include "tests/support/TempDir.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace std::chrono_literals;

namespace {

constexpr double kPi = 3.14159265358979323846;
const double kHfov = 58.0 * kPi / 180.0, kVfov = 45.0 * kPi / 180.0;

/// The real Kinect scene when available, else the synthetic bin scene at the same resolution
/// (the playback path is the same; the real scene adds real invalid regions).
core::PointCloud scene() {
  const auto path = test::sharedData("pcl/milk_cartoon_all_small_clorox.pcd");
  if (!path.empty())
    return core::loadCloud(path, core::LengthUnit::Metres).cloud;
  return test::syntheticBinScene(640, 480, 577.0);
}

/// Records `frames` frames of `cloud_mm` with the recorder tool (a child process, see
/// OniRecorderTool.cpp); returns its stderr, empty on success.
std::string recordOni(const std::filesystem::path& oni, const core::PointCloud& cloud_mm,
                      int frames) {
  const auto src = oni.parent_path() / "source.pcd";
  core::saveCloudPcd(src, cloud_mm);
  const auto err_file = oni.parent_path() / "recorder.txt";
  const std::string cmd = std::string("'") + SCANPICK_ONI_RECORDER + "' '" + src.string() +
                          "' mm '" + oni.string() + "' " + std::to_string(frames) + " 58 45 2> '" +
                          err_file.string() + "'";
  const int status = std::system(cmd.c_str());
  std::string err = core::readFile(err_file);
  if (status != 0 && err.empty())
    err = "recorder failed with status " + std::to_string(status);
  return status == 0 ? std::string() : err;
}

} // namespace

TEST(OniPlayback, RecordedDepthPlaysBackExactly) {
  test::TempDir dir;
  const core::PointCloud source = scene();
  const auto oni = dir / "scene.oni";
  ASSERT_EQ(recordOni(oni, source, 3), "");

  auto camera = devices::openCamera("oni:" + oni.string());
  for (int f = 0; f < 3; ++f) {
    const devices::Frame frame = camera->capture(2000ms);
    ASSERT_EQ(frame.cloud.width, source.width);
    ASSERT_EQ(frame.cloud.height, source.height);
    ASSERT_TRUE(frame.metadata.intrinsics);
    const devices::Intrinsics k = *frame.metadata.intrinsics;
    EXPECT_NEAR(k.fx, 320.0 / std::tan(kHfov / 2), 0.01);
    EXPECT_NEAR(k.fy, 240.0 / std::tan(kVfov / 2), 0.01);
    double max_dz = 0, max_dxy = 0;
    std::size_t validity_mismatch = 0;
    for (std::size_t i = 0; i < source.size(); ++i) {
      const float z = source.points_mm[i].z();
      const bool valid = std::isfinite(z) && std::lround(z) > 0;
      const Eigen::Vector3f& g = frame.cloud.points_mm[i];
      if (valid != core::isValid(g)) {
        ++validity_mismatch;
        continue;
      }
      if (!valid)
        continue;
      max_dz = std::max(max_dz, std::abs(static_cast<double>(g.z()) - std::round(z)));
      const double u = static_cast<double>(i % source.width),
                   v = static_cast<double>(i / source.width);
      max_dxy = std::max({max_dxy, std::abs(g.x() - (u - k.cx) * g.z() / k.fx),
                          std::abs(g.y() - (v - k.cy) * g.z() / k.fy)});
    }
    EXPECT_EQ(validity_mismatch, 0u);
    EXPECT_EQ(max_dz, 0.0);
    EXPECT_LT(max_dxy, 1e-2);
    EXPECT_EQ(frame.metadata.frame_index, static_cast<std::uint64_t>(f));
  }
  // Three frames recorded: the fourth capture reports the end, promptly.
  const auto start = std::chrono::steady_clock::now();
  try {
    camera->capture(2000ms);
    FAIL() << "a fourth frame came out of a three-frame recording";
  } catch (const devices::DeviceError& e) {
    EXPECT_EQ(e.kind(), devices::DeviceErrorKind::StreamEnded) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 3s);
  // Close, reopen and continue from the start.
  camera.reset();
  camera = devices::openCamera("oni:" + oni.string());
  EXPECT_EQ(camera->capture(2000ms).metadata.frame_index, 0u);
}

TEST(OniPlayback, TruncatedRecordingEndsWithAClearError) {
  test::TempDir dir;
  const auto oni = dir / "full.oni";
  ASSERT_EQ(recordOni(oni, scene(), 4), "");
  const std::string bytes = core::readFile(oni);
  // Cut early (the header survives, frame data does not) and late (some frames survive).
  for (const double keep : {0.3, 0.6, 0.9}) {
    const auto cut = dir / ("cut-" + std::to_string(static_cast<int>(keep * 100)) + ".oni");
    std::ofstream(cut, std::ios::binary)
        << bytes.substr(0, static_cast<std::size_t>(bytes.size() * keep));
    std::size_t frames = 0;
    try {
      auto camera = devices::openCamera("oni:" + cut.string());
      for (; frames < 10; ++frames)
        camera->capture(1000ms);
      ADD_FAILURE() << "a truncated recording played 10 frames";
    } catch (const devices::DeviceError& e) {
      EXPECT_TRUE(e.kind() == devices::DeviceErrorKind::StreamEnded ||
                  e.kind() == devices::DeviceErrorKind::Protocol)
          << devices::toString(e.kind()) << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
      std::printf("cut at %.0f%%: %zu frame(s), then %s: %s\n", keep * 100, frames,
                  devices::toString(e.kind()), e.what());
    }
    EXPECT_LT(frames, 4u);
  }
}

TEST(OniPlayback, MissingRecordingIsNotFound) {
  try {
    devices::openCamera("oni:/nonexistent/scene.oni");
    FAIL();
  } catch (const devices::DeviceError& e) {
    EXPECT_EQ(e.kind(), devices::DeviceErrorKind::NotFound);
    EXPECT_NE(std::string(e.what()).find("check the path"), std::string::npos) << e.what();
  }
}
