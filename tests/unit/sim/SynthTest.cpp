// Scene files: complete ground truth, byte-identical for identical seeds, nothing written on error.
#include "core/sim/Synth.h"

#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/MeshIo.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace scanpick::core;
using scanpick::test::TempDir;

namespace {

SynthRequest smallKinectBin() {
  SynthRequest r;
  r.parts = {"cup"};
  r.count = 4;
  r.sensor = "kinect-v1"; // the smallest preset keeps the test fast
  r.seed = 5;
  return r;
}

Eigen::Matrix4d matrixFrom(const nlohmann::json& j) {
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      m(r, c) = j.at(r).at(c).get<double>();
  return m;
}

} // namespace

TEST(Synth, WritesCloudPictureAndGroundTruth) {
  TempDir dir;
  const SynthScene s = synthesize(smallKinectBin());
  const auto files = writeSynthScene(dir / "scene", s);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(scanpick::test::fileCount(dir.path()), 3u); // no temporary file left

  const LoadedCloud cloud = loadCloud(dir / "scene.pcd", LengthUnit::Millimetres);
  EXPECT_EQ(cloud.cloud.width, 640u);
  EXPECT_EQ(cloud.cloud.height, 480u);
  EXPECT_EQ(cloud.cloud.validCount(), s.render.cloud.validCount());
  EXPECT_EQ(readFile(dir / "scene.png").substr(1, 3), "PNG");

  const auto gt = nlohmann::json::parse(readFile(dir / "scene.gt.json"));
  EXPECT_EQ(gt["format"], "scanpick-ground-truth");
  EXPECT_EQ(gt["units"], "mm");
  EXPECT_EQ(gt["scene"]["cloud"], "scene.pcd");
  EXPECT_EQ(gt["sensor"]["preset"], "kinect-v1");
  EXPECT_DOUBLE_EQ(gt["sensor"]["fx"].get<double>(), s.sensor.fx);
  ASSERT_EQ(gt["instances"].size(), 4u);
  ASSERT_TRUE(gt["parts"].contains("cup"));
  const auto& grip = gt["parts"]["cup"]["grip_points"][0];
  for (const auto& inst : gt["instances"]) {
    const Eigen::Matrix4d T = matrixFrom(inst["T_scene_part"]);
    // A rigid transform, and the grip point in the scene is that transform of the part's one.
    EXPECT_LT((T.topLeftCorner<3, 3>() * T.topLeftCorner<3, 3>().transpose() -
               Eigen::Matrix3d::Identity())
                  .norm(),
              1e-9);
    const Eigen::Vector4d g(grip["position_mm"][0], grip["position_mm"][1], grip["position_mm"][2],
                            1.0);
    const Eigen::Vector4d expected = T * g;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(inst["grip_points"][0]["position_mm"][k].get<double>(), expected[k], 1e-9);
    const double vf = inst["visible_fraction"];
    EXPECT_GE(vf, 0.0);
    EXPECT_LE(vf, 1.0);
  }
  EXPECT_FALSE(gt.contains("crop_box"));
}

TEST(Synth, IdenticalSeedsGiveByteIdenticalFiles) {
  TempDir dir;
  writeSynthScene(dir / "a", synthesize(smallKinectBin()));
  writeSynthScene(dir / "b", synthesize(smallKinectBin()));
  SynthRequest other = smallKinectBin();
  other.seed = 6;
  writeSynthScene(dir / "c", synthesize(other));
  EXPECT_EQ(readFile(dir / "a.pcd"), readFile(dir / "b.pcd"));
  EXPECT_EQ(readFile(dir / "a.png"), readFile(dir / "b.png"));
  // The JSON names its own files; everything else must match.
  std::string ja = readFile(dir / "a.gt.json"), jb = readFile(dir / "b.gt.json");
  auto unname = [](std::string s, const std::string& n) {
    for (std::size_t p; (p = s.find("\"" + n + ".")) != std::string::npos;)
      s.replace(p, n.size() + 2, "\"X.");
    return s;
  };
  EXPECT_EQ(unname(ja, "a"), unname(jb, "b"));
  EXPECT_NE(readFile(dir / "a.pcd"), readFile(dir / "c.pcd"));
}

TEST(Synth, TeachSceneCarriesTheCropBox) {
  SynthRequest r;
  r.parts = {"support"};
  r.layout = LayoutKind::Teach;
  r.count = 1;
  r.sensor = "kinect-v1";
  const SynthScene s = synthesize(r);
  const auto gt = nlohmann::json::parse(groundTruthJson(s, "t.pcd", "t.png"));
  ASSERT_TRUE(gt.contains("crop_box"));
  EXPECT_EQ(gt["scene"]["kind"], "teach");
  // The crop box, taken back to the scene frame, holds the instance's visible points.
  const Eigen::Matrix4d T_scene_box = matrixFrom(gt["crop_box"]["T_scene_box"]);
  const Eigen::Vector3d lo(gt["crop_box"]["min_mm"][0], gt["crop_box"]["min_mm"][1],
                           gt["crop_box"]["min_mm"][2]);
  const Eigen::Vector3d hi(gt["crop_box"]["max_mm"][0], gt["crop_box"]["max_mm"][1],
                           gt["crop_box"]["max_mm"][2]);
  const Eigen::Matrix4d T_box_scene = T_scene_box.inverse();
  std::size_t inside = 0, on_part = 0;
  for (std::size_t i = 0; i < s.render.cloud.size(); ++i) {
    if (s.render.labels[i] != 0 || !isValid(s.render.cloud.points_mm[i]))
      continue;
    ++on_part;
    const Eigen::Vector3d p =
        (T_box_scene * s.render.cloud.points_mm[i].cast<double>().homogeneous()).head<3>();
    inside += (p.array() >= lo.array() - 30).all() && (p.array() <= hi.array() + 30).all();
  }
  EXPECT_GT(on_part, 100u);
  EXPECT_GE(inside, on_part * 95 / 100); // flying pixels and Kinect steps may stray a little
}

TEST(Synth, BadInputThrowsAndWritesNothing) {
  TempDir dir;
  auto expectNothing = [&](const SynthRequest& r) {
    EXPECT_THROW(writeSynthScene(dir / "out" / "scene", synthesize(r)), Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  };
  SynthRequest r = smallKinectBin();
  r.sensor = "realsense";
  expectNothing(r);
  r = smallKinectBin();
  r.count = 0;
  expectNothing(r);
  r = smallKinectBin();
  r.parts = {"teapot"};
  expectNothing(r);
  try {
    validateRequest(r);
    ADD_FAILURE() << "an unknown part is refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--mesh FILE"), std::string::npos) << e.what();
  }
  r = smallKinectBin();
  r.mesh_path = dir / "missing.stl";
  expectNothing(r);
  writeFileAtomic(dir / "notes.obj", "just some text\n");
  r.mesh_path = dir / "notes.obj";
  expectNothing(r);
  TriangleMesh open = boxMesh({0, 0, 0}, {30, 30, 30});
  open.triangles.resize(10);
  saveMeshPly(dir / "open.ply", open);
  r.mesh_path = dir / "open.ply";
  expectNothing(r);
  writeFileAtomic(dir / "empty.ply",
                  "ply\nformat ascii 1.0\nelement vertex 0\nelement face 0\nend_header\n");
  r.mesh_path = dir / "empty.ply";
  expectNothing(r);
  EXPECT_EQ(scanpick::test::fileCount(dir.path()), 3u); // only the three inputs made above
}

TEST(Synth, MeshFilePartIsSimulated) {
  TempDir dir;
  saveMeshPly(dir / "block.ply", boxMesh({0, 0, 0}, {60, 40, 20}));
  SynthRequest r = smallKinectBin();
  r.mesh_path = dir / "block.ply";
  r.count = 3;
  const SynthScene s = synthesize(r);
  ASSERT_EQ(s.scene.instances.size(), 3u);
  EXPECT_EQ(s.scene.parts[0].name, "block");
  std::size_t points = 0;
  for (auto n : s.render.visible_points)
    points += n;
  EXPECT_GT(points, 100u);
}
