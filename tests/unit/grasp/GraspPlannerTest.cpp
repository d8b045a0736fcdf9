#include "core/grasp/GraspPlanner.h"

#include "GraspScenes.h"
#include "core/common/Error.h"
#include "core/grasp/GraspJson.h"

#include <gtest/gtest.h>

using namespace scanpick::core;
using namespace scanpick::core::grasp;
using namespace scanpick::core::grasp::test;

namespace {

const Eigen::Vector3d kPartHalf(30, 20, 15); // a 60 x 40 x 30 mm box part

/// The box part as a taught model: its surface, with a grip point in the middle of its top face
/// (model z = -15: the model frame has the camera's axes, so the top faces -z) approached along +z.
GraspModel boxModel() {
  GraspModel m;
  m.cloud_mm = PointCloud::fromPoints(boxSurface(kPartHalf));
  m.grasps.push_back({"top", {0, 0, -kPartHalf.z()}, Eigen::Vector3d::UnitZ(), std::nullopt});
  return m;
}

/// A scene of the floor (500 x 500 mm around the origin) and box parts at the given poses.
PointCloud sceneWith(const std::vector<Eigen::Isometry3d>& parts) {
  std::vector<Eigen::Vector3f> points;
  addPlane(points, {-250, -250, kFloorZ}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 500,
           500, 3.0);
  for (const auto& T : parts)
    addPosed(points, boxSurface(kPartHalf), T);
  return PointCloud::fromPoints(points);
}

bool hasReason(const GraspCandidate& c, RejectKind kind, const std::string& text = "") {
  for (const auto& r : c.rejections)
    if (r.kind == kind && r.detail.find(text) != std::string::npos)
      return true;
  return false;
}

std::string reasons(const GraspCandidate& c) {
  std::string s;
  for (const auto& r : c.rejections)
    s += std::string(toString(r.kind)) + ": " + r.detail + "; ";
  return s;
}

/// Every grasp of the box on the floor holding `grasps`, detected with its half turn about up as
/// an alternative pose the scan cannot tell from it.
PickList planWithHalfTurnAlternative(std::vector<GraspPoint> grasps, bool reject_ambiguous) {
  const auto T = onFloor(0, 0, kPartHalf.z());
  GraspModel m = boxModel();
  m.grasps = std::move(grasps);
  Detection d = detectionAt(T);
  Eigen::Isometry3d turned = T;
  turned.linear() = Eigen::AngleAxisd(EIGEN_PI, Eigen::Vector3d::UnitZ()).matrix();
  d.alternative_poses = {turned};
  GraspPlanParams p;
  p.one_per_part = false;
  p.reject_ambiguous = reject_ambiguous;
  return planGrasps(sceneWith({T}), {d}, {m}, Gripper{}, std::nullopt, p);
}

} // namespace

TEST(GraspPlanner, AFreePartIsPickedFromAboveAtItsGripPoint) {
  const auto T = onFloor(0, 0, kPartHalf.z());
  const PickList list =
      planGrasps(sceneWith({T}), {detectionAt(T)}, {boxModel()}, Gripper{}, std::nullopt, {});
  ASSERT_EQ(list.picks.size(), 1u) << (list.rejected.empty() ? "" : reasons(list.rejected[0]));
  const GraspCandidate& c = list.picks[0];
  // Top face centre: z = 1000 - 30; the approach straight down (+z of the camera).
  EXPECT_TRUE(c.T_scene_tool.translation().isApprox(Eigen::Vector3d(0, 0, 970)));
  EXPECT_NEAR(c.tilt_deg, 0.0, 1e-9);
  EXPECT_NEAR(c.height_mm, -970.0, 1e-9);
  EXPECT_TRUE(c.T_scene_pregrasp.translation().isApprox(Eigen::Vector3d(0, 0, 870)));
  EXPECT_EQ(c.grip, "top");
}

TEST(GraspPlanner, ANeighbourUnderTheFlangeRejectsTheGraspAndIsNamed) {
  // The default flange (63 mm diameter, 15 mm behind the TCP) reaches 31.5 mm from the grip
  // point; a taller part 50 mm away (its near edge 20 mm away) stands up into it.
  const auto low = onFloor(0, 0, kPartHalf.z());
  Eigen::Isometry3d tall = onFloor(0, 50, kPartHalf.z());
  tall.translation().z() -= 40.0; // stacked on something: its top 40 mm higher
  GraspPlanParams p;
  p.one_per_part = true;
  const PickList list = planGrasps(sceneWith({low, tall}), {detectionAt(low), detectionAt(tall)},
                                   {boxModel()}, Gripper{}, std::nullopt, p);
  ASSERT_EQ(list.rejected.size(), 1u);
  EXPECT_EQ(list.rejected[0].detection, 0);
  EXPECT_TRUE(hasReason(list.rejected[0], RejectKind::PartCollision, "part #1"))
      << reasons(list.rejected[0]);
  ASSERT_EQ(list.picks.size(), 1u);
  EXPECT_EQ(list.picks[0].detection, 1);

  // The same clutter undetected is "scan points".
  const PickList alone = planGrasps(sceneWith({low, tall}), {detectionAt(low)}, {boxModel()},
                                    Gripper{}, std::nullopt, p);
  ASSERT_EQ(alone.rejected.size(), 1u);
  EXPECT_TRUE(hasReason(alone.rejected[0], RejectKind::SceneCollision, "body"))
      << reasons(alone.rejected[0]);
  // A slimmer flange passes by it.
  Gripper slim;
  slim.body.diameter_mm = 30.0;
  const PickList fits =
      planGrasps(sceneWith({low, tall}), {detectionAt(low)}, {boxModel()}, slim, std::nullopt, p);
  EXPECT_EQ(fits.picks.size(), 1u) << (fits.rejected.empty() ? "" : reasons(fits.rejected[0]));
}

TEST(GraspPlanner, TiltBeyondTheLimitIsRejectedAndEveryReasonIsListed) {
  // The part rests tilted 40 deg about x (on a wedge not in the scan): its top's approach is
  // tilted 40 deg.
  Eigen::Isometry3d T = onFloor(0, 0, 40.0);
  T.linear() = Eigen::AngleAxisd(40.0 * EIGEN_PI / 180.0, Eigen::Vector3d::UnitX()).matrix();
  GraspPlanParams p;
  p.max_tilt_deg = 30.0;
  const PickList list =
      planGrasps(sceneWith({T}), {detectionAt(T, 0.2)}, {boxModel()}, Gripper{}, std::nullopt, [&] {
        GraspPlanParams q = p;
        q.min_score = 0.5;
        return q;
      }());
  ASSERT_EQ(list.rejected.size(), 1u);
  EXPECT_NEAR(list.rejected[0].tilt_deg, 40.0, 1e-6);
  EXPECT_TRUE(hasReason(list.rejected[0], RejectKind::TiltTooLarge));
  EXPECT_TRUE(hasReason(list.rejected[0], RejectKind::LowScore));
  p.max_tilt_deg = 45.0;
  const PickList ok =
      planGrasps(sceneWith({T}), {detectionAt(T)}, {boxModel()}, Gripper{}, std::nullopt, p);
  EXPECT_EQ(ok.picks.size(), 1u) << (ok.rejected.empty() ? "" : reasons(ok.rejected[0]));
}

TEST(GraspPlanner, OrdersPicksHighestFirstByScoreOrByOcclusion) {
  // Three parts far apart: heights 0, +20 and +10 mm above the floor-resting height.
  std::vector<Eigen::Isometry3d> poses = {onFloor(-150, 0, 15), onFloor(0, 0, 15),
                                          onFloor(150, 0, 15)};
  poses[1].translation().z() -= 20.0;
  poses[2].translation().z() -= 10.0;
  const std::vector<Detection> dets = {detectionAt(poses[0], 0.9), detectionAt(poses[1], 0.5),
                                       detectionAt(poses[2], 0.7)};
  GraspPlanParams p;
  auto order = [&](PickOrder o) {
    p.order = o;
    const PickList l = planGrasps(sceneWith(poses), dets, {boxModel()}, Gripper{}, std::nullopt, p);
    std::vector<int> out;
    for (const auto& c : l.picks)
      out.push_back(c.detection);
    return out;
  };
  EXPECT_EQ(order(PickOrder::HighestFirst), (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(order(PickOrder::BestScore), (std::vector<int>{0, 2, 1}));
}

TEST(GraspPlanner, LeastOccludedPutsAPartUnderAnOverhangLast) {
  // Part 0 on the floor (x in [-90, -30]) with a plate 60 mm above its top over x in [-45, 15]
  // (undetected clutter, a shelf): a quarter of the part lies under it. Part 1 is free. The slim
  // gripper at part 0's grip point (x = -60) passes beside the plate.
  const auto under = onFloor(-60, 0, 15), free = onFloor(150, 0, 15);
  PointCloud scene = sceneWith({under, free});
  std::vector<Eigen::Vector3f> plate;
  addPlane(plate, {-45, -40, kFloorZ - 90}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 60,
           80, 3.0);
  for (const auto& q : plate)
    scene.points_mm.push_back(q);
  scene.width = std::uint32_t(scene.points_mm.size());
  GraspPlanParams p;
  p.order = PickOrder::LeastOccluded;
  Gripper slim;
  slim.body.diameter_mm = 20.0;
  slim.suction.diameter_mm = 20.0;
  const PickList l = planGrasps(scene, {detectionAt(under), detectionAt(free)}, {boxModel()}, slim,
                                std::nullopt, p);
  ASSERT_EQ(l.picks.size(), 2u) << (l.rejected.empty() ? "" : reasons(l.rejected[0]));
  EXPECT_EQ(l.picks[0].detection, 1);
  EXPECT_NEAR(l.picks[0].occlusion, 0.0, 1e-9);
  EXPECT_GT(l.picks[1].occlusion, 0.1); // a sizeable share of part 0 lies under the plate
}

TEST(GraspPlanner, FingersMustFitAroundThePartAndCloseOnNothingElse) {
  const auto T = onFloor(0, 0, kPartHalf.z());
  Gripper g;
  g.kind = GripperKind::Fingers;
  g.fingers = {10.0, 15.0, 40.0, 50.0, 10.0}; // opening 50 mm
  g.body.diameter_mm = 40.0;
  GraspModel m = boxModel();
  // Closing along the part's 40 mm side (y) fits; along its 60 mm side (x) it does not.
  m.grasps = {{"across-y", {0, 0, -15}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()},
              {"across-x", {0, 0, -15}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX()}};
  GraspPlanParams p;
  p.one_per_part = false;
  const PickList l = planGrasps(sceneWith({T}), {detectionAt(T)}, {m}, g, std::nullopt, p);
  ASSERT_EQ(l.picks.size(), 1u);
  EXPECT_EQ(l.picks[0].grip, "across-y");
  ASSERT_EQ(l.rejected.size(), 1u);
  EXPECT_TRUE(hasReason(l.rejected[0], RejectKind::PickedPart, "finger")) << reasons(l.rejected[0]);

  // A small undetected object right beside the part, between the open fingers: closing along y,
  // the fingers' inner faces lie at y = ±25 (±24 with the clearance), the part's sides at ±20
  // (±23 with the part tolerance), so it sits at y = 23.5; the fingertips reach z = 980.
  PointCloud scene = sceneWith({T});
  for (double x = -5; x <= 5; x += 1.0)
    for (double z = 972; z <= 980; z += 1.0)
      scene.points_mm.emplace_back(float(x), 23.5f, float(z));
  scene.width = std::uint32_t(scene.points_mm.size());
  m.grasps.resize(1);
  const PickList blocked = planGrasps(scene, {detectionAt(T)}, {m}, g, std::nullopt, p);
  ASSERT_EQ(blocked.rejected.size(), 1u);
  EXPECT_TRUE(hasReason(blocked.rejected[0], RejectKind::SceneCollision, "closing region"))
      << reasons(blocked.rejected[0]);
}

TEST(GraspPlanner, ThePartsOwnPointsDoNotBlockASuctionGrasp) {
  // With the part excluded nothing is hit; with a part tolerance of 0 its top face (inside the
  // cup's swept volume, grown by the clearance) counts as scan points.
  const auto T = onFloor(0, 0, kPartHalf.z());
  GraspPlanParams p;
  EXPECT_EQ(planGrasps(sceneWith({T}), {detectionAt(T)}, {boxModel()}, Gripper{}, std::nullopt, p)
                .picks.size(),
            1u);
  p.part_tolerance_mm = 0.0;
  p.clearance_mm = 2.0;
  // Detected slightly off (1 mm): with no tolerance its points are no longer its own.
  Eigen::Isometry3d off = T;
  off.translation().x() += 1.0;
  const PickList l =
      planGrasps(sceneWith({T}), {detectionAt(off)}, {boxModel()}, Gripper{}, std::nullopt, p);
  ASSERT_EQ(l.rejected.size(), 1u);
  EXPECT_TRUE(hasReason(l.rejected[0], RejectKind::SceneCollision, "cup"));
}

TEST(GraspPlanner, BinWallsAndFloorBlockGrasps) {
  // A part 10 mm from the bin's +x wall (x in [130, 190]): a 100 mm flange on its grip point
  // (x = 160) reaches x = 211 below the rim (the rim is 150 mm high, the part 30 mm), so the grasp
  // is rejected on the bin. A slim tool fits.
  BinBox bin;
  bin.T_scene_bin.translation() = Eigen::Vector3d(0, 0, kFloorZ);
  bin.T_scene_bin.linear() = Eigen::AngleAxisd(EIGEN_PI, Eigen::Vector3d::UnitX()).matrix();
  bin.half_size_mm = {200, 150};
  bin.rim_height_mm = 150;
  bin.floor_found = true;
  bin.walls_found = {true, true, true, true};
  const auto T = onFloor(200 - 30 - 10, 0, kPartHalf.z());
  std::vector<Eigen::Vector3f> pts;
  addPosed(pts, boxSurface(kPartHalf), T);
  const PointCloud scene = PointCloud::fromPoints(pts); // the planes stand for the bin's points
  GraspPlanParams p;
  Gripper wide;
  wide.body.diameter_mm = 100.0;
  const PickList l = planGrasps(scene, {detectionAt(T)}, {boxModel()}, wide, bin, p);
  ASSERT_EQ(l.rejected.size(), 1u);
  EXPECT_TRUE(hasReason(l.rejected[0], RejectKind::BinCollision, "bin wall +x"))
      << reasons(l.rejected[0]);
  Gripper slim;
  slim.body.diameter_mm = 30.0;
  EXPECT_EQ(planGrasps(scene, {detectionAt(T)}, {boxModel()}, slim, bin, p).picks.size(), 1u);
  // Fingers reaching 10 mm past a grip point 5 mm above the floor hit the floor.
  Gripper fingers;
  fingers.kind = GripperKind::Fingers;
  fingers.body.diameter_mm = 30.0;
  GraspModel m = boxModel();
  m.grasps = {{"low", {0, 0, 10}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()}};
  const auto centre = onFloor(0, 0, kPartHalf.z());
  std::vector<Eigen::Vector3f> pts2;
  addPosed(pts2, boxSurface(kPartHalf), centre);
  const PickList f =
      planGrasps(PointCloud::fromPoints(pts2), {detectionAt(centre)}, {m}, fingers, bin, p);
  ASSERT_EQ(f.rejected.size(), 1u);
  EXPECT_TRUE(hasReason(f.rejected[0], RejectKind::BinCollision, "bin floor"))
      << reasons(f.rejected[0]);
}

TEST(GraspPlanner, GraspsThatMoveBetweenIndistinguishablePosesAreRejected) {
  // Turned 180 deg about up: the corner moves, the centre stays.
  const std::vector<GraspPoint> grasps = {
      {"corner", {25, 15, -15}, Eigen::Vector3d::UnitZ(), std::nullopt},
      {"centre", {0, 0, -15}, Eigen::Vector3d::UnitZ(), std::nullopt}};
  const PickList l = planWithHalfTurnAlternative(grasps, true);
  ASSERT_EQ(l.rejected.size(), 1u);
  EXPECT_EQ(l.rejected[0].grip, "corner");
  EXPECT_TRUE(hasReason(l.rejected[0], RejectKind::Ambiguous));
  ASSERT_EQ(l.picks.size(), 1u);
  EXPECT_EQ(l.picks[0].grip, "centre");
  EXPECT_EQ(planWithHalfTurnAlternative(grasps, false).picks.size(), 2u);
}

TEST(GraspPlanner, AGraspThatASymmetricPartsAlternativePutsAnotherGraspOnIsKept) {
  // Two corners the half turn about up swaps, and a third it moves where no grasp is.
  const PickList l = planWithHalfTurnAlternative(
      {{"corner-a", {25, 15, -15}, Eigen::Vector3d::UnitZ(), std::nullopt},
       {"corner-b", {-25, -15, -15}, Eigen::Vector3d::UnitZ(), std::nullopt},
       {"corner-c", {25, -15, -15}, Eigen::Vector3d::UnitZ(), std::nullopt}},
      true);
  ASSERT_EQ(l.picks.size(), 2u);
  EXPECT_NE(l.picks[0].grip, "corner-c");
  EXPECT_NE(l.picks[1].grip, "corner-c");
  ASSERT_EQ(l.rejected.size(), 1u);
  EXPECT_EQ(l.rejected[0].grip, "corner-c");
  EXPECT_TRUE(hasReason(l.rejected[0], RejectKind::Ambiguous)) << reasons(l.rejected[0]);
}

TEST(GraspPlanner, IsDeterministicAndChecksItsInput) {
  std::vector<Eigen::Isometry3d> poses = {onFloor(-40, 0, 15), onFloor(40, 10, 15, 20)};
  poses[1].translation().z() -= 12.0;
  const std::vector<Detection> dets = {detectionAt(poses[0]), detectionAt(poses[1])};
  const PointCloud scene = sceneWith(poses);
  const auto a = toJson(planGrasps(scene, dets, {boxModel()}, Gripper{}, std::nullopt, {}));
  const auto b = toJson(planGrasps(scene, dets, {boxModel()}, Gripper{}, std::nullopt, {}));
  EXPECT_EQ(a.dump(), b.dump());
  Detection bad = dets[0];
  bad.model_index = 3;
  EXPECT_THROW((void)planGrasps(scene, {bad}, {boxModel()}, Gripper{}, std::nullopt, {}), Error);
  GraspPlanParams p;
  p.grid_cell_mm = 0.0;
  EXPECT_THROW((void)planGrasps(scene, dets, {boxModel()}, Gripper{}, std::nullopt, p), Error);
  // No detections: an empty list.
  const PickList none = planGrasps(scene, {}, {boxModel()}, Gripper{}, std::nullopt, {});
  EXPECT_TRUE(none.picks.empty());
  EXPECT_TRUE(none.rejected.empty());
}
