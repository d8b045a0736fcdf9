// Bad input at the command line: every file that is not what it claims to be, every output that
// cannot be written and every usage error ends with a one-line message and a documented exit
// code (1 for a failure, 2 for usage), and leaves no file behind.
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "tests/support/RunCli.h"
#include "tests/support/TempDir.h"
#include "tests/unit/pipeline/IdealScene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using namespace scanpick;
using test::exitCode;
using test::quoted;
using test::readText;
using test::runCli;

namespace {

/// A model of the ideal part and a scene with two copies of it, in `dir`.
void writeModelAndScene(const fs::path& dir) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 700);
  core::TeachOptions o;
  o.name = "ideal";
  o.crop_box_mm = Eigen::AlignedBox3f(Eigen::Vector3f(-60, -60, 650), Eigen::Vector3f(90, 90, 750));
  const auto params = test::idealParams(0.001);
  core::saveModel(dir / "ideal.spmodel",
                  core::teach(test::idealScene(test::idealPartPoints(), {T}, 0.0, 1), o, params));
  core::saveCloudPcd(dir / "scene.pcd",
                     test::idealScene(test::idealPartPoints(), test::idealCopyPoses(), 0.0, 2));
}

class CliBadInput : public ::testing::Test {
protected:
  void SetUp() override {
    if (!fs::exists(test::kCli))
      GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
    writeModelAndScene(m_dir.path());
  }
  /// Runs `recognize` on `scene` with the ideal model; returns the exit code, output in `log`.
  int recognize(const fs::path& scene, const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"recognize", "--model",     quoted(m_dir / "ideal.spmodel"),
                                  "--scene",   quoted(scene), "--out",
                                  quoted(out)};
    args.insert(args.end(), extra.begin(), extra.end());
    return exitCode(runCli(args, m_dir / "log.txt"));
  }
  std::string log() const { return readText(m_dir / "log.txt"); }
  test::TempDir m_dir;
};

} // namespace

TEST_F(CliBadInput, FilesThatAreNotPointCloudsFailCleanly) {
  const std::vector<std::pair<std::string, std::string>> files{
      {"text.pcd", "just some notes\n"},
      {"png.pcd", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)},
      {"byte.pcd", "x"},
      {"fields.pcd", "VERSION 0.7\nFIELSD x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT "
                     "1\nPOINTS 1\nDATA ascii\n1 2 3\n"},
      {"wide.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH "
                   "2147483648\nHEIGHT 2147483648\nDATA binary\n"},
      {"count.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 2147483647 "
                    "1\nWIDTH 1\nHEIGHT 1\nDATA binary\n"}};
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    core::writeFileAtomic(m_dir / name, bytes);
    EXPECT_EQ(recognize(m_dir / name, m_dir / "r.json"), 1);
    EXPECT_NE(log().find("error: cannot read '" + (m_dir / name).string() + "'"), std::string::npos)
        << log();
    EXPECT_FALSE(fs::exists(m_dir / "r.json"));
  }
}

TEST_F(CliBadInput, AnUnwritablePictureWritesNoResults) {
  EXPECT_EQ(recognize(m_dir / "scene.pcd", m_dir / "r.json",
                      {"--picture", quoted(m_dir / "no-such-folder" / "p.png")}),
            1);
  EXPECT_NE(log().find("no-such-folder"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(m_dir / "r.json"));
}

TEST_F(CliBadInput, UsageErrorsExitWithTwo) {
  EXPECT_EQ(exitCode(runCli({"recognize", "--scene", "x.pcd"}, m_dir / "log.txt")), 2) << log();
  EXPECT_EQ(exitCode(runCli({"recognize", "--no-such-flag"}, m_dir / "log.txt")), 2);
  EXPECT_EQ(exitCode(runCli({"no-such-command"}, m_dir / "log.txt")), 2);
  EXPECT_EQ(exitCode(runCli({"--help"}, m_dir / "log.txt")), 0);
}

TEST_F(CliBadInput, AFileNameThatIsNotUtf8IsRecognizedAndReported) {
  const fs::path odd = m_dir / "scene-\xff.pcd";
  fs::copy_file(m_dir / "scene.pcd", odd);
  ASSERT_EQ(recognize(odd, m_dir / "r.json"), 0) << log();
  const auto results = nlohmann::json::parse(readText(m_dir / "r.json"));
  EXPECT_FALSE(results.dump().empty());
}

TEST_F(CliBadInput, GripDirectionsAreTaughtCheckedAndReportedInTheScene) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0, 0, 700);
  core::saveCloudPcd(m_dir / "teach.pcd", test::idealScene(test::idealPartPoints(), {T}, 0.0, 1));
  // The fixture model's parameters: the ideal part is a few sparse circles.
  core::savePreset(m_dir / "ideal.json", {"ideal", "", test::idealParams(0.001)});
  const auto teach = [&](const std::string& grip, const fs::path& out) {
    return exitCode(runCli({"teach", "--scan", quoted(m_dir / "teach.pcd"), "--params",
                            quoted(m_dir / "ideal.json"), "--crop-box", "-60,-60,650,90,90,750",
                            "--grip", grip, "--out", quoted(out)},
                           m_dir / "log.txt"));
  };
  EXPECT_EQ(teach("top=0,0,700,0,0", m_dir / "bad.spmodel"), 1);
  EXPECT_NE(log().find("expected 3 numbers"), std::string::npos) << log();
  EXPECT_EQ(teach("top=0,0,700,0,0,0", m_dir / "bad.spmodel"), 1);
  EXPECT_NE(log().find("non-zero direction"), std::string::npos) << log();
  EXPECT_EQ(teach("top=0,0,700,0,0,1,0,0,5", m_dir / "bad.spmodel"), 1);
  EXPECT_NE(log().find("along its approach"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(m_dir / "bad.spmodel"));

  ASSERT_EQ(teach("top=0,0,700,0,0,2,1,0,0", m_dir / "grip.spmodel"), 0) << log();
  const core::TaughtModel model = core::loadModel(m_dir / "grip.spmodel");
  ASSERT_EQ(model.grip_points.size(), 1u);
  ASSERT_TRUE(model.grip_points[0].approach && model.grip_points[0].closing_axis);
  EXPECT_TRUE((model.T_teach_model.linear() * *model.grip_points[0].approach)
                  .isApprox(Eigen::Vector3d::UnitZ()));
  // Each detection reports the grip's directions turned into the scene with it.
  ASSERT_EQ(exitCode(runCli({"recognize", "--model", quoted(m_dir / "grip.spmodel"), "--scene",
                             quoted(m_dir / "scene.pcd"), "--out", quoted(m_dir / "r.json")},
                            m_dir / "log.txt")),
            0)
      << log();
  const auto results = nlohmann::json::parse(readText(m_dir / "r.json"));
  ASSERT_FALSE(results["detections"].empty()) << log();
  for (const auto& d : results["detections"]) {
    Eigen::Matrix4d T_scene_model;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        T_scene_model(r, c) = d["T_scene_model"][r][c].get<double>();
    const auto& approach = d["grip_points"][0]["approach"];
    const Eigen::Vector3d expected =
        T_scene_model.topLeftCorner<3, 3>() * *model.grip_points[0].approach;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(approach[k].get<double>(), expected[k], 1e-6);
    EXPECT_TRUE(d["grip_points"][0].contains("closing_axis"));
  }
}

TEST_F(CliBadInput, AMeshIsTaughtAsThePartSeenFromEverySideAndBadOnesAreRefused) {
  const auto teachMesh = [&](std::vector<std::string> extra, const fs::path& out) {
    std::vector<std::string> args{"teach", "--name", "support", "--out", quoted(out)};
    args.insert(args.end(), extra.begin(), extra.end());
    return exitCode(runCli(args, m_dir / "log.txt"));
  };
  ASSERT_EQ(exitCode(runCli({"synth", "--part", "support", "--export-mesh", "--out",
                             quoted(m_dir / "support.ply")},
                            m_dir / "log.txt")),
            0)
      << log();
  ASSERT_EQ(teachMesh({"--mesh", quoted(m_dir / "support.ply"), "--grip", "top=0,0,10"},
                      m_dir / "mesh.spmodel"),
            0)
      << log();
  EXPECT_NE(log().find("seen from every side"), std::string::npos) << log();
  const core::TaughtModel model = core::loadModel(m_dir / "mesh.spmodel");
  EXPECT_TRUE(model.all_around);
  ASSERT_TRUE(model.T_part_model) << "the mesh's frame is the part's";
  ASSERT_EQ(model.grip_points.size(), 1u);
  // The grip was given in the mesh's frame.
  EXPECT_TRUE((*model.T_part_model * model.grip_points[0].position_mm)
                  .isApprox(Eigen::Vector3d(0, 0, 10), 1e-9));

  core::writeFileAtomic(m_dir / "empty.ply", "ply\nformat ascii 1.0\nelement vertex 0\n"
                                             "element face 0\nend_header\n");
  for (const auto& extra : std::vector<std::vector<std::string>>{
           {"--mesh", quoted(m_dir / "empty.ply")},
           {"--mesh", quoted(m_dir / "no-such.ply")},
           {"--mesh", quoted(m_dir / "support.ply"), "--scan", quoted(m_dir / "scene.pcd")},
           {"--mesh", quoted(m_dir / "support.ply"), "--crop-box", "0,0,0,1,1,1"},
           {}}) {
    EXPECT_EQ(teachMesh(extra, m_dir / "bad.spmodel"), 1) << log();
    EXPECT_NE(log().find("error"), std::string::npos) << log();
    EXPECT_FALSE(fs::exists(m_dir / "bad.spmodel"));
  }
}
