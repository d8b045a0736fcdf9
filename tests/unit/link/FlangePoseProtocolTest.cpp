// The flange pose in the robot link's requests (docs/robot-link.md, "Poses in the robot base
// frame"): JSON "flange_pose" and the 48-byte binary trigger at a flange pose (command 6), cut
// from a stream and decoded.
#include "core/calib/BaseFrame.h"
#include "core/link/RequestFramer.h"

#include <gtest/gtest.h>

using namespace scanpick::core;
using namespace scanpick::core::link;

namespace {

Request triggerAt(std::int32_t id, const Eigen::Isometry3d& F) {
  const Eigen::Quaterniond q(F.linear());
  Request r;
  r.command = Command::Trigger;
  r.id = id;
  r.flange_pose = std::array<double, 7>{
      F.translation().x(), F.translation().y(), F.translation().z(), q.w(), q.x(), q.y(), q.z()};
  return r;
}

const Eigen::Isometry3d kFlange =
    calib::poseFromRotationVector({412.5, -88.1, 530.2}, {179.2, -2.1, 4.8});

} // namespace

TEST(FlangePoseProtocol, BinaryTriggerAtIsFortyEightBytesAndRoundTrips) {
  const std::string bytes = encodeBinaryRequest(triggerAt(7, kFlange));
  ASSERT_EQ(bytes.size(), kBinaryTriggerAtSize);
  const Decoded d = decodeBinaryRequest(bytes);
  ASSERT_TRUE(d.request) << d.message;
  EXPECT_EQ(d.request->command, Command::TriggerAt);
  EXPECT_EQ(d.request->id, 7);
  ASSERT_TRUE(d.request->flange_pose);
  // 0.1 µm and 0.0001° steps.
  const Eigen::Isometry3d F = flangePose(*d.request->flange_pose);
  EXPECT_LT((F.translation() - kFlange.translation()).norm(), 1e-4);
  EXPECT_LT(Eigen::AngleAxisd(F.linear().transpose() * kFlange.linear()).angle(), 1e-5);
  // Cut short to the usual 32 bytes, or with a reserved field set, it is malformed.
  EXPECT_EQ(decodeBinaryRequest(bytes.substr(0, kBinaryRequestSize)).error, Status::Malformed);
  std::string reserved = bytes;
  reserved[44] = 1;
  EXPECT_EQ(decodeBinaryRequest(reserved).error, Status::Malformed);
}

TEST(FlangePoseProtocol, TheFramerCutsTriggerAtByItsCommand) {
  Request status;
  status.command = Command::Status;
  const std::string stream = encodeBinaryRequest(triggerAt(1, kFlange)) +
                             encodeBinaryRequest(status) + "{\"cmd\":\"status\"}\n";
  RequestFramer f;
  std::vector<Frame> frames;
  for (char c : stream) {
    f.feed(std::string_view(&c, 1));
    while (auto frame = f.next())
      frames.push_back(*frame);
  }
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].bytes.size(), kBinaryTriggerAtSize);
  EXPECT_EQ(frames[1].bytes.size(), kBinaryRequestSize);
  EXPECT_EQ(frames[2].kind, Frame::Kind::Json);
}

TEST(FlangePoseProtocol, JsonFlangePoses) {
  const Decoded d = decodeJsonRequest(encodeJsonRequest(triggerAt(3, kFlange)));
  ASSERT_TRUE(d.request) << d.message;
  EXPECT_EQ(d.request->command, Command::Trigger);
  const Eigen::Isometry3d F = flangePose(*d.request->flange_pose);
  EXPECT_LT((F.matrix() - kFlange.matrix()).norm(), 1e-9);
  // Seven numbers: position and quaternion, w first.
  const Decoded q = decodeJsonRequest(R"({"cmd":"trigger","flange_pose":[1,2,3,0,1,0,0]})");
  ASSERT_TRUE(q.request) << q.message;
  EXPECT_LT((flangePose(*q.request->flange_pose).linear() * Eigen::Vector3d::UnitZ() +
             Eigen::Vector3d::UnitZ())
                .norm(),
            1e-12);
  for (const char* bad : {R"({"cmd":"trigger","flange_pose":[1,2,3]})",
                          R"({"cmd":"trigger","flange_pose":[1,2,3,"a",0,0]})",
                          R"({"cmd":"trigger","flange_pose":{"x":1}})",
                          R"({"cmd":"trigger","flange_pose":[1,2,3,0.5,0.5,0.5,0]})",
                          R"({"cmd":"next","flange_pose":[1,2,3,0,0,0]})"}) {
    const Decoded e = decodeJsonRequest(bad);
    EXPECT_FALSE(e.request) << bad;
    EXPECT_EQ(e.error, Status::Malformed) << bad;
  }
}
