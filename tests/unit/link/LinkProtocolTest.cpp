#include "core/link/LinkProtocol.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace scanpick::core;
using namespace scanpick::core::link;

namespace {
std::string binaryRequest(std::array<std::int32_t, 8> f) {
  std::string out;
  for (auto v : f)
    for (int b = 0; b < 4; ++b)
      out.push_back(char((std::uint32_t(v) >> (8 * b)) & 0xFF));
  return out;
}

Pick samplePick() {
  Pick p;
  p.rank = 2;
  p.detection = 5;
  p.grasp = 1;
  p.grip = "top";
  p.T_tool.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
  p.T_tool.translation() = Eigen::Vector3d(123.45678, -0.00004, 1000.5);
  p.approach_length_mm = 100.0;
  p.score = 0.8765432;
  p.tilt_deg = 12.5;
  return p;
}
} // namespace

TEST(LinkProtocol, BinaryRequestsRoundTripAndAreLittleEndian) {
  Request r;
  r.command = Command::SetRecipe;
  r.id = 0x01020304;
  r.recipe_index = 2;
  r.binary = true;
  const std::string bytes = encodeBinaryRequest(r);
  ASSERT_EQ(bytes.size(), kBinaryRequestSize);
  EXPECT_EQ(bytes.substr(0, 4), "SPK1");
  EXPECT_EQ(bytes[8], 0x04); // the id's lowest byte first
  const Decoded d = decodeBinaryRequest(bytes);
  ASSERT_TRUE(d.request) << d.message;
  EXPECT_EQ(*d.request, r);
}

TEST(LinkProtocol, BadBinaryRequestsGetTheirStatus) {
  EXPECT_EQ(decodeBinaryRequest("SPK1").error, Status::Malformed);
  EXPECT_EQ(decodeBinaryRequest(binaryRequest({1, 1, 0, 0, 0, 0, 0, 0})).error, Status::BadMagic);
  const Decoded unknown = decodeBinaryRequest(binaryRequest({kMagic, 9, 77, 0, 0, 0, 0, 0}));
  EXPECT_EQ(unknown.error, Status::UnknownCommand);
  EXPECT_EQ(unknown.id, 77); // echoed so that the client can match the answer
  EXPECT_EQ(decodeBinaryRequest(binaryRequest({kMagic, 1, 0, 0, 0, 0, 5, 0})).error,
            Status::Malformed);
  EXPECT_EQ(decodeBinaryRequest(binaryRequest({kMagic, 4, 0, -1, 0, 0, 0, 0})).error,
            Status::Malformed);
  EXPECT_TRUE(decodeBinaryRequest(binaryRequest({kMagic, 2, 0, 0, 0, 0, 0, 0})).request);
}

TEST(LinkProtocol, JsonRequests) {
  const Decoded ok = decodeJsonRequest(R"({"cmd": "set_recipe", "id": 7, "recipe": "cups"})");
  ASSERT_TRUE(ok.request) << ok.message;
  EXPECT_EQ(ok.request->command, Command::SetRecipe);
  EXPECT_EQ(ok.request->id, 7);
  EXPECT_EQ(ok.request->recipe, "cups");
  EXPECT_FALSE(ok.request->binary);
  EXPECT_TRUE(decodeJsonRequest("{\"cmd\":\"next\"}\r\n").request);
  const auto status = [](const char* line) { return decodeJsonRequest(line).error; };
  EXPECT_EQ(status("{\"cmd\": \"trigger\""), Status::Malformed);
  EXPECT_EQ(status("[1, 2]"), Status::Malformed);
  EXPECT_EQ(status(R"({"cmd": "trigger", "speed": 3})"), Status::Malformed);
  EXPECT_EQ(status(R"({"cmd": 1})"), Status::Malformed);
  EXPECT_EQ(status(R"({"cmd": "trigger", "id": 1.5})"), Status::Malformed);
  EXPECT_EQ(status(R"({"cmd": "trigger", "id": 4294967296})"), Status::Malformed);
  EXPECT_EQ(status(R"({"cmd": "dance"})"), Status::UnknownCommand);
  EXPECT_EQ(status(R"({"cmd": "set_recipe"})"), Status::Malformed);
  EXPECT_EQ(status(R"({"cmd": "status", "recipe": "x"})"), Status::Malformed);
  EXPECT_EQ(decodeJsonRequest(R"({"cmd": "dance", "id": 3})").id, 3);
  const Request r{Command::SetRecipe, 9, "a", -1, false, std::nullopt};
  EXPECT_EQ(*decodeJsonRequest(encodeJsonRequest(r)).request, r);
}

TEST(LinkProtocol, BinaryPickAnswersCarryScaledIntegers) {
  Response r;
  r.command = Command::NextPick;
  r.id = 11;
  r.count = 3;
  r.cycle = 4;
  r.picks = {samplePick()};
  const std::string bytes = encodeBinaryResponse(r);
  ASSERT_EQ(bytes.size(), kBinaryResponseSize);
  const auto a = decodeBinaryResponse(bytes);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->command(), 2);
  EXPECT_EQ(a->id(), 11);
  EXPECT_EQ(a->status(), 0);
  EXPECT_EQ(a->count(), 3);
  EXPECT_EQ(a->fields[5], 2); // rank
  EXPECT_EQ(a->fields[6], 5);
  EXPECT_EQ(a->fields[7], 1);
  // 123.45678 mm = 1234567.8 units of 0.1 µm, rounded.
  EXPECT_EQ(a->fields[8], 1234568);
  EXPECT_EQ(a->fields[9], 0); // -0.4 units round to 0
  EXPECT_EQ(a->fields[10], 10005000);
  EXPECT_GE(a->fields[11], 0); // w >= 0
  const Eigen::Quaterniond q(samplePick().T_tool.linear());
  EXPECT_LT(a->rotation().angularDistance(q), 1e-5);
  const Eigen::Vector3d e = eulerZyxDeg(samplePick().T_tool.linear());
  EXPECT_EQ(a->fields[15], std::int32_t(std::lround(e.x() * 10000)));
  EXPECT_EQ(a->fields[18], 1000000); // approach 100 mm
  EXPECT_EQ(a->fields[19], 876543);
  EXPECT_EQ(a->fields[20], 125000);
  EXPECT_EQ(a->fields[21], 4);
}

TEST(LinkProtocol, APickListIsOneMessagePerPickAndOutOfRangeIsFlagged) {
  Response r;
  r.command = Command::PickList;
  r.count = 3;
  r.picks = {samplePick(), samplePick(), samplePick()};
  r.picks[1].rank = 1;
  r.picks[2].T_tool.translation().x() = 300000.0; // 300 m does not fit 0.1 µm units
  const std::string bytes = encodeBinaryResponse(r);
  ASSERT_EQ(bytes.size(), 3 * kBinaryResponseSize);
  for (int i = 0; i < 3; ++i) {
    const auto a = decodeBinaryResponse(
        bytes.substr(std::size_t(i) * kBinaryResponseSize, kBinaryResponseSize));
    ASSERT_TRUE(a);
    EXPECT_EQ(a->count(), 3);
    EXPECT_EQ(a->status(), i == 2 ? int(Status::OutOfRange) : 0);
  }
  r.picks.clear();
  r.count = 0;
  r.status = Status::NoPicks;
  const auto none = decodeBinaryResponse(encodeBinaryResponse(r));
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status(), int(Status::NoPicks));
  EXPECT_EQ(none->fields[5], -1);
  EXPECT_FALSE(decodeBinaryResponse("SPK1"));
}

TEST(LinkProtocol, JsonAnswersAreOneLine) {
  Response r;
  r.command = Command::NextPick;
  r.id = 3;
  r.count = 1;
  r.picks = {samplePick()};
  const std::string line = encodeJsonResponse(r);
  ASSERT_FALSE(line.empty());
  EXPECT_EQ(line.back(), '\n');
  EXPECT_EQ(line.find('\n'), line.size() - 1);
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["code"], 0);
  EXPECT_EQ(j["pick"]["grip"], "top");
  EXPECT_NEAR(j["pick"]["position_mm"][0].get<double>(), 123.45678, 1e-9);
  EXPECT_NEAR(j["pick"]["pregrasp_position_mm"][2].get<double>(),
              (samplePick().T_tool * Eigen::Vector3d(0, 0, -100)).z(), 1e-9);
  Response bad;
  bad.status = Status::Malformed;
  bad.message = std::string("bad \xff name");
  const auto k = nlohmann::json::parse(encodeJsonResponse(bad));
  EXPECT_EQ(k["code"], 12);
}

TEST(LinkProtocol, EulerZyxRebuildsTheRotationAlsoAtGimbalLock) {
  const auto rebuild = [](const Eigen::Vector3d& e) {
    const double k = EIGEN_PI / 180.0;
    return (Eigen::AngleAxisd(e.z() * k, Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(e.y() * k, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(e.x() * k, Eigen::Vector3d::UnitX()))
        .matrix();
  };
  for (const Eigen::Vector3d& e : {Eigen::Vector3d(10, 20, 30), Eigen::Vector3d(-170, 45, 90),
                                   Eigen::Vector3d(0, 90, 30), Eigen::Vector3d(20, -90, -40)}) {
    const Eigen::Matrix3d R = rebuild(e);
    EXPECT_TRUE(rebuild(eulerZyxDeg(R)).isApprox(R, 1e-9)) << e.transpose();
  }
}
