// The calibration target and the calibration's files: the built-in target can be matched without
// ambiguity, bad targets are refused with what to change, poses are read as 4 × 4 matrices or
// position + quaternion in mm or m, and a result file reads back.
#include "core/calib/CalibTarget.h"

#include "core/calib/CalibJson.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "tests/support/ErrorText.h"
#include "tests/support/TempDir.h"
#include "tests/unit/calib/CalibScenes.h"

#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core::calib;
using json = nlohmann::json;
using test::errorOf;

TEST(CalibTarget, TheDefaultTargetsDistancesAllDiffer) {
  // Six distances between four spheres, the closest two 8.3 mm apart: far more than the 2 mm
  // matching tolerance, so no sphere can be taken for another.
  const TargetLayout t = defaultTarget();
  EXPECT_EQ(t.sphere_centres_mm.size(), 4u);
  EXPECT_NEAR(smallestDistanceGap_mm(t), 8.29, 0.01);
  EXPECT_NO_THROW(validateTarget(t, 4.0));
}

TEST(CalibTarget, BadLayoutsAreRefusedWithWhatToChange) {
  TargetLayout t = defaultTarget();
  t.sphere_centres_mm.resize(2);
  EXPECT_NE(errorOf([&] { validateTarget(t, 4); }).find("it needs at least 3"), std::string::npos);
  t.sphere_centres_mm = {{0, 0, 0}, {50, 0, 0}, {120, 0.5, 0}};
  EXPECT_NE(errorOf([&] { validateTarget(t, 4); }).find("on one line"), std::string::npos);
  t.sphere_centres_mm = {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}}; // an isosceles triangle
  EXPECT_NE(errorOf([&] { validateTarget(t, 4); }).find("differ by only 0.0 mm"),
            std::string::npos);
  t.sphere_centres_mm = {{0, 0, 0}, {20, 0, 0}, {0, 100, 0}};
  EXPECT_NE(errorOf([&] { validateTarget(t, 4); }).find("overlap"), std::string::npos);
}

TEST(CalibJson, TargetsRoundTripAndUnknownKeysAreRefused) {
  const TargetLayout t = defaultTarget();
  EXPECT_EQ(targetFromJson(toJson(t), "t", 4.0), t);
  json j = toJson(t);
  j["sphere_radius"] = 3;
  EXPECT_NE(
      errorOf([&] { targetFromJson(j, "t.json", 4.0); }).find("unknown key \"sphere_radius\""),
      std::string::npos);
  j = toJson(t);
  j.erase("sphere_radius_mm");
  EXPECT_NE(errorOf([&] { targetFromJson(j, "t.json", 4.0); }).find("sphere_radius_mm"),
            std::string::npos);
}

TEST(CalibJson, PosesReadAsMatrixOrQuaternionInEitherUnit) {
  const Eigen::Isometry3d T = test::pose({0.4, -0.1, 0.3}, test::rotation(70, {1, -2, 0.5}));
  const json as_json = poseToJson(T);
  // The matrix and the quaternion form give the same pose; metres become millimetres.
  const Eigen::Isometry3d a = poseFromJson(as_json["matrix"], 1000, "a");
  const Eigen::Isometry3d b = poseFromJson(json{{"x", as_json["x"]},
                                                {"y", as_json["y"]},
                                                {"z", as_json["z"]},
                                                {"qw", as_json["qw"]},
                                                {"qx", as_json["qx"]},
                                                {"qy", as_json["qy"]},
                                                {"qz", as_json["qz"]}},
                                           1000, "b");
  for (const auto& p : {a, b}) {
    EXPECT_LT((p.translation() - 1000 * T.translation()).norm(), 1e-9);
    EXPECT_LT(test::angleBetween_deg(p, T), 1e-6);
  }
  EXPECT_NE(errorOf([] {
              poseFromJson(json{{"x", 1}}, 1, "pose 3");
            }).find("pose 3 needs"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              poseFromJson(
                  json{{"x", 1}, {"y", 1}, {"z", 1}, {"qw", 1}, {"qx", 1}, {"qy", 0}, {"qz", 0}}, 1,
                  "p");
            }).find("must have length 1"),
            std::string::npos);
  json skewed = as_json["matrix"];
  skewed[0][1] = 0.5;
  EXPECT_NE(errorOf([&] { poseFromJson(skewed, 1, "p"); }).find("not a rotation matrix"),
            std::string::npos);
}

TEST(CalibJson, PoseListsResolveScansNextToTheFile) {
  test::TempDir dir;
  core::writeFileAtomic(
      dir / "poses.json",
      R"([{"scan": "a.pcd", "T_base_flange": [[1,0,0,0.1],[0,1,0,0.2],[0,0,1,0.3],)"
      R"([0,0,0,1]]}, {"scan": "/abs/b.pcd", "T_base_flange": {"x": 1, "y": 2, )"
      R"("z": 3, "qw": 1, "qx": 0, "qy": 0, "qz": 0}}])");
  const auto list = loadPoseList(dir / "poses.json", 1000);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].scan, dir / "a.pcd");
  EXPECT_EQ(list[1].scan, std::filesystem::path("/abs/b.pcd"));
  EXPECT_LT((list[0].T_base_flange.translation() - Eigen::Vector3d(100, 200, 300)).norm(), 1e-9);
  EXPECT_LT((list[1].T_base_flange.translation() - Eigen::Vector3d(1000, 2000, 3000)).norm(), 1e-9);
  core::writeFileAtomic(dir / "bad.json", R"([{"scan": "a.pcd"}])");
  EXPECT_NE(errorOf([&] {
              loadPoseList(dir / "bad.json", 1);
            }).find("pose 1 must be {\"scan\": PATH, \"T_base_flange\": pose}"),
            std::string::npos);
}

TEST(CalibJson, ResultsReadBack) {
  test::TempDir dir;
  HandEyeResult r;
  r.mode = HandEyeMode::EyeInHand;
  r.T_camera = test::pose({1, 2, 3}, test::rotation(10, {0, 1, 0}));
  r.T_target = test::pose({600, 0, 20}, test::rotation(-35, {0, 0, 1}));
  r.residuals = {{0, 0.01, 0.02, 0.003, false, ""}, {1, 5.0, 6.0, 1.0, true, "wrong"}};
  r.poses_used = 1;
  saveCalibration(dir / "c.json", r, defaultTarget());
  const json doc = json::parse(core::readFile(dir / "c.json"));
  EXPECT_EQ(doc["mode"], "eye-in-hand");
  EXPECT_EQ(doc["poses_rejected"][0]["pose"], 2);
  EXPECT_TRUE(doc.contains("T_flange_camera"));
  const HandEyeResult back = loadCalibration(dir / "c.json");
  EXPECT_EQ(back.mode, r.mode);
  EXPECT_LT((back.T_camera.matrix() - r.T_camera.matrix()).norm(), 1e-9);
  EXPECT_LT((back.T_target.matrix() - r.T_target.matrix()).norm(), 1e-9);
}
