// Poses in the robot base frame at the command line, as an integrator gets them: the virtual PhoXi
// scans the calibration target at 8 simulated robot poses, `scanpick-cli calibrate` solves the
// hand-eye calibration from them (eye-to-hand and eye-in-hand), and `scanpick-cli recognize
// --calibration` then finds supports in a simulated scan and writes each one's pose in the robot
// base ("pose_base"). The truth in the base is the simulated cell's: eye-to-hand
// T_base_camera · T_camera_part, eye-in-hand T_base_flange · T_flange_camera · T_camera_part with
// the flange pose given. Bad calibrations and missing or unexpected flange poses are refused with
// a one-line message, exit code 1 and no results file.
#include "core/calib/BaseFrame.h"
#include "core/calib/CalibJson.h"
#include "core/cloud/CloudIo.h"
#include "core/common/AtomicFile.h"
#include "core/eval/ResultsFile.h"
#include "core/model/ModelFile.h"
#include "tests/integration/SynthTeach.h"
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

Eigen::Isometry3d matrixOf(const json& rows) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      T.matrix()(r, c) = rows[std::size_t(r)][std::size_t(c)].get<double>();
  return T;
}

/// Writes the scans of `cell` and their poses file into `dir`, runs calibrate; returns the
/// calibration file.
fs::path calibrate(const test::SimulatedCell& cell, const fs::path& dir, const std::string& mode) {
  const auto mesh = test::targetMesh(core::calib::defaultTarget());
  json poses = json::array();
  for (int i = 0; i < int(cell.T_base_flange.size()); ++i) {
    const std::string scan = mode + "-scan-" + std::to_string(i + 1) + ".pcd";
    core::saveCloudPcd(dir / scan, core::dropInvalid(test::scanOf(cell, i, mesh)));
    json pose = core::calib::poseToJson(cell.T_base_flange[std::size_t(i)]);
    pose.erase("matrix");
    poses.push_back({{"scan", scan}, {"T_base_flange", pose}});
  }
  core::writeFileAtomic(dir / (mode + "-poses.json"), poses.dump(2));
  const fs::path out = dir / (mode + ".json");
  const int code = exitCode(runCli({"calibrate", "--mode", mode, "--poses",
                                    quoted(dir / (mode + "-poses.json")), "--out", quoted(out)},
                                   dir / "calibrate-log.txt"));
  EXPECT_EQ(code, 0) << readText(dir / "calibrate-log.txt");
  return out;
}

/// A truth instance of the scene: where the taught model lies on it, camera frame.
struct Truth {
  std::vector<Eigen::Isometry3d> T_camera_model;
};

class CliBaseFrame : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    if (!fs::exists(test::kCli))
      return;
    s_dir = std::make_unique<test::TempDir>();
    const fs::path& d = s_dir->path();
    s_eye_to_hand = test::eyeToHandCell(kPoses, 21);
    s_eye_in_hand = test::eyeInHandCell(kPoses, 22);
    s_e2h = calibrate(s_eye_to_hand, d, "eye-to-hand");
    s_eih = calibrate(s_eye_in_hand, d, "eye-in-hand");
    // A support taught on a table, then three supports scattered on a table.
    const core::RecognitionParams params = test::bundledPreset("phoxi-bin");
    const test::SynthTeach taught = test::teachFromSynth("support", 5, params);
    core::saveModel(d / "support.spmodel", *taught.model);
    core::SynthRequest request;
    request.parts = {"support"};
    request.layout = core::LayoutKind::Scatter;
    request.count = 3;
    request.seed = 11;
    const core::SynthScene scene = core::synthesize(request);
    core::saveCloudPcd(d / "scene.pcd", scene.render.cloud);
    s_truth = {};
    for (const auto& instance : scene.scene.instances)
      s_truth.T_camera_model.push_back(scene.scene.T_scene_part(instance) * taught.T_part_model());
  }
  static void TearDownTestSuite() { s_dir.reset(); }
  void SetUp() override {
    if (!s_dir)
      GTEST_SKIP() << test::kCli << " is not built (build the scanpick-cli target first)";
  }

  /// Runs recognize on the scene with `extra` options; output in log().
  int recognize(const fs::path& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"recognize",
                                  "--model",
                                  quoted(*s_dir / "support.spmodel"),
                                  "--scene",
                                  quoted(*s_dir / "scene.pcd"),
                                  "--preset",
                                  "phoxi-bin",
                                  "--out",
                                  quoted(out)};
    args.insert(args.end(), extra.begin(), extra.end());
    return exitCode(runCli(args, *s_dir / "log.txt"));
  }
  static std::string log() { return readText(*s_dir / "log.txt"); }

  /// Checks every detection's pose_base against `T_base_camera` (the true camera in the base)
  /// applied to its camera pose and to the nearest truth instance. Returns the detections seen.
  static int expectBaseFrame(const json& doc, const Eigen::Isometry3d& T_base_camera) {
    int n = 0;
    for (const auto& d : doc["detections"]) {
      const Eigen::Isometry3d T_camera_model = matrixOf(d["T_scene_model"]);
      const Eigen::Isometry3d T_base_model = matrixOf(d["pose_base"]["matrix"]);
      // The calibration's own error, carried to the part (about 1.3 m from the camera): the
      // calibration goal is 0.2 mm / 0.05°; a rotation error of 0.05° moves a point 1.3 m away by
      // 1.1 mm, so the bound on the position is that.
      const Eigen::Isometry3d expected = T_base_camera * T_camera_model;
      EXPECT_LT(test::distanceBetween_mm(T_base_model, expected), 1.2);
      EXPECT_LT(test::angleBetween_deg(T_base_model, expected), 0.05);
      const Eigen::Vector3d p(d["pose_base"]["position_mm"][0].get<double>(),
                              d["pose_base"]["position_mm"][1].get<double>(),
                              d["pose_base"]["position_mm"][2].get<double>());
      EXPECT_LT((p - T_base_model.translation()).norm(), 1e-9);
      // Against the truth in the base: recognition's error adds to the calibration's.
      double best_mm = 1e9, best_deg = 0;
      for (const auto& T_true : s_truth.T_camera_model) {
        const Eigen::Isometry3d T_base_true = T_base_camera * T_true;
        const double mm = test::distanceBetween_mm(T_base_model, T_base_true);
        if (mm < best_mm)
          best_mm = mm, best_deg = test::angleBetween_deg(T_base_model, T_base_true);
      }
      std::printf("detection in the base: %.3f mm / %.3f deg from the truth\n", best_mm, best_deg);
      EXPECT_LT(best_mm, 3.0);
      EXPECT_LT(best_deg, 2.0);
      ++n;
    }
    return n;
  }

  static inline std::unique_ptr<test::TempDir> s_dir;
  static inline test::SimulatedCell s_eye_to_hand, s_eye_in_hand;
  static inline fs::path s_e2h, s_eih;
  static inline Truth s_truth;
};

/// A flange pose for the eye-in-hand scan: position (mm) and rotation vector (degrees).
const Eigen::Vector3d kFlangeAt(420.0, -35.0, 610.0);
const Eigen::Vector3d kFlangeTurn(170.0, 12.0, -20.0);

} // namespace

TEST_F(CliBaseFrame, EyeToHandPosesInTheBaseMatchTheTruth) {
  const fs::path out = *s_dir / "e2h-results.json";
  ASSERT_EQ(recognize(out, {"--calibration", quoted(s_e2h)}), 0) << log();
  const json doc = json::parse(readText(out));
  EXPECT_EQ(doc["calibration"]["file"], "eye-to-hand.json");
  EXPECT_EQ(doc["calibration"]["mode"], "eye-to-hand");
  EXPECT_FALSE(doc["calibration"].contains("T_base_flange"));
  EXPECT_GE(expectBaseFrame(doc, s_eye_to_hand.X), 1);
  // Grip points follow the part into the base frame.
  for (const auto& d : doc["detections"])
    for (const auto& g : d["grip_points"])
      EXPECT_TRUE(g.contains("position_base_mm"));
  // The evaluator's reader takes the file as before.
  const core::eval::ResultsFile read = core::eval::loadResults(out);
  EXPECT_EQ(read.detections.size(), doc["detections"].size());
}

TEST_F(CliBaseFrame, WithoutACalibrationTheResultsAreAsBefore) {
  const fs::path out = *s_dir / "camera-results.json";
  ASSERT_EQ(recognize(out), 0) << log();
  const json doc = json::parse(readText(out));
  EXPECT_FALSE(doc.contains("calibration"));
  ASSERT_FALSE(doc["detections"].empty());
  for (const auto& d : doc["detections"])
    EXPECT_FALSE(d.contains("pose_base"));
  EXPECT_EQ(core::eval::loadResults(out).detections.size(), doc["detections"].size());
}

TEST_F(CliBaseFrame, EyeInHandPosesUseTheFlangePose) {
  const Eigen::Isometry3d F = core::calib::poseFromRotationVector(kFlangeAt, kFlangeTurn);
  char flange[160];
  std::snprintf(flange, sizeof flange, "%.3f,%.3f,%.3f,%.3f,%.3f,%.3f", kFlangeAt.x(),
                kFlangeAt.y(), kFlangeAt.z(), kFlangeTurn.x(), kFlangeTurn.y(), kFlangeTurn.z());
  const fs::path out = *s_dir / "eih-results.json";
  ASSERT_EQ(recognize(out, {"--calibration", quoted(s_eih), "--flange-pose", flange}), 0) << log();
  const json doc = json::parse(readText(out));
  EXPECT_EQ(doc["calibration"]["mode"], "eye-in-hand");
  EXPECT_LT((matrixOf(doc["calibration"]["T_base_flange"]["matrix"]).matrix() - F.matrix()).norm(),
            1e-9);
  // The truth: T_base_part = T_base_flange · T_flange_camera · T_camera_part.
  EXPECT_GE(expectBaseFrame(doc, F * s_eye_in_hand.X), 1);

  // The same flange pose as position + quaternion (w first, as in calibrate's poses file).
  const Eigen::Quaterniond q(F.linear());
  char as_quaternion[200];
  std::snprintf(as_quaternion, sizeof as_quaternion, "%.3f,%.3f,%.3f,%.12f,%.12f,%.12f,%.12f",
                kFlangeAt.x(), kFlangeAt.y(), kFlangeAt.z(), q.w(), q.x(), q.y(), q.z());
  const fs::path out_q = *s_dir / "eih-results-q.json";
  ASSERT_EQ(recognize(out_q, {"--calibration", quoted(s_eih), "--flange-pose", as_quaternion}), 0)
      << log();
  const json doc_q = json::parse(readText(out_q));
  ASSERT_EQ(doc_q["detections"].size(), doc["detections"].size());
  for (std::size_t i = 0; i < doc["detections"].size(); ++i)
    EXPECT_LT((matrixOf(doc_q["detections"][i]["pose_base"]["matrix"]).matrix() -
               matrixOf(doc["detections"][i]["pose_base"]["matrix"]).matrix())
                  .norm(),
              1e-6);
}

TEST_F(CliBaseFrame, MissingOrUnexpectedFlangePosesAreRefused) {
  const fs::path out = *s_dir / "refused.json";
  EXPECT_EQ(recognize(out, {"--calibration", quoted(s_eih)}), 1);
  EXPECT_NE(log().find("error: eye-in-hand.json is an eye-in-hand calibration (the camera rides "
                       "on the flange): give the flange pose"),
            std::string::npos)
      << log();
  EXPECT_EQ(recognize(out, {"--calibration", quoted(s_e2h), "--flange-pose", "1,2,3,0,0,0"}), 1);
  EXPECT_NE(log().find("error: eye-to-hand.json is an eye-to-hand calibration (the camera stands "
                       "still): it needs no flange pose"),
            std::string::npos)
      << log();
  EXPECT_EQ(recognize(out, {"--flange-pose", "1,2,3,0,0,0"}), 1);
  EXPECT_NE(log().find("error: --flange-pose needs --calibration"), std::string::npos) << log();
  EXPECT_EQ(recognize(out, {"--calibration", quoted(s_eih), "--flange-pose", "1,2,3"}), 1);
  EXPECT_NE(log().find("error: --flange-pose must be 6 numbers x,y,z,rx,ry,rz (mm; rotation "
                       "vector in degrees) or 7 numbers"),
            std::string::npos)
      << log();
  EXPECT_EQ(recognize(out, {"--calibration", quoted(s_eih), "--flange-pose", "1,2,3,0,0,deg"}), 1);
  EXPECT_NE(log().find("error: --flange-pose '1,2,3,0,0,deg': expected comma-separated numbers"),
            std::string::npos)
      << log();
  EXPECT_EQ(
      recognize(out, {"--calibration", quoted(s_eih), "--flange-pose", "1,2,3,0.5,0.5,0.5,0"}), 1);
  EXPECT_NE(log().find("the quaternion (qw, qx, qy, qz) must have length 1"), std::string::npos)
      << log();
  // A suite of eye-in-hand scans would need one flange pose per scan.
  EXPECT_EQ(exitCode(runCli({"recognize", "--model", quoted(*s_dir / "support.spmodel"), "--suite",
                             quoted(s_dir->path()), "--calibration", quoted(s_eih), "--flange-pose",
                             "1,2,3,0,0,0", "--out", quoted(*s_dir / "suite-out")},
                            *s_dir / "log.txt")),
            1);
  EXPECT_NE(log().find("recognize the scans one at a time with --scene and --flange-pose"),
            std::string::npos)
      << log();
  EXPECT_FALSE(fs::exists(*s_dir / "suite-out"));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliBaseFrame, MalformedCalibrationFilesAreRefused) {
  const json good = json::parse(readText(s_e2h));
  const fs::path out = *s_dir / "refused.json";
  const auto refused = [&](const std::string& name, const std::function<void(json&)>& change) {
    json doc = good;
    change(doc);
    core::writeFileAtomic(*s_dir / name, doc.dump(2));
    EXPECT_EQ(recognize(out, {"--calibration", quoted(*s_dir / name)}), 1) << name;
    EXPECT_FALSE(fs::exists(out)) << name;
    return log();
  };
  // A skewed rotation (a column scaled by 1.1).
  std::string message = refused("skewed.json", [](json& d) {
    for (std::size_t r = 0; r < 3; ++r)
      d["T_base_camera"]["matrix"][r][0] = d["T_base_camera"]["matrix"][r][0].get<double>() * 1.1;
  });
  EXPECT_NE(message.find("skewed.json' T_base_camera: the upper left 3 x 3 block is not a "
                         "rotation matrix"),
            std::string::npos)
      << message;
  // A number too large for a double (JSON has no infinity or NaN): the file is refused as it is
  // read.
  const auto withInfinity = [&](const std::string& name, const std::function<void(json&)>& mark) {
    json doc = good;
    mark(doc); // puts the sentinel 12345.678 where the infinity goes
    std::string text = doc.dump(2);
    text.replace(text.find("12345.678"), 9, "1e999");
    core::writeFileAtomic(*s_dir / name, text);
    EXPECT_EQ(recognize(out, {"--calibration", quoted(*s_dir / name)}), 1) << name;
    EXPECT_FALSE(fs::exists(out)) << name;
    return log();
  };
  for (const std::string name : {"infinite-matrix.json", "infinite-x.json"}) {
    message = withInfinity(name, [&](json& d) {
      if (name == "infinite-matrix.json") {
        d["T_base_camera"]["matrix"][0][3] = 12345.678;
      } else {
        d["T_base_camera"].erase("matrix");
        d["T_base_camera"]["x"] = 12345.678;
      }
    });
    EXPECT_NE(message.find(name + "' is not valid JSON"), std::string::npos) << message;
    EXPECT_NE(message.find("number overflow parsing '1e999'"), std::string::npos) << message;
  }
  message = refused("not-calibration.json", [](json& d) { d["format"] = "scanpick-results"; });
  EXPECT_NE(message.find("is not a hand-eye calibration"), std::string::npos) << message;
  message = refused("no-camera.json", [](json& d) { d.erase("T_base_camera"); });
  EXPECT_NE(message.find("\"T_base_camera\" is missing"), std::string::npos) << message;
  message = refused("bad-mode.json", [](json& d) { d["mode"] = "sideways"; });
  EXPECT_NE(message.find("bad-mode.json': unknown calibration mode 'sideways'"), std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(out));
}
