// scanpick-cli calibrate end to end, as an integrator runs it: scans of the target written by the
// virtual PhoXi to a folder, a poses file with the robot's flange poses (some as 4 × 4 matrices,
// some as position + quaternion, in metres), and the calibration file it writes. Bad input ends
// with a message that says what to do, exit code 1 (2 for usage) and no calibration file.
#include "core/calib/CalibJson.h"
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"
#include "tests/unit/calib/CalibScenes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using namespace scanpick;
using json = nlohmann::json;
using test::exitCode;
using test::quoted;
using test::readText;
using test::runCli;

namespace {

constexpr int kPoses = 8;

/// A robot pose in the poses file: odd poses as a 4 × 4 matrix, even ones as position +
/// quaternion, translations in metres.
json poseEntry(int i, const Eigen::Isometry3d& T_base_flange) {
  json pose = core::calib::poseToJson(T_base_flange);
  for (std::size_t row = 0; row < 3; ++row)
    pose["matrix"][row][3] = pose["matrix"][row][3].get<double>() / 1000;
  for (const char* k : {"x", "y", "z"})
    pose[k] = pose[k].get<double>() / 1000;
  json T = i % 2 ? pose["matrix"] : pose;
  if (i % 2 == 0)
    T.erase("matrix");
  return {{"scan", "scan-" + std::to_string(i + 1) + ".pcd"}, {"T_base_flange", T}};
}

class CliCalibrate : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    if (!fs::exists(test::kCli))
      return;
    s_dir = std::make_unique<test::TempDir>();
    s_cell = test::eyeToHandCell(kPoses, 21);
    const auto mesh = test::targetMesh(core::calib::defaultTarget());
    json poses = json::array();
    for (int i = 0; i < kPoses; ++i) {
      // Only the valid points: a 1032 × 772 organized scan is mostly empty air here.
      core::saveCloudPcd(*s_dir / ("scan-" + std::to_string(i + 1) + ".pcd"),
                         core::dropInvalid(test::scanOf(s_cell, i, mesh)));
      poses.push_back(poseEntry(i, s_cell.T_base_flange[std::size_t(i)]));
    }
    core::writeFileAtomic(*s_dir / "poses.json", poses.dump(2));
  }
  static void TearDownTestSuite() { s_dir.reset(); }
  void SetUp() override {
    if (!s_dir)
      GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  }

  /// Runs calibrate with `poses` (a file in the folder) and `extra` arguments; output in log().
  int calibrate(const std::string& poses, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{
        "calibrate",    "--mode", "eye-to-hand", "--poses",    quoted(*s_dir / poses),
        "--pose-units", "m",      "--out",       quoted(out())};
    args.insert(args.end(), extra.begin(), extra.end());
    return exitCode(runCli(args, *s_dir / "log.txt"));
  }
  fs::path out() const { return m_out.path() / "calibration.json"; }
  static std::string log() { return readText(*s_dir / "log.txt"); }
  /// The poses file with entry `i` changed by `change`, written as `name`.
  static void writePosesWith(const std::string& name, const std::function<void(json&)>& change) {
    json poses = json::parse(readText(*s_dir / "poses.json"));
    change(poses);
    core::writeFileAtomic(*s_dir / name, poses.dump(2));
  }

  static inline std::unique_ptr<test::TempDir> s_dir;
  static inline test::SimulatedCell s_cell;
  test::TempDir m_out;
};

} // namespace

TEST_F(CliCalibrate, WritesACalibrationCloseToTheTruth) {
  ASSERT_EQ(calibrate("poses.json"), 0) << log();
  EXPECT_NE(log().find("scan 8 scan-8.pcd: 4 of 4 spheres"), std::string::npos) << log();
  EXPECT_NE(log().find("no pose rejected"), std::string::npos) << log();
  EXPECT_NE(log().find("eye-to-hand calibration from 8 of 8 poses"), std::string::npos) << log();
  const json doc = json::parse(readText(out()));
  EXPECT_EQ(doc["format"], "scanpick-handeye");
  EXPECT_EQ(doc["residuals"].size(), std::size_t(kPoses));
  const auto result = core::calib::loadCalibration(out());
  // The poses went through the file in metres with 17 significant digits: no loss.
  EXPECT_LT(test::distanceBetween_mm(result.T_camera, s_cell.X), 0.2);
  EXPECT_LT(test::angleBetween_deg(result.T_camera, s_cell.X), 0.05);
  EXPECT_LT(test::distanceBetween_mm(result.T_target, s_cell.Y), 0.2);
  EXPECT_LT(test::angleBetween_deg(result.T_target, s_cell.Y), 0.05);
}

TEST_F(CliCalibrate, AWrongRobotPoseIsReportedAndLeftOut) {
  writePosesWith("wrong.json", [](json& poses) {
    poses[4]["T_base_flange"]["x"] = poses[4]["T_base_flange"]["x"].get<double>() + 0.002;
  });
  ASSERT_EQ(calibrate("wrong.json"), 0) << log();
  EXPECT_NE(log().find("rejected pose 5"), std::string::npos) << log();
  EXPECT_NE(log().find("the robot pose or the scan of this pose is wrong"), std::string::npos);
  EXPECT_NE(log().find("from 7 of 8 poses"), std::string::npos) << log();
  const json doc = json::parse(readText(out()));
  ASSERT_EQ(doc["poses_rejected"].size(), 1u);
  EXPECT_EQ(doc["poses_rejected"][0]["pose"], 5);
}

TEST_F(CliCalibrate, AScanWithoutTheTargetFailsNamingTheScan) {
  // Scan 3 with the spheres cut out: the plate alone.
  const core::PointCloud scan =
      core::loadCloud(*s_dir / "scan-3.pcd", core::LengthUnit::Millimetres).cloud;
  const Eigen::Isometry3d T = s_cell.T_camera_target[2];
  const auto layout = core::calib::defaultTarget();
  core::saveCloudPcd(*s_dir / "plate.pcd", core::selectPoints(scan, [&](std::size_t i) {
    for (const auto& c : layout.sphere_centres_mm)
      if ((scan.points_mm[i].cast<double>() - T * c).norm() < 16)
        return false;
    return true;
  }));
  writePosesWith("plate.json", [](json& poses) { poses[2]["scan"] = "plate.pcd"; });
  EXPECT_EQ(calibrate("plate.json"), 1);
  EXPECT_NE(log().find("error: scan 3 (" + (*s_dir / "plate.pcd").string() +
                       "): no sphere of radius 12.5 mm found: check that the calibration target is "
                       "in view"),
            std::string::npos)
      << log();
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CliCalibrate, TooFewPosesFailBeforeReadingScans) {
  core::writeFileAtomic(
      *s_dir / "two.json",
      R"([{"scan": "missing-1.pcd", "T_base_flange": {"x": 0, "y": 0, "z": 0, "qw": 1, "qx": 0, "qy": 0, "qz": 0}},)"
      R"( {"scan": "missing-2.pcd", "T_base_flange": {"x": 0, "y": 0, "z": 0, "qw": 0, "qx": 1, "qy": 0, "qz": 0}}])");
  EXPECT_EQ(calibrate("two.json"), 1);
  EXPECT_NE(log().find("error: too few poses: 2 given; a hand-eye calibration needs at least 3 "
                       "robot poses with rotations about non-parallel axes"),
            std::string::npos)
      << log();
  EXPECT_FALSE(fs::exists(out()));
}

TEST_F(CliCalibrate, BadPosesFilesAndUsageErrors) {
  core::writeFileAtomic(*s_dir / "broken.json", "[{\"scan\": ");
  EXPECT_EQ(calibrate("broken.json"), 1);
  EXPECT_NE(log().find("is not valid JSON"), std::string::npos) << log();
  writePosesWith("skewed.json", [](json& poses) { poses[1]["T_base_flange"][0][1] = 0.3; });
  EXPECT_EQ(calibrate("skewed.json"), 1);
  EXPECT_NE(log().find("pose 2 T_base_flange: the upper left 3 x 3 block is not a rotation"),
            std::string::npos)
      << log();
  EXPECT_EQ(calibrate("poses.json", {"--mode", "sideways"}), 2);
  EXPECT_EQ(calibrate("poses.json", {"--units", "inch"}), 2);
  EXPECT_EQ(exitCode(runCli({"calibrate", "--mode", "eye-in-hand", "--out", quoted(out())})), 2);
  EXPECT_FALSE(fs::exists(out()));
}
