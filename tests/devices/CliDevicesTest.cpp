// scanpick-cli devices / capture end to end (the real executable as a child process).
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "tests/devices/SyntheticScene.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

using namespace scanpick;

namespace {

/// Runs scanpick-cli with `args`; returns the exit code, stdout+stderr in `output`.
int runCli(const std::string& args, const std::filesystem::path& dir, std::string& output) {
  const auto out_file = dir / "cli-output.txt";
  const std::string cmd =
      std::string("'") + SCANPICK_CLI + "' " + args + " > '" + out_file.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  output = core::readFile(out_file);
  std::filesystem::remove(out_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

TEST(CliDevices, ListingWithNothingAttachedSucceeds) {
  test::TempDir dir;
  std::string out;
  EXPECT_EQ(runCli("devices", dir.path(), out), 0) << out;
  // Test machines have no camera: the listing says so (a machine with one lists its id).
  EXPECT_TRUE(out.find("no cameras found") != std::string::npos ||
              out.find(':') != std::string::npos)
      << out;
}

TEST(CliDevices, CaptureFromFilesWritesNumberedCloudsAndSidecars) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "in");
  core::saveCloudPcd(dir / "in" / "f0.pcd", test::syntheticBinScene(32, 24, 32.0));
  core::saveCloudPcd(dir / "in" / "f1.pcd", test::syntheticBinScene(32, 24, 32.0, 5.0f));
  std::string out;
  ASSERT_EQ(runCli("capture --device file:" + (dir / "in").string() + " --out " +
                       (dir / "scan.pcd").string() + " --frames 2 --timeout-ms 2000",
                   dir.path(), out),
            0)
      << out;
  const auto second = core::loadCloud(dir / "scan-001.pcd", core::LengthUnit::Millimetres).cloud;
  EXPECT_EQ(second.width, 32u);
  EXPECT_EQ(second.height, 24u);
  const auto meta = nlohmann::json::parse(core::readFile(dir / "scan-000.json"));
  EXPECT_EQ(meta["format"], "scanpick-capture");
  EXPECT_EQ(meta["units"], "mm");
}

TEST(CliDevices, UnknownDeviceFailsWithAnActionableMessage) {
  test::TempDir dir;
  std::string out;
  EXPECT_EQ(runCli("capture --device webcam:0 --out " + (dir / "x.pcd").string(), dir.path(), out),
            1)
      << out;
  EXPECT_NE(out.find("scanpick-cli devices"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.pcd"));
}
