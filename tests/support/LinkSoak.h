#pragma once
// A soak of the robot link (a day of requests simulated as 100,000, memory read before and after):
// a LinkServer on 127.0.0.1 with a cheap cell (canned picks: the soak measures the
// server, not recognition), loopback clients sending a fixed-seed mix of valid and malformed
// JSON lines and binary messages (and leaving mid-message, and bursts of 100 clients at once),
// every answer checked, and the process's resident memory (the server runs in this process) read
// from /proc/self/status after a warm-up and at the end. Used by soak_link
// (tests/benchmarks/LinkSoakTool.cpp: the long run, by hand) and by RobotLinkSoakTest (a short run
// in CI).
#include "core/link/LinkServer.h"
#include "tests/support/LoopbackClient.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace scanpick::test {

/// Resident memory of this process, kB (VmRSS of /proc/self/status); 0 when unreadable.
inline long residentKb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kb = 0;
      status >> kb;
      return kb;
    }
    status.ignore(1 << 16, '\n');
  }
  return 0;
}

/// A cell that answers every trigger with three canned picks in the camera and the base frame.
class SoakCell : public core::link::CellBackend {
public:
  core::link::CycleResult runCycle(const core::link::CycleInput& input) override {
    core::link::CycleResult r;
    r.detections = 4;
    for (int i = 0; i < 3; ++i) {
      core::link::Pick p;
      p.rank = i;
      p.detection = i;
      p.grasp = 0;
      p.grip = "top";
      p.T_tool.translation() = Eigen::Vector3d(-100.0 + 100.0 * i, 20.0, 900.0);
      p.T_part = p.T_tool;
      Eigen::Isometry3d T_base_camera = Eigen::Isometry3d::Identity();
      T_base_camera.translation() = Eigen::Vector3d(500, 0, 1300);
      if (input.T_base_flange)
        T_base_camera = *input.T_base_flange * T_base_camera;
      p.T_base_tool = T_base_camera * p.T_tool;
      p.T_base_part = T_base_camera * p.T_part;
      p.approach_length_mm = 80;
      p.score = 0.9 - 0.1 * i;
      r.picks.push_back(p);
    }
    return r;
  }
  [[nodiscard]] std::vector<std::string> recipes() const override { return {"a", "b"}; }
  void setRecipe(std::size_t index) override { m_recipe = index; }
  [[nodiscard]] std::size_t recipe() const override { return m_recipe; }
  [[nodiscard]] std::string calibration() const override { return "soak-calibration.json"; }

private:
  std::size_t m_recipe = 0;
};

struct SoakOptions {
  long requests = 100000; ///< measured requests (after the warm-up)
  long warmup = 2000;     ///< requests before the first memory reading
  int clients = 4;        ///< client threads sending at once
  int bursts = 4;         ///< bursts of 100 clients at once during the measured run (+1 in warm-up)
  int burst_clients = 100;
  int max_clients = 32; ///< the server's client limit (bursts go beyond it)
  std::uint64_t seed = 43;
  std::function<void(const std::string&)> log; ///< progress lines (optional)
};

struct SoakReport {
  long requests = 0;    ///< requests sent in the measured run (warm-up excluded)
  long answers = 0;     ///< answers read (a binary pick list: one per message set)
  long well_formed = 0; ///< answers that decode and echo the request
  long unexpected = 0;  ///< answers with a status the request cannot have (or none)
  long burst_clients = 0, burst_refused = 0;
  long rss_warm_kb = 0, rss_end_kb = 0, rss_max_kb = 0;
  double seconds = 0;
  core::link::ServerStats stats;
  std::vector<std::string> problems; ///< the first few unexpected answers
  [[nodiscard]] double growthPercent() const {
    return rss_warm_kb > 0 ? 100.0 * double(rss_end_kb - rss_warm_kb) / double(rss_warm_kb) : 0;
  }
};

namespace soak {

using core::link::Command;
using core::link::Status;

using Conn = LoopbackClient;

/// One request of the mix: its bytes, how its answer comes and which statuses it may get.
struct Message {
  std::string bytes;
  bool binary_answer = false;
  bool pick_list = false; ///< binary pick list: `count` messages
  bool closes = false;    ///< the server answers and closes the connection
  bool no_answer = false; ///< the client leaves mid-message
  std::set<int> statuses; ///< allowed status codes
  std::int32_t id = 0;    ///< echoed (when the request can be read)
  bool echoes_id = true;
};

/// A binary request; `reserved` goes into field 4 (which must be 0).
inline std::string binaryRequest(Command c, std::int32_t id, std::int32_t reserved = 0) {
  core::link::Request r;
  r.command = c;
  r.id = id;
  std::string bytes = core::link::encodeBinaryRequest(r);
  bytes[16] = char(reserved);
  return bytes;
}

inline Message makeMessage(std::mt19937_64& rng, std::int32_t id) {
  const int ok = int(Status::Ok), none = int(Status::NoPicks), busy = int(Status::Busy),
            not_triggered = int(Status::NotTriggered), full = int(Status::TooManyClients);
  // Requests that need the cell may meet another client's request (busy) or a fresh connection
  // over the client limit (too many clients); next/picks may come before any trigger.
  const std::set<int> cell{ok, none, busy, not_triggered, full};
  Message m;
  m.id = id;
  const std::string sid = std::to_string(id);
  switch (std::uniform_int_distribution<int>(0, 19)(rng)) {
  case 0:
  case 1:
    m.bytes = R"({"cmd":"trigger","id":)" + sid + "}\n";
    m.statuses = cell;
    break;
  case 2:
    m.bytes = R"({"cmd":"trigger","id":)" + sid + R"(,"flange_pose":[400,-20,550,180,0,0]})" + "\n";
    m.statuses = cell;
    break;
  case 3:
  case 4:
    m.bytes = R"({"cmd":"next","id":)" + sid + "}\n";
    m.statuses = cell;
    break;
  case 5:
    m.bytes = R"({"cmd":"picks","id":)" + sid + "}\n";
    m.statuses = cell;
    break;
  case 6:
  case 7:
    m.bytes = R"({"cmd":"status","id":)" + sid + "}\n";
    m.statuses = {ok, full};
    break;
  case 8:
    m.bytes = R"({"cmd":"set_recipe","recipe":"b","id":)" + sid + "}\n";
    m.statuses = {ok, busy, full};
    break;
  case 9:
    m.bytes = binaryRequest(Command::Trigger, id);
    m.binary_answer = true;
    m.statuses = cell;
    break;
  case 10:
    m.bytes = binaryRequest(Command::NextPick, id);
    m.binary_answer = true;
    m.statuses = cell;
    break;
  case 11:
    m.bytes = binaryRequest(Command::PickList, id);
    m.binary_answer = m.pick_list = true;
    m.statuses = cell;
    break;
  case 12: {
    core::link::Request r;
    r.command = Command::Trigger;
    r.id = id;
    r.flange_pose = std::array<double, 7>{400, -20, 550, 0, 1, 0, 0};
    m.bytes = core::link::encodeBinaryRequest(r); // TriggerAt
    m.binary_answer = true;
    m.statuses = cell;
    break;
  }
  case 13:
    m.bytes = binaryRequest(Command::Status, id);
    m.binary_answer = true;
    m.statuses = {ok, full};
    break;
  // Malformed, the stream still followed: answered, the connection kept.
  case 14:
    m.bytes = "{\"cmd\": trig\n";
    m.statuses = {int(Status::Malformed), full};
    m.echoes_id = false;
    break;
  case 15:
    m.bytes = R"({"cmd":"dance","id":)" + sid + "}\n";
    m.statuses = {int(Status::UnknownCommand), full};
    break;
  case 16:
    switch (std::uniform_int_distribution<int>(0, 3)(rng)) {
    case 0:
      m.bytes = R"({"cmd":"status","x":1,"id":)" + sid + "}\n";
      m.statuses = {int(Status::Malformed), full};
      break;
    case 1:
      m.bytes = R"({"cmd":"trigger","flange_pose":[1,2],"id":)" + sid + "}\n";
      m.statuses = {int(Status::Malformed), full};
      break;
    case 2:
      m.bytes = R"({"cmd":"set_recipe","recipe":"nope","id":)" + sid + "}\n";
      m.statuses = {int(Status::RecipeFailed), busy, full};
      break;
    default:
      m.bytes = R"({"cmd":"status","id":99999999999})"
                "\n";
      m.statuses = {int(Status::Malformed), full};
      m.echoes_id = false;
    }
    break;
  case 17:
    m.binary_answer = true;
    if (std::uniform_int_distribution<int>(0, 1)(rng)) {
      m.bytes = binaryRequest(Command(42), id);
      m.statuses = {int(Status::UnknownCommand), full};
    } else {
      m.bytes = binaryRequest(Command::Status, id, 7);
      m.statuses = {int(Status::Malformed), full};
    }
    break;
  // Malformed, the stream lost: answered and closed, or left by the client.
  case 18:
    m.closes = true;
    m.echoes_id = false;
    switch (std::uniform_int_distribution<int>(0, 2)(rng)) {
    case 0:
      m.bytes = "GET / HTTP/1.0\r\n\r\n";
      m.statuses = {int(Status::BadMagic), full};
      break;
    case 1:
      m.bytes = std::string("\x01\x02\x03\x04", 4);
      m.binary_answer = true;
      m.statuses = {int(Status::BadMagic), full};
      break;
    default:
      m.bytes = "{" + std::string(5000, ' ');
      m.statuses = {int(Status::TooLong), full};
    }
    break;
  default:
    m.no_answer = true; // half a message, then gone
    m.bytes = std::uniform_int_distribution<int>(0, 1)(rng)
                  ? binaryRequest(Command::Trigger, id).substr(0, 13)
                  : std::string(R"({"cmd":"trig)");
  }
  return m;
}

/// Checks one answer against its request; returns "" when it is well-formed and expected, else
/// what is wrong. `count` receives a binary pick list's count.
inline std::string check(const Message& m, const std::string& answer, int& status, int& count) {
  count = 1;
  if (answer.empty())
    return "no answer";
  std::int32_t id = 0;
  if (m.binary_answer || answer.front() == 'S') {
    const auto a = core::link::decodeBinaryResponse(answer);
    if (!a)
      return "not a binary answer";
    status = a->status();
    id = a->id();
    count = a->count();
  } else {
    const auto j = nlohmann::json::parse(answer, nullptr, false);
    if (!j.is_object() || !j.contains("code") || !j["code"].is_number_integer() ||
        !j.contains("status") || !j["status"].is_string() || !j.contains("id"))
      return "not a JSON answer: " + answer.substr(0, 80);
    status = j["code"].get<int>();
    id = j["id"].get<std::int32_t>();
    if (j["status"] != core::link::toString(Status(status)))
      return "status name and code disagree: " + answer.substr(0, 80);
  }
  if (!m.statuses.contains(status))
    return "status " + std::to_string(status) + " for " + m.bytes.substr(0, 40);
  if (m.echoes_id && status != int(Status::TooManyClients) && id != m.id)
    return "id " + std::to_string(id) + " for " + std::to_string(m.id);
  return "";
}

/// Counters the client threads share.
struct Tally {
  std::atomic<long> sent{0}, answers{0}, well_formed{0}, unexpected{0};
  std::mutex mutex;
  std::vector<std::string> problems;
  void problem(const std::string& p) {
    ++unexpected;
    const std::lock_guard lock(mutex);
    if (problems.size() < 10)
      problems.push_back(p);
  }
};

/// One client thread: `n` requests of the mix on as many connections as the errors need.
inline void clientRun(int port, long n, std::uint64_t seed, Tally& tally) {
  std::mt19937_64 rng(seed);
  auto conn = std::make_unique<Conn>(port);
  for (long i = 0; i < n; ++i) {
    const Message m = makeMessage(rng, std::int32_t(i % 1000000));
    if (!conn->connected())
      conn = std::make_unique<Conn>(port);
    conn->send(m.bytes);
    ++tally.sent;
    if (m.no_answer) {
      conn = std::make_unique<Conn>(port);
      continue;
    }
    int status = -1, count = 1;
    const std::string first = conn->answer();
    ++tally.answers;
    std::string wrong = check(m, first, status, count);
    // A binary pick list comes as one message per pick.
    for (int k = 1; wrong.empty() && m.pick_list && status == 0 && k < count; ++k) {
      int s2 = -1, c2 = 0;
      wrong = check(m, conn->answer(), s2, c2);
    }
    if (wrong.empty())
      ++tally.well_formed;
    else
      tally.problem(wrong);
    if (m.closes || status == int(Status::TooManyClients) || !wrong.empty())
      conn = std::make_unique<Conn>(port); // the server closed it (or it is out of step)
  }
}

/// `clients` clients connect at once, then each asks once (status or trigger).
inline void burst(int port, int clients, Tally& tally, long& refused) {
  std::atomic<int> connected{0}, refused_count{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < clients; ++i)
    threads.emplace_back([&, i] {
      Conn c(port);
      ++connected;
      while (connected.load() < clients)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      Message m;
      m.id = 7000 + i;
      m.bytes = (i % 2 ? R"({"cmd":"trigger","id":)" : R"({"cmd":"status","id":)") +
                std::to_string(m.id) + "}\n";
      m.statuses = {int(Status::Ok), int(Status::NoPicks), int(Status::TooManyClients)};
      if (i % 2)
        m.statuses.insert(int(Status::Busy));
      c.send(m.bytes);
      ++tally.sent;
      ++tally.answers;
      int status = -1, count = 0;
      const std::string wrong = check(m, c.answer(), status, count);
      if (wrong.empty())
        ++tally.well_formed;
      else
        tally.problem("burst: " + wrong);
      if (status == int(Status::TooManyClients))
        ++refused_count;
    });
  for (auto& t : threads)
    t.join();
  refused += refused_count.load();
}

/// `n` requests spread over the client threads, with `bursts` bursts in between.
inline void phase(int port, long n, const SoakOptions& o, std::uint64_t seed, int bursts,
                  Tally& tally, SoakReport& report) {
  const long per_burst_slice = n / (bursts + 1);
  for (int b = 0; b <= bursts; ++b) {
    const long slice = b == bursts ? n - per_burst_slice * bursts : per_burst_slice;
    std::vector<std::thread> threads;
    for (int c = 0; c < o.clients; ++c) {
      const long share = slice / o.clients + (c < slice % o.clients ? 1 : 0);
      threads.emplace_back(clientRun, port, share, seed + std::uint64_t(b * 1000 + c),
                           std::ref(tally));
    }
    for (auto& t : threads)
      t.join();
    report.rss_max_kb = std::max(report.rss_max_kb, residentKb());
    if (o.log)
      o.log(std::to_string(tally.sent.load()) + " requests sent, RSS " +
            std::to_string(residentKb()) + " kB");
    if (b < bursts) {
      burst(port, o.burst_clients, tally, report.burst_refused);
      report.burst_clients += o.burst_clients;
    }
  }
}

} // namespace soak

/// Runs the soak: warm-up, first memory reading, the measured requests, last reading.
inline SoakReport runLinkSoak(const SoakOptions& o) {
  core::link::ServerOptions server_options;
  server_options.host = "127.0.0.1";
  server_options.port = 0;
  server_options.max_clients = o.max_clients;
  core::link::LinkServer server(
      std::make_shared<core::link::CellService>(std::make_shared<SoakCell>()), server_options);
  server.start();
  const int port = server.port();
  SoakReport report;
  {
    soak::Tally warm;
    SoakReport ignored;
    soak::phase(port, o.warmup, o, o.seed, 1, warm, ignored);
  }
  report.rss_warm_kb = residentKb();
  soak::Tally tally;
  const auto start = std::chrono::steady_clock::now();
  soak::phase(port, o.requests, o, o.seed + 1000000, o.bursts, tally, report);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.rss_end_kb = residentKb();
  report.requests = tally.sent.load();
  report.answers = tally.answers.load();
  report.well_formed = tally.well_formed.load();
  report.unexpected = tally.unexpected.load();
  report.problems = tally.problems;
  report.stats = server.stats();
  server.stop();
  server.join();
  return report;
}

} // namespace scanpick::test
