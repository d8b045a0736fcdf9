// The robot link with a hand-eye calibration, over loopback (a real TCP client against LinkServer
// on 127.0.0.1): the cell reads the calibration file `scanpick-cli calibrate` writes and every pick
// carries, next to its camera-frame poses, the tool and the part in the robot base frame
// (eye-to-hand: T_base_camera · T_camera_x; eye-in-hand: T_base_flange · T_flange_camera ·
// T_camera_x with the flange pose the trigger carries, as JSON or as binary command 6).
#include "core/calib/BaseFrame.h"
#include "core/calib/CalibJson.h"
#include "core/link/PlanningCell.h"
#include "tests/support/ErrorText.h"
#include "tests/support/LinkSoak.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;
using namespace scanpick::core::link;
using nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Isometry3d pose(const Eigen::Vector3d& t, const Eigen::Matrix3d& R) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

Eigen::Matrix3d turn(double deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(deg * kPi / 180, axis.normalized()).toRotationMatrix();
}

/// The camera 1.3 m above the base looking down (eye-to-hand), or 95 mm off the flange.
const Eigen::Isometry3d kBaseCamera = pose(
    {450, -120, 1300}, turn(25, Eigen::Vector3d::UnitZ()) * turn(184, Eigen::Vector3d::UnitX()));
const Eigen::Isometry3d kFlangeCamera =
    pose({-65, 40, 95}, turn(90, Eigen::Vector3d::UnitZ()) * turn(5, Eigen::Vector3d::UnitY()));
/// The flange pose of the eye-in-hand trigger: position (mm) and rotation vector (degrees).
const Eigen::Vector3d kFlangeAt(400, -20, 550), kFlangeTurn(170, 10, -20);

/// The middle one of three boxes (40 x 60 x 30 mm) on a floor 1000 mm below the camera; it is 20
/// mm higher than the others and is picked first, from its top at (0, 0, 950) camera frame.
const Eigen::Vector3d kTopCamera(0, 0, 950), kPartCamera(0, 0, 965);

std::vector<Eigen::Vector3f> boxSurface() {
  std::vector<Eigen::Vector3f> out;
  for (double x = -30; x <= 30; x += 3)
    for (double y = -20; y <= 20; y += 3)
      for (double z : {-15.0, 15.0})
        out.emplace_back(float(x), float(y), float(z));
  return out;
}

/// Writes a calibration file as calibrate does and reads it back as the server does.
calib::CameraCalibration calibrationFile(const test::TempDir& dir, calib::HandEyeMode mode,
                                         const Eigen::Isometry3d& T_camera) {
  calib::HandEyeResult r;
  r.mode = mode;
  r.T_camera = T_camera;
  r.T_target = pose({10, 0, 40}, Eigen::Matrix3d::Identity());
  r.poses_used = 10;
  const auto path = dir / (calib::modeName(mode) + ".json");
  calib::saveCalibration(path, r, calib::defaultTarget());
  return calib::loadCameraCalibration(path);
}

std::vector<CellRecipe> boxRecipes() {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 3; ++i)
    poses.push_back(
        pose({-150.0 + 150.0 * i, 0, 985.0 - (i == 1 ? 20.0 : 0.0)}, Eigen::Matrix3d::Identity()));
  CellRecipe r;
  r.name = "boxes";
  r.detect = [poses](const PointCloud&) {
    std::vector<Detection> dets;
    for (const auto& T : poses) {
      Detection d;
      d.T_scene_model = T;
      d.score = 0.9;
      dets.push_back(d);
    }
    return dets;
  };
  grasp::GraspModel model;
  model.cloud_mm = PointCloud::fromPoints(boxSurface());
  model.grasps = {{"top", {0, 0, -15}, Eigen::Vector3d::UnitZ(), std::nullopt}};
  r.models = {model};
  return {r};
}

PointCloud boxScene() {
  std::vector<Eigen::Vector3f> pts;
  for (double x = -250; x <= 250; x += 4)
    for (double y = -250; y <= 250; y += 4)
      pts.emplace_back(float(x), float(y), 1000.0f);
  for (int i = 0; i < 3; ++i)
    for (const auto& p : boxSurface())
      pts.push_back(p + Eigen::Vector3f(float(-150 + 150 * i), 0, float(985 - (i == 1 ? 20 : 0))));
  return PointCloud::fromPoints(pts);
}

struct Server {
  std::unique_ptr<LinkServer> server;
  explicit Server(std::optional<calib::CameraCalibration> calibration) {
    const PointCloud scene = boxScene();
    auto cell = std::make_shared<PlanningCell>([scene] { return scene; }, boxRecipes(),
                                               std::move(calibration));
    ServerOptions options;
    options.host = "127.0.0.1";
    options.port = 0;
    server = std::make_unique<LinkServer>(std::make_shared<CellService>(cell), options);
    server->start();
  }
  [[nodiscard]] int port() const { return server->port(); }
};

json ask(test::soak::Conn& c, const std::string& line) {
  c.send(line + "\n");
  return json::parse(c.answer(), nullptr, false);
}

Eigen::Vector3d vec(const json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

/// A binary trigger at a flange pose with the rotation given as Euler angles Rz·Ry·Rx (field 3 =
/// 1), built field by field as a robot controller would.
std::string binaryTriggerAtEuler(std::int32_t id, const Eigen::Isometry3d& F) {
  const Eigen::Vector3d e = eulerZyxDeg(F.linear());
  const std::int32_t fields[12] = {kMagic,
                                   6,
                                   id,
                                   1,
                                   std::int32_t(std::lround(F.translation().x() * kPositionScale)),
                                   std::int32_t(std::lround(F.translation().y() * kPositionScale)),
                                   std::int32_t(std::lround(F.translation().z() * kPositionScale)),
                                   std::int32_t(std::lround(e.x() * kAngleScale)),
                                   std::int32_t(std::lround(e.y() * kAngleScale)),
                                   std::int32_t(std::lround(e.z() * kAngleScale)),
                                   0,
                                   0};
  std::string out;
  for (std::int32_t f : fields)
    for (int b = 0; b < 4; ++b)
      out.push_back(char((std::uint32_t(f) >> (8 * b)) & 0xFFu));
  return out;
}

} // namespace

TEST(RobotLinkBaseFrame, EyeToHandPicksCarryBaseFramePoses) {
  const test::TempDir dir;
  Server s(calibrationFile(dir, calib::HandEyeMode::EyeToHand, kBaseCamera));
  test::soak::Conn c(s.port());
  ASSERT_TRUE(c.connected());
  const json st = ask(c, R"({"cmd":"status"})");
  EXPECT_EQ(st["calibration"], "eye-to-hand.json");
  EXPECT_EQ(st["base_frame"], true);
  EXPECT_EQ(st["needs_flange_pose"], false);
  ASSERT_EQ(ask(c, R"({"cmd":"trigger","id":1})")["status"], "ok");
  const json next = ask(c, R"({"cmd":"next","id":2})");
  ASSERT_EQ(next["status"], "ok") << next.dump();
  const json& pick = next["pick"];
  // The camera-frame poses as before, the base-frame ones next to them.
  EXPECT_LT((vec(pick["position_mm"]) - kTopCamera).norm(), 1e-9);
  EXPECT_LT((vec(pick["part"]["position_mm"]) - kPartCamera).norm(), 1e-9);
  EXPECT_LT((vec(pick["pose_base"]["position_mm"]) - kBaseCamera * kTopCamera).norm(), 1e-6);
  EXPECT_LT((vec(pick["pose_base"]["part"]["position_mm"]) - kBaseCamera * kPartCamera).norm(),
            1e-6);
  // The tool's orientation in the base: the camera's rotation applied to the camera-frame one.
  const auto rotationOf = [](const json& q) {
    return Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(),
                              q[3].get<double>())
        .toRotationMatrix();
  };
  EXPECT_LT((rotationOf(pick["pose_base"]["quaternion_wxyz"]) -
             kBaseCamera.linear() * rotationOf(pick["quaternion_wxyz"]))
                .norm(),
            1e-6);
  // The pre-grasp point lies back along the approach, in the base as well.
  const Eigen::Vector3d pre = vec(pick["pose_base"]["pregrasp_position_mm"]);
  EXPECT_NEAR((pre - vec(pick["pose_base"]["position_mm"])).norm(),
              pick["approach_length_mm"].get<double>(), 1e-6);

  // Binary answers carry the base-frame pose (a robot controller's frame).
  Request r;
  r.command = Command::NextPick;
  r.id = 3;
  c.send(encodeBinaryRequest(r));
  const auto a = decodeBinaryResponse(c.answer());
  ASSERT_TRUE(a);
  EXPECT_EQ(a->status(), 0);
  // The next box: 20 mm lower, 150 mm to either side (they tie).
  const double off = std::min(
      (a->position_mm() - kBaseCamera * (kTopCamera + Eigen::Vector3d(-150, 0, 20))).norm(),
      (a->position_mm() - kBaseCamera * (kTopCamera + Eigen::Vector3d(150, 0, 20))).norm());
  EXPECT_LT(off, 1e-4);
  r.command = Command::Status;
  c.send(encodeBinaryRequest(r));
  const auto status = decodeBinaryResponse(c.answer());
  ASSERT_TRUE(status);
  EXPECT_EQ(status->fields[23], 2); // base frame, no flange pose needed, not busy

  // An eye-to-hand cell refuses a flange pose: the calibration is likely the wrong one.
  const json refused = ask(c, R"({"cmd":"trigger","flange_pose":[400,-20,550,180,0,0]})");
  EXPECT_EQ(refused["code"], int(Status::Malformed)) << refused.dump();
  EXPECT_NE(refused["message"].get<std::string>().find("eye-to-hand calibration"),
            std::string::npos);
}

TEST(RobotLinkBaseFrame, EyeInHandTriggersCarryTheFlangePose) {
  const test::TempDir dir;
  Server s(calibrationFile(dir, calib::HandEyeMode::EyeInHand, kFlangeCamera));
  const Eigen::Isometry3d F = calib::poseFromRotationVector(kFlangeAt, kFlangeTurn);
  const Eigen::Isometry3d T_base_camera = F * kFlangeCamera;
  test::soak::Conn c(s.port());
  ASSERT_TRUE(c.connected());
  EXPECT_EQ(ask(c, R"({"cmd":"status"})")["needs_flange_pose"], true);
  const json missing = ask(c, R"({"cmd":"trigger","id":1})");
  EXPECT_EQ(missing["code"], int(Status::NoFlangePose)) << missing.dump();
  EXPECT_EQ(missing["status"], "no-flange-pose");
  EXPECT_EQ(ask(c, R"({"cmd":"trigger","flange_pose":[1,2,3]})")["code"], int(Status::Malformed));
  EXPECT_EQ(ask(c, R"({"cmd":"status","flange_pose":[400,-20,550,170,10,-20]})")["code"],
            int(Status::Malformed));

  // JSON: [x, y, z, rx, ry, rz], mm and a rotation vector in degrees.
  const json t = ask(c, R"({"cmd":"trigger","id":2,"flange_pose":[400,-20,550,170,10,-20]})");
  ASSERT_EQ(t["status"], "ok") << t.dump();
  const json pick = ask(c, R"({"cmd":"next"})")["pick"];
  EXPECT_LT((vec(pick["position_mm"]) - kTopCamera).norm(), 1e-9);
  EXPECT_LT((vec(pick["pose_base"]["position_mm"]) - T_base_camera * kTopCamera).norm(), 1e-6);
  EXPECT_LT((vec(pick["pose_base"]["part"]["position_mm"]) - T_base_camera * kPartCamera).norm(),
            1e-6);

  // Binary command 6, rotation vector (field 3 = 0) and Euler angles (field 3 = 1); the binary
  // flange pose has 0.1 µm and 0.0001° steps, which move a point 1.3 m away by under 0.01 mm.
  for (int convention = 0; convention < 2; ++convention) {
    Request r;
    r.command = Command::Trigger;
    r.id = 10 + convention;
    const Eigen::Quaterniond q(F.linear());
    r.flange_pose = std::array<double, 7>{kFlangeAt.x(), kFlangeAt.y(), kFlangeAt.z(), q.w(),
                                          q.x(),         q.y(),         q.z()};
    c.send(convention == 0 ? encodeBinaryRequest(r) : binaryTriggerAtEuler(r.id, F));
    const auto a = decodeBinaryResponse(c.answer());
    ASSERT_TRUE(a);
    EXPECT_EQ(a->status(), 0) << convention;
    EXPECT_EQ(a->command(), 6);
    EXPECT_EQ(a->count(), 3);
    Request next;
    next.command = Command::NextPick;
    c.send(encodeBinaryRequest(next));
    const auto n = decodeBinaryResponse(c.answer());
    ASSERT_TRUE(n);
    EXPECT_LT((n->position_mm() - T_base_camera * kTopCamera).norm(), 0.01) << convention;
  }
  // A rotation convention other than 0 and 1 is malformed.
  std::string bad = binaryTriggerAtEuler(20, F);
  bad[12] = 5;
  c.send(bad);
  const auto a = decodeBinaryResponse(c.answer());
  ASSERT_TRUE(a);
  EXPECT_EQ(a->status(), int(Status::Malformed));
  EXPECT_EQ(a->id(), 20);
}

TEST(RobotLinkBaseFrame, CellsWithoutACalibrationRefuseFlangePoses) {
  Server s(std::nullopt);
  test::soak::Conn c(s.port());
  const json st = ask(c, R"({"cmd":"status"})");
  EXPECT_TRUE(st["calibration"].is_null());
  EXPECT_EQ(st["base_frame"], false);
  const json refused = ask(c, R"({"cmd":"trigger","flange_pose":[400,-20,550,180,0,0]})");
  EXPECT_EQ(refused["code"], int(Status::Malformed));
  EXPECT_NE(refused["message"].get<std::string>().find("no hand-eye calibration"),
            std::string::npos);
  ASSERT_EQ(ask(c, R"({"cmd":"trigger"})")["status"], "ok");
  const json pick = ask(c, R"({"cmd":"next"})")["pick"];
  EXPECT_FALSE(pick.contains("pose_base"));
  EXPECT_LT((vec(pick["position_mm"]) - kTopCamera).norm(), 1e-9);
}

TEST(RobotLinkBaseFrame, ACalibrationAndARecipePlacingTheCameraAreRefusedTogether) {
  const test::TempDir dir;
  auto recipes = boxRecipes();
  recipes[0].T_robot_scene.translation() = Eigen::Vector3d(1000, 0, 0);
  const auto calibration = calibrationFile(dir, calib::HandEyeMode::EyeToHand, kBaseCamera);
  EXPECT_EQ(test::errorOf([&] { PlanningCell([] { return PointCloud(); }, recipes, calibration); }),
            "recipe 'boxes' places the camera in the robot frame itself (robot_from_camera) and "
            "the cell has the calibration eye-to-hand.json: give one of the two");
}
