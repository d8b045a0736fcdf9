// The robot link over loopback: a real TCP client against LinkServer on 127.0.0.1 (an ephemeral
// port), with a cell built in code (a floor with box parts, a detector that knows their poses,
// the real grasp planner).
#include "core/link/LinkServer.h"
#include "core/link/PlanningCell.h"
#include "tests/support/LoopbackClient.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <thread>

using namespace scanpick::core;
using namespace scanpick::core::link;
using nlohmann::json;

namespace {

const Eigen::Vector3d kHalf(30, 20, 15);

std::vector<Eigen::Vector3f> boxSurface(double step = 3.0) {
  std::vector<Eigen::Vector3f> out;
  for (double x = -kHalf.x(); x <= kHalf.x(); x += step)
    for (double y = -kHalf.y(); y <= kHalf.y(); y += step)
      for (double z : {-kHalf.z(), kHalf.z()})
        out.emplace_back(float(x), float(y), float(z));
  return out;
}

/// Three parts on a floor at z = 1000 (camera frame, up = -z), the middle one 20 mm higher.
struct Bench {
  std::vector<Eigen::Isometry3d> poses;
  PointCloud scene;
  Bench() {
    for (int i = 0; i < 3; ++i) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = Eigen::Vector3d(-150.0 + 150.0 * i, 0, 1000 - 15 - (i == 1 ? 20 : 0));
      poses.push_back(T);
    }
    std::vector<Eigen::Vector3f> pts;
    for (double x = -250; x <= 250; x += 4)
      for (double y = -250; y <= 250; y += 4)
        pts.emplace_back(float(x), float(y), 1000.0f);
    for (const auto& T : poses)
      for (const auto& p : boxSurface())
        pts.push_back((T * p.cast<double>()).cast<float>());
    scene = PointCloud::fromPoints(pts);
  }
};

struct Server {
  std::shared_ptr<std::atomic<int>> delay_ms = std::make_shared<std::atomic<int>>(0);
  std::unique_ptr<LinkServer> server;
  explicit Server(ServerOptions options = {}) {
    auto bench = std::make_shared<Bench>();
    grasp::GraspModel model;
    model.cloud_mm = PointCloud::fromPoints(boxSurface());
    model.grasps = {{"top", {0, 0, -15}, Eigen::Vector3d::UnitZ(), std::nullopt}};
    CellRecipe a;
    a.name = "boxes";
    auto delay = delay_ms;
    a.detect = [bench, delay](const PointCloud&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay->load()));
      std::vector<Detection> dets;
      for (const auto& T : bench->poses) {
        Detection d;
        d.T_scene_model = T;
        d.score = 0.9;
        dets.push_back(d);
      }
      return dets;
    };
    a.models = {model};
    CellRecipe b = a;
    b.name = "boxes-robot";
    b.T_robot_scene.translation() = Eigen::Vector3d(1000, 0, 0);
    auto cell = std::make_shared<PlanningCell>([bench] { return bench->scene; },
                                               std::vector<CellRecipe>{a, b});
    options.host = "127.0.0.1";
    options.port = 0;
    server = std::make_unique<LinkServer>(std::make_shared<CellService>(cell), options);
    server->start();
  }
  ~Server() { server->stop(); }
};

/// A loopback client that asks the link in JSON lines and binary messages.
class Client : public scanpick::test::LoopbackClient {
public:
  using LoopbackClient::LoopbackClient;
  json ask(const std::string& request) {
    send(request + "\n");
    const std::string l = line();
    return l.empty() ? json() : json::parse(l, nullptr, false);
  }
  std::optional<BinaryAnswer> askBinary(Command c, std::int32_t id, std::int32_t arg = 0) {
    Request r;
    r.command = c;
    r.id = id;
    r.recipe_index = arg;
    send(encodeBinaryRequest(r));
    return decodeBinaryResponse(read(kBinaryResponseSize));
  }
};

} // namespace

TEST(RobotLink, JsonSessionTriggersAndHandsOutPicksHighestFirst) {
  Server s;
  Client c(s.server->port());
  ASSERT_TRUE(c.connected());
  EXPECT_EQ(c.ask(R"({"cmd":"next","id":1})")["status"], "not-triggered");
  const json t = c.ask(R"({"cmd":"trigger","id":2})");
  ASSERT_EQ(t["status"], "ok") << t.dump();
  EXPECT_EQ(t["id"], 2);
  EXPECT_EQ(t["detections"], 3);
  EXPECT_EQ(t["picks"], 3);
  // The middle part is 20 mm higher: it comes first; its top centre is at (0, 0, 950).
  const json first = c.ask(R"({"cmd":"next","id":3})");
  ASSERT_EQ(first["status"], "ok") << first.dump();
  EXPECT_EQ(first["pick"]["detection"], 1);
  EXPECT_NEAR(first["pick"]["position_mm"][2].get<double>(), 950.0, 1e-6);
  EXPECT_EQ(first["remaining"], 2);
  const json list = c.ask(R"({"cmd":"picks"})");
  EXPECT_EQ(list["picks"].size(), 3u);
  const json st = c.ask(R"({"cmd":"status"})");
  EXPECT_EQ(st["remaining"], 2);
  EXPECT_EQ(st["recipe"], "boxes");
  EXPECT_EQ(st["busy"], false);
  EXPECT_EQ(c.ask(R"({"cmd":"set_recipe","recipe":"nope"})")["status"], "recipe-failed");
  EXPECT_EQ(c.ask(R"({"cmd":"set_recipe","recipe":"boxes-robot"})")["status"], "ok");
  ASSERT_EQ(c.ask(R"({"cmd":"trigger"})")["status"], "ok");
  // That recipe reports in the robot frame: the camera 1000 mm along the robot's x.
  EXPECT_NEAR(c.ask(R"({"cmd":"next"})")["pick"]["position_mm"][0].get<double>(), 1000.0, 1e-6);
}

TEST(RobotLink, BinarySessionCarriesScaledIntegers) {
  Server s;
  Client c(s.server->port());
  auto a = c.askBinary(Command::Trigger, 10);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->status(), 0);
  EXPECT_EQ(a->id(), 10);
  EXPECT_EQ(a->count(), 3);
  a = c.askBinary(Command::NextPick, 11);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->fields[8], 0);
  EXPECT_EQ(a->fields[10], 950 * 10000);
  EXPECT_EQ(a->fields[11], 1000000); // identity rotation: w = 1
  // The whole list: three messages, each with the count.
  Request r;
  r.command = Command::PickList;
  c.send(encodeBinaryRequest(r));
  for (int i = 0; i < 3; ++i) {
    const auto m = decodeBinaryResponse(c.read(kBinaryResponseSize));
    ASSERT_TRUE(m) << i;
    EXPECT_EQ(m->count(), 3);
    EXPECT_EQ(m->fields[5], i);
  }
  a = c.askBinary(Command::SetRecipe, 12, 7);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->status(), int(Status::RecipeFailed));
  a = c.askBinary(Command::Status, 13);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->status(), 0);
  EXPECT_EQ(a->fields[5], 0); // recipe index
}

TEST(RobotLink, EveryMalformedOrPartialMessageIsAnsweredWithAnErrorStatus) {
  ServerOptions o;
  o.request_timeout_ms = 300;
  Server s(o);
  const int port = s.server->port();
  {
    Client c(port); // bad JSON keeps the connection: the line framing is intact
    EXPECT_EQ(c.ask("{\"cmd\": trig")["code"], int(Status::Malformed));
    EXPECT_EQ(c.ask(R"({"cmd":"dance","id":4})")["code"], int(Status::UnknownCommand));
    EXPECT_EQ(c.ask(R"({"cmd":"status","x":1})")["code"], int(Status::Malformed));
    EXPECT_EQ(c.ask(R"({"cmd":"status"})")["code"], 0);
  }
  {
    Client c(port); // a bad binary command keeps it too
    const auto a = c.askBinary(Command(42), 9);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->status(), int(Status::UnknownCommand));
    EXPECT_EQ(a->id(), 9);
    EXPECT_EQ(c.askBinary(Command::Status, 1)->status(), 0);
  }
  {
    Client c(port); // garbage text: answered in JSON, then closed
    const json j = c.ask("GET / HTTP/1.0");
    EXPECT_EQ(j["code"], int(Status::BadMagic));
    EXPECT_TRUE(c.closedByServer());
  }
  {
    Client c(port); // garbage bytes: answered in binary, then closed
    c.send(std::string("\x01\x02\x03\x04", 4));
    const auto a = decodeBinaryResponse(c.read(kBinaryResponseSize));
    ASSERT_TRUE(a);
    EXPECT_EQ(a->status(), int(Status::BadMagic));
    EXPECT_TRUE(c.closedByServer());
  }
  {
    Client c(port); // half a binary message: Incomplete after the request timeout
    c.send(encodeBinaryRequest({Command::Trigger, 1, "", 0, true, std::nullopt}).substr(0, 13));
    const auto a = decodeBinaryResponse(c.read(kBinaryResponseSize));
    ASSERT_TRUE(a);
    EXPECT_EQ(a->status(), int(Status::Incomplete));
    EXPECT_TRUE(c.closedByServer());
  }
  {
    Client c(port); // a JSON line that never ends
    c.send("{\"cmd\":\"status\"");
    EXPECT_EQ(json::parse(c.line())["code"], int(Status::Incomplete));
  }
  {
    Client c(port); // an endless line
    c.send("{" + std::string(10000, ' '));
    EXPECT_EQ(json::parse(c.line())["code"], int(Status::TooLong));
    EXPECT_TRUE(c.closedByServer());
  }
  Client after(port);
  EXPECT_EQ(after.ask(R"({"cmd":"status"})")["code"], 0);
  EXPECT_GE(s.server->stats().errors, 7u);
}

TEST(RobotLink, OneRequestAtATimeOthersAreToldBusyAndLeaversDoNotHurt) {
  Server s;
  *s.delay_ms = 400;
  const int port = s.server->port();
  {
    Client leaver(port); // disconnects while its trigger runs
    leaver.send("{\"cmd\":\"trigger\"}\n");
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    leaver.closeNow();
    Client other(port);
    EXPECT_EQ(other.ask(R"({"cmd":"trigger"})")["status"], "busy");
    const json st = other.ask(R"({"cmd":"status"})");
    EXPECT_EQ(st["status"], "ok");
    EXPECT_EQ(st["busy"], true);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  Client c(port);
  *s.delay_ms = 0;
  EXPECT_EQ(c.ask(R"({"cmd":"trigger"})")["status"], "ok");
  EXPECT_EQ(c.ask(R"({"cmd":"status"})")["cycle"], 2);
}

TEST(RobotLink, HundredConcurrentClientsAreServedOrRefused) {
  ServerOptions o;
  o.max_clients = 32;
  Server s(o);
  *s.delay_ms = 20;
  const int port = s.server->port();
  std::atomic<int> ok{0}, busy{0}, refused{0}, other{0};
  std::vector<std::thread> threads;
  std::atomic<int> connected{0};
  for (int i = 0; i < 100; ++i)
    threads.emplace_back([&, i] {
      Client c(port, 10000);
      if (!c.connected()) {
        ++other;
        return;
      }
      ++connected;
      // Everyone connects first, then all ask at once.
      while (connected.load() < 100)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      const bool trigger = i % 2;
      const json a = c.ask(trigger ? R"({"cmd":"trigger"})" : R"({"cmd":"status"})");
      if (a.is_discarded() || a.is_null())
        ++other;
      else if (a["code"] == 0 || a["code"] == int(Status::NoPicks))
        ++ok;
      else if (a["code"] == int(Status::Busy) && trigger) // status is answered even when busy
        ++busy;
      else if (a["code"] == int(Status::TooManyClients))
        ++refused;
      else
        ++other;
    });
  for (auto& t : threads)
    t.join();
  std::printf("100 clients: %d served, %d busy, %d refused (too many clients), %d other\n",
              ok.load(), busy.load(), refused.load(), other.load());
  EXPECT_EQ(other.load(), 0);
  EXPECT_EQ(ok + busy + refused, 100);
  EXPECT_GE(ok.load(), 1); // which 32 clients are admitted depends on the scheduling
  EXPECT_GE(refused.load(), 100 - 32);
  Client after(port);
  EXPECT_EQ(after.ask(R"({"cmd":"status"})")["code"], 0);
}

TEST(RobotLink, SlowReadersAndIdleClientsAreDroppedWhileOthersAreServed) {
  ServerOptions o;
  o.idle_timeout_ms = 300;
  o.write_timeout_ms = 300;
  o.max_output_bytes = 64 * 1024;
  Server s(o);
  const int port = s.server->port();
  Client idle(port);
  ASSERT_EQ(idle.ask(R"({"cmd":"status"})")["code"], 0);
  // A client that asks and asks but never reads: its answers pile up until it is dropped.
  Client flood(port);
  std::string burst;
  for (int i = 0; i < 2000; ++i)
    burst += "{\"cmd\":\"status\"}\n";
  for (int k = 0; k < 40; ++k)
    if (!flood.send(burst))
      break;
  Client c(port);
  EXPECT_EQ(c.ask(R"({"cmd":"status"})")["code"], 0);
  const auto start = std::chrono::steady_clock::now();
  while (s.server->stats().timeouts < 2 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(5))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_GE(s.server->stats().timeouts, 2u); // the idle one and the flooder
  EXPECT_TRUE(idle.closedByServer());
  Client later(port);
  EXPECT_EQ(later.ask(R"({"cmd":"status"})")["code"], 0);
}
