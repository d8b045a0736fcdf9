// Kinect v1 capture path under Debian's fakenect: the unchanged libfreenect API replays a dump
// that this test writes from a real organized Kinect scene (milk_cartoon_all_small_clorox.pcd,
// metres, 640x480). Depth is written as raw 11-bit disparity with the inverse of our conversion,
// so the captured cloud must reproduce the scene's depth within half a disparity step.
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "devices/freenect/DisparityConversion.h"
#include "tests/support/TempDir.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

using namespace scanpick;

namespace {

constexpr const char* kFakenectDir = "/usr/lib/x86_64-linux-gnu/fakenect";
constexpr int kW = 640, kH = 480;

/// Writes `frames` identical depth+RGB frames ~1/30 s apart (fakenect sleeps the recorded gaps).
void writeDump(const std::filesystem::path& dir, const core::PointCloud& scene, int frames) {
  std::filesystem::create_directories(dir);
  std::string depth(kW * kH * 2, '\0'), rgb(kW * kH * 3, '\0');
  for (std::size_t i = 0; i < scene.size(); ++i) {
    const std::uint16_t raw = devices::depthMmToDisparity(scene.points_mm[i].z());
    depth[2 * i] = static_cast<char>(raw & 0xff); // little-endian, as fakenect reads it
    depth[2 * i + 1] = static_cast<char>(raw >> 8);
    if (!scene.colors.empty())
      for (int c = 0; c < 3; ++c)
        rgb[3 * i + c] = static_cast<char>(scene.colors[i][static_cast<std::size_t>(c)]);
  }
  std::ofstream index(dir / "INDEX.txt");
  for (int k = 0; k < frames; ++k) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%f", 100.0 + k / 30.0);
    const std::string d =
        std::string("d-") + seconds + "-" + std::to_string(1000 + 2000000 * k) + ".pgm";
    const std::string r =
        std::string("r-") + seconds + "-" + std::to_string(1000 + 2000000 * k) + ".ppm";
    std::ofstream(dir / d, std::ios::binary) << "P5 640 480 65535\n" << depth;
    std::ofstream(dir / r, std::ios::binary) << "P6 640 480 255\n" << rgb;
    index << d << "\n" << r << "\n";
  }
}

/// Runs the capture tool under fakenect; returns its exit code, stderr in `err`.
int runUnderFakenect(const std::filesystem::path& dump, const std::filesystem::path& out,
                     int frames, int timeout_ms, std::string& err) {
  const std::filesystem::path err_file = out.parent_path() / "stderr.txt";
  const std::string cmd =
      std::string("LD_LIBRARY_PATH=") + kFakenectDir + " FAKENECT_PATH='" + dump.string() + "' '" +
      SCANPICK_CAPTURE_TOOL + "' kinect:0 '" + out.string() + "' " + std::to_string(frames) + " " +
      std::to_string(timeout_ms) + " > /dev/null 2> '" + err_file.string() + "'";
  const int status = std::system(cmd.c_str());
  std::ifstream in(err_file);
  err.assign(std::istreambuf_iterator<char>(in), {});
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

core::PointCloud loadScene() {
  const auto path = test::sharedData("pcl/milk_cartoon_all_small_clorox.pcd");
  if (path.empty())
    return {};
  return core::loadCloud(path, core::LengthUnit::Metres).cloud;
}

} // namespace

TEST(Fakenect, CaptureReproducesTheRecordedSceneWithinDisparityQuantization) {
  ASSERT_TRUE(std::filesystem::exists(std::string(kFakenectDir) + "/libfreenect.so.0.5"))
      << "Debian's fakenect is missing: apt-get install libfreenect0.5";
  const core::PointCloud scene = loadScene();
  if (scene.empty())
    GTEST_SKIP()
        << "../shared/data/pcl/milk_cartoon_all_small_clorox.pcd is absent (the real Kinect scene)";
  ASSERT_EQ(scene.width, 640u);
  ASSERT_EQ(scene.height, 480u);

  test::TempDir dir;
  writeDump(dir / "dump", scene, 2);
  std::string err;
  ASSERT_EQ(runUnderFakenect(dir / "dump", dir / "scan.pcd", 2, 5000, err), 0) << err;

  const devices::Intrinsics k = devices::kinectDepthIntrinsics();
  for (const char* name : {"scan-000.pcd", "scan-001.pcd"}) {
    const core::PointCloud got = core::loadCloud(dir / name, core::LengthUnit::Millimetres).cloud;
    ASSERT_EQ(got.width, 640u);
    ASSERT_EQ(got.height, 480u);
    double max_dz = 0, max_excess = -1e9, max_dxy_model = 0, max_dxy_source = 0;
    std::size_t both = 0, lost = 0, colour_mismatch = 0;
    for (std::size_t i = 0; i < scene.size(); ++i) {
      const Eigen::Vector3f& s = scene.points_mm[i];
      const Eigen::Vector3f& g = got.points_mm[i];
      const bool expect_valid = devices::depthMmToDisparity(s.z()) != devices::kDisparityNoData;
      if (!expect_valid) {
        EXPECT_FALSE(core::isValid(g)) << "pixel " << i;
        continue;
      }
      if (!core::isValid(g)) {
        ++lost;
        continue;
      }
      ++both;
      const double dz = std::abs(g.z() - s.z());
      max_dz = std::max(max_dz, dz);
      // Half a disparity step (+ float rounding) is the most a round trip may move a point.
      max_excess =
          std::max(max_excess, dz - devices::disparityQuantizationMm(s.z()) * 1.001 - 1e-3);
      const auto u = static_cast<double>(i % kW), v = static_cast<double>(i / kW);
      max_dxy_model = std::max({max_dxy_model, std::abs(g.x() - (u - k.cx) * g.z() / k.fx),
                                std::abs(g.y() - (v - k.cy) * g.z() / k.fy)});
      // Not asserted: the source's x/y follow the intrinsics it was captured with, ours the
      // preset's.
      max_dxy_source = std::max({max_dxy_source, static_cast<double>(std::abs(g.x() - s.x())),
                                 static_cast<double>(std::abs(g.y() - s.y()))});
      if (!scene.colors.empty() && !got.colors.empty() && got.colors[i] != scene.colors[i])
        ++colour_mismatch;
    }
    std::printf("%s: %zu points, max |dz| = %.3f mm, max dz beyond half-step = %.4f mm, "
                "max |dx|,|dy| vs source = %.2f mm (different intrinsics)\n",
                name, both, max_dz, max_excess, max_dxy_source);
    EXPECT_EQ(lost, 0u);
    EXPECT_GT(both, scene.validCount() * 9 / 10);
    EXPECT_LE(max_excess, 0.0);
    EXPECT_LT(max_dxy_model, 1e-2);
    if (!scene.colors.empty()) {
      ASSERT_EQ(got.colors.size(), got.size()) << "RGB was not captured";
      EXPECT_EQ(colour_mismatch, 0u);
    }
  }
  const auto meta = nlohmann::json::parse(core::readFile(dir / "scan-001.json"));
  EXPECT_EQ(meta["format"], "scanpick-capture");
  EXPECT_EQ(meta["sensor"], "kinect-v1");
  EXPECT_EQ(meta["units"], "mm");
  EXPECT_EQ(meta["frame_index"], 1);
  EXPECT_NEAR(meta["intrinsics"]["fx"].get<double>(), k.fx, 1e-9);
}

TEST(Fakenect, DumpThatEndsGivesStreamEndedWithinTimeoutAndNoPartialFile) {
  const core::PointCloud scene = loadScene();
  if (scene.empty())
    GTEST_SKIP()
        << "../shared/data/pcl/milk_cartoon_all_small_clorox.pcd is absent (the real Kinect scene)";
  test::TempDir dir;
  writeDump(dir / "dump", scene, 1);
  std::string err;
  const auto start = std::chrono::steady_clock::now();
  // Three frames asked, one recorded: the second capture hits the end of the dump.
  EXPECT_EQ(runUnderFakenect(dir / "dump", dir / "scan.pcd", 3, 3000, err), 1);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_NE(err.find("stream-ended"), std::string::npos) << err;
  EXPECT_NE(err.find("reopen"), std::string::npos) << err;
  EXPECT_NE(err.find("1 of 3 frame(s) were saved"), std::string::npos) << err;
  // The completed frame is kept, nothing half-written and no temporary file is left.
  EXPECT_TRUE(std::filesystem::exists(dir / "scan-000.pcd"));
  EXPECT_TRUE(std::filesystem::exists(dir / "scan-000.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "scan-001.pcd"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();

  // Reopen (a fresh process, as the operator would) and continue.
  EXPECT_EQ(runUnderFakenect(dir / "dump", dir / "again.pcd", 1, 3000, err), 0) << err;
  EXPECT_TRUE(std::filesystem::exists(dir / "again.pcd"));
}
