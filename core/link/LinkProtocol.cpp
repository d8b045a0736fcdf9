#include "core/link/LinkProtocol.h"

#include "core/calib/BaseFrame.h"
#include "core/common/Error.h"
#include "core/grasp/GraspJson.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace scanpick::core::link {
namespace {
using nlohmann::json;

void putInt(std::string& out, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int shift = 0; shift < 32; shift += 8)
    out.push_back(static_cast<char>((u >> shift) & 0xFFu));
}

std::int32_t getInt(std::string_view bytes, std::size_t field) {
  std::uint32_t u = 0;
  for (std::size_t b = 0; b < 4; ++b)
    u |= std::uint32_t(static_cast<unsigned char>(bytes[field * 4 + b])) << (8 * b);
  return static_cast<std::int32_t>(u);
}

/// value x scale rounded, or nothing when it does not fit an int32 (or is not finite).
std::optional<std::int32_t> scaled(double value, double scale) {
  const double v = std::round(value * scale);
  if (!std::isfinite(v) || v > double(std::numeric_limits<std::int32_t>::max()) ||
      v < double(std::numeric_limits<std::int32_t>::min()))
    return std::nullopt;
  return static_cast<std::int32_t>(v);
}

constexpr double kPi = 3.14159265358979323846;

bool knownCommand(std::int32_t c) {
  return c >= 1 && c <= 6;
}

/// x, y, z, qw, qx, qy, qz of a pose.
std::array<double, 7> poseArray(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  return {t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()};
}

/// The rotation vector (axis × angle) of a unit quaternion, degrees.
Eigen::Vector3d rotationVectorDeg(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd aa(q.normalized());
  return aa.axis() * aa.angle() * 180.0 / kPi;
}

json poseJson(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  return {{"position_mm", {t.x(), t.y(), t.z()}},
          {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

json toolJson(const Eigen::Isometry3d& T, double approach_length_mm) {
  json j = poseJson(T);
  const Eigen::Vector3d e = eulerZyxDeg(T.linear());
  const Eigen::Vector3d pre = T * Eigen::Vector3d(0.0, 0.0, -approach_length_mm);
  j["euler_zyx_deg"] = {e.x(), e.y(), e.z()};
  j["pregrasp_position_mm"] = {pre.x(), pre.y(), pre.z()};
  return j;
}

Command commandFromName(const std::string& name) {
  for (Command c : {Command::Trigger, Command::NextPick, Command::PickList, Command::SetRecipe,
                    Command::Status})
    if (name == toString(c))
      return c;
  return Command::None;
}

json pickJson(const Pick& p) {
  const Eigen::Quaterniond q(p.T_tool.linear());
  const Eigen::Vector3d t = p.T_tool.translation();
  const Eigen::Vector3d e = eulerZyxDeg(p.T_tool.linear());
  const Eigen::Vector3d pre = p.T_tool * Eigen::Vector3d(0.0, 0.0, -p.approach_length_mm);
  json j = {{"rank", p.rank},
            {"detection", p.detection},
            {"grasp", p.grasp},
            {"grip", p.grip},
            {"position_mm", {t.x(), t.y(), t.z()}},
            {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}},
            {"euler_zyx_deg", {e.x(), e.y(), e.z()}},
            {"pregrasp_position_mm", {pre.x(), pre.y(), pre.z()}},
            {"approach_length_mm", p.approach_length_mm},
            {"score", p.score},
            {"tilt_deg", p.tilt_deg},
            {"occlusion", p.occlusion},
            {"part", poseJson(p.T_part)}};
  if (p.T_base_tool) {
    json base = toolJson(*p.T_base_tool, p.approach_length_mm);
    if (p.T_base_part)
      base["part"] = poseJson(*p.T_base_part);
    j["pose_base"] = base;
  }
  return j;
}

/// The 24 fields of one binary answer for `r`, with `pick` (or none) in it.
std::string binaryMessage(const Response& r, const Pick* pick) {
  std::array<std::int32_t, 24> f{};
  f[0] = kMagic;
  f[1] = static_cast<std::int32_t>(r.command);
  f[2] = r.id;
  f[3] = static_cast<std::int32_t>(r.status);
  f[4] = r.count;
  f[5] = -1;
  f[6] = r.detections;
  f[7] = -1;
  if (r.command == Command::SetRecipe || r.command == Command::Status)
    f[5] = r.recipe_index;
  bool fits = true;
  const auto put = [&fits](std::int32_t& field, double value, double scale) {
    const auto v = scaled(value, scale);
    fits = fits && v.has_value();
    field = v.value_or(0);
  };
  if (pick != nullptr) {
    f[5] = pick->rank;
    f[6] = pick->detection;
    f[7] = pick->grasp;
    // A robot controller wants the base frame: with a calibration the binary pose is that one.
    const Eigen::Isometry3d& T = pick->T_base_tool ? *pick->T_base_tool : pick->T_tool;
    const Eigen::Vector3d t = T.translation();
    Eigen::Quaterniond q(T.linear());
    q.normalize();
    if (q.w() < 0.0) // one sign for one rotation: w >= 0
      q.coeffs() = -q.coeffs();
    const Eigen::Vector3d e = eulerZyxDeg(T.linear());
    for (int a = 0; a < 3; ++a) {
      put(f[std::size_t(8 + a)], t[a], kPositionScale);
      put(f[std::size_t(15 + a)], e[a], kAngleScale);
    }
    put(f[11], q.w(), kUnitScale);
    put(f[12], q.x(), kUnitScale);
    put(f[13], q.y(), kUnitScale);
    put(f[14], q.z(), kUnitScale);
    put(f[18], pick->approach_length_mm, kPositionScale);
    put(f[19], pick->score, kUnitScale);
    put(f[20], pick->tilt_deg, kAngleScale);
  }
  f[21] = static_cast<std::int32_t>(r.cycle & 0x7FFFFFFFu);
  put(f[22], r.elapsed_ms, 1.0);
  f[23] = (r.busy ? 1 : 0) | (r.base_frame ? 2 : 0) | (r.needs_flange_pose ? 4 : 0);
  if (!fits && f[3] == 0)
    f[3] = static_cast<std::int32_t>(Status::OutOfRange);
  std::string out;
  out.reserve(kBinaryResponseSize);
  for (auto v : f)
    putInt(out, v);
  return out;
}

/// The flange pose of a binary TriggerAt request: position from fields 4-6 (0.1 µm, returned in
/// mm), rotation from fields 7-9 (0.0001°) read as a rotation vector (convention 0) or as Euler
/// angles Rz·Ry·Rx (convention 1).
Eigen::Isometry3d triggerAtFlangePose(std::string_view bytes, std::int32_t convention) {
  const Eigen::Vector3d position(getInt(bytes, 4) / kPositionScale,
                                 getInt(bytes, 5) / kPositionScale,
                                 getInt(bytes, 6) / kPositionScale);
  const Eigen::Vector3d r(getInt(bytes, 7) / kAngleScale, getInt(bytes, 8) / kAngleScale,
                          getInt(bytes, 9) / kAngleScale);
  Eigen::Isometry3d T =
      calib::poseFromRotationVector(position, convention == 0 ? r : Eigen::Vector3d::Zero());
  if (convention == 1)
    T.linear() = (Eigen::AngleAxisd(r.z() * kPi / 180, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(r.y() * kPi / 180, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(r.x() * kPi / 180, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
  return T;
}

} // namespace

const char* toString(Command command) {
  switch (command) {
  case Command::None:
    return "none";
  case Command::Trigger:
    return "trigger";
  case Command::NextPick:
    return "next";
  case Command::PickList:
    return "picks";
  case Command::SetRecipe:
    return "set_recipe";
  case Command::Status:
    return "status";
  case Command::TriggerAt:
    return "trigger";
  }
  return "none";
}

std::size_t binaryRequestSize(std::int32_t command) {
  return command == static_cast<std::int32_t>(Command::TriggerAt) ? kBinaryTriggerAtSize
                                                                  : kBinaryRequestSize;
}

Eigen::Isometry3d flangePose(const std::array<double, 7>& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond(pose[3], pose[4], pose[5], pose[6]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose[0], pose[1], pose[2]);
  return T;
}

const char* toString(Status status) {
  switch (status) {
  case Status::Ok:
    return "ok";
  case Status::NoPicks:
    return "no-picks";
  case Status::Busy:
    return "busy";
  case Status::NotTriggered:
    return "not-triggered";
  case Status::BadMagic:
    return "bad-magic";
  case Status::UnknownCommand:
    return "unknown-command";
  case Status::Malformed:
    return "malformed";
  case Status::Incomplete:
    return "incomplete";
  case Status::TooLong:
    return "too-long";
  case Status::TooManyClients:
    return "too-many-clients";
  case Status::OutOfRange:
    return "out-of-range";
  case Status::NoFlangePose:
    return "no-flange-pose";
  case Status::CaptureFailed:
    return "capture-failed";
  case Status::CellFailed:
    return "cell-failed";
  case Status::RecipeFailed:
    return "recipe-failed";
  case Status::Internal:
    return "internal";
  }
  return "internal";
}

Decoded decodeBinaryRequest(std::string_view bytes) {
  Decoded d;
  const auto wrongSize = [&](std::size_t expected) {
    d.error = Status::Malformed;
    d.message = "a binary request is " + std::to_string(expected) + " bytes (" +
                std::to_string(kBinaryTriggerAtSize) + " for command 6), not " +
                std::to_string(bytes.size());
    return d;
  };
  if (bytes.size() < 8)
    return wrongSize(kBinaryRequestSize);
  if (getInt(bytes, 0) != kMagic) {
    d.error = Status::BadMagic;
    d.message = "not a scanpick message: it must begin with \"SPK1\"";
    return d;
  }
  const std::int32_t command = getInt(bytes, 1);
  if (bytes.size() != binaryRequestSize(command))
    return wrongSize(binaryRequestSize(command));
  d.id = getInt(bytes, 2);
  if (!knownCommand(command)) {
    d.error = Status::UnknownCommand;
    d.message = "unknown command " + std::to_string(command) + ": use 1 to 6";
    return d;
  }
  d.command = static_cast<Command>(command);
  if (d.command == Command::TriggerAt) {
    const std::int32_t convention = getInt(bytes, 3);
    if (convention != 0 && convention != 1) {
      d.error = Status::Malformed;
      d.message = "field 3 of a trigger at a flange pose is the rotation convention: 0 rotation "
                  "vector, 1 Euler angles Rz·Ry·Rx";
      return d;
    }
    for (std::size_t f = 10; f < 12; ++f)
      if (getInt(bytes, f) != 0) {
        d.error = Status::Malformed;
        d.message = "fields 10 and 11 of a trigger at a flange pose are reserved and must be 0";
        return d;
      }
    Request req;
    req.command = d.command;
    req.id = d.id;
    req.binary = true;
    req.flange_pose = poseArray(triggerAtFlangePose(bytes, convention));
    d.request = req;
    return d;
  }
  for (std::size_t f = 4; f < 8; ++f)
    if (getInt(bytes, f) != 0) {
      d.error = Status::Malformed;
      d.message = "fields 4 to 7 are reserved and must be 0";
      return d;
    }
  Request r;
  r.command = d.command;
  r.id = d.id;
  r.binary = true;
  r.recipe_index = getInt(bytes, 3);
  if (r.command == Command::SetRecipe && r.recipe_index < 0) {
    d.error = Status::Malformed;
    d.message = "set recipe needs a recipe index of 0 or more in field 3";
    return d;
  }
  if (r.command != Command::SetRecipe)
    r.recipe_index = -1;
  d.request = r;
  return d;
}

Decoded decodeJsonRequest(std::string_view line) {
  Decoded d;
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r'))
    line.remove_suffix(1);
  const json doc = json::parse(line, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) {
    d.error = Status::Malformed;
    d.message = "not a JSON object: send one object per line, e.g. {\"cmd\": \"status\"}";
    return d;
  }
  if (doc.contains("id")) {
    const json& id = doc["id"];
    if (!id.is_number_integer() || id.get<long long>() < std::numeric_limits<std::int32_t>::min() ||
        id.get<long long>() > std::numeric_limits<std::int32_t>::max()) {
      d.error = Status::Malformed;
      d.message = "\"id\" must be an integer that fits 32 bits";
      return d;
    }
    d.id = static_cast<std::int32_t>(id.get<long long>());
  }
  for (const auto& item : doc.items())
    if (item.key() != "cmd" && item.key() != "id" && item.key() != "recipe" &&
        item.key() != "flange_pose") {
      d.error = Status::Malformed;
      d.message = "unknown key \"" + item.key() +
                  "\": a request has \"cmd\", \"id\", \"recipe\", \"flange_pose\"";
      return d;
    }
  if (!doc.contains("cmd") || !doc["cmd"].is_string()) {
    d.error = Status::Malformed;
    d.message = "\"cmd\" (a string) is missing";
    return d;
  }
  const Command command = commandFromName(doc["cmd"].get<std::string>());
  if (command == Command::None) {
    d.error = Status::UnknownCommand;
    d.message = "unknown cmd: use trigger, next, picks, set_recipe or status";
    return d;
  }
  d.command = command;
  Request r;
  r.command = command;
  r.id = d.id;
  if (doc.contains("recipe")) {
    if (!doc["recipe"].is_string() || command != Command::SetRecipe) {
      d.error = Status::Malformed;
      d.message = "\"recipe\" is a string, and only for set_recipe";
      return d;
    }
    r.recipe = doc["recipe"].get<std::string>();
  }
  if (doc.contains("flange_pose")) {
    const json& pose = doc["flange_pose"];
    std::vector<double> numbers;
    if (pose.is_array())
      for (const auto& v : pose)
        if (v.is_number())
          numbers.push_back(v.get<double>());
    if (command != Command::Trigger || !pose.is_array() || numbers.size() != pose.size()) {
      d.error = Status::Malformed;
      d.message = "\"flange_pose\" is an array of numbers [x, y, z, rx, ry, rz] (mm, rotation "
                  "vector in degrees), and only for trigger";
      return d;
    }
    try {
      r.flange_pose = poseArray(calib::flangePoseFromNumbers(numbers, "\"flange_pose\""));
    } catch (const Error& e) {
      d.error = Status::Malformed;
      d.message = e.what();
      return d;
    }
  }
  if (command == Command::SetRecipe && r.recipe.empty()) {
    d.error = Status::Malformed;
    d.message = "set_recipe needs \"recipe\": the name of a recipe the server was started with";
    return d;
  }
  d.request = r;
  return d;
}

std::string encodeBinaryRequest(const Request& r) {
  std::string out;
  if (r.flange_pose) {
    const Eigen::Isometry3d T = flangePose(*r.flange_pose);
    const Eigen::Vector3d rv = rotationVectorDeg(Eigen::Quaterniond(
        (*r.flange_pose)[3], (*r.flange_pose)[4], (*r.flange_pose)[5], (*r.flange_pose)[6]));
    putInt(out, kMagic);
    putInt(out, static_cast<std::int32_t>(Command::TriggerAt));
    putInt(out, r.id);
    putInt(out, 0); // rotation vector
    for (int a = 0; a < 3; ++a)
      putInt(out, scaled(T.translation()[a], kPositionScale).value_or(0));
    for (int a = 0; a < 3; ++a)
      putInt(out, scaled(rv[a], kAngleScale).value_or(0));
    putInt(out, 0);
    putInt(out, 0);
    return out;
  }
  putInt(out, kMagic);
  putInt(out, static_cast<std::int32_t>(r.command));
  putInt(out, r.id);
  putInt(out, r.command == Command::SetRecipe ? r.recipe_index : 0);
  for (int i = 0; i < 4; ++i)
    putInt(out, 0);
  return out;
}

std::string encodeJsonRequest(const Request& r) {
  json j = {{"cmd", toString(r.command)}, {"id", r.id}};
  if (r.command == Command::SetRecipe)
    j["recipe"] = r.recipe;
  if (r.flange_pose) {
    const auto& p = *r.flange_pose;
    const Eigen::Vector3d rv = rotationVectorDeg(Eigen::Quaterniond(p[3], p[4], p[5], p[6]));
    j["flange_pose"] = {p[0], p[1], p[2], rv.x(), rv.y(), rv.z()};
  }
  return j.dump() + "\n";
}

std::string encodeBinaryResponse(const Response& r) {
  if (r.command == Command::PickList && r.picks.size() > 1) {
    std::string out;
    for (const auto& p : r.picks)
      out += binaryMessage(r, &p);
    return out;
  }
  return binaryMessage(r, r.picks.empty() ? nullptr : &r.picks.front());
}

std::string encodeJsonResponse(const Response& r) {
  json j = {{"id", r.id},
            {"cmd", toString(r.command)},
            {"status", toString(r.status)},
            {"code", static_cast<int>(r.status)}};
  if (!r.message.empty())
    j["message"] = r.message;
  if (r.status == Status::Ok || r.status == Status::NoPicks) {
    switch (r.command) {
    case Command::Trigger:
    case Command::TriggerAt:
      j["cycle"] = r.cycle;
      j["detections"] = r.detections;
      j["picks"] = r.count;
      j["elapsed_ms"] = r.elapsed_ms;
      break;
    case Command::NextPick:
      if (!r.picks.empty())
        j["pick"] = pickJson(r.picks.front());
      j["remaining"] = r.count;
      j["cycle"] = r.cycle;
      break;
    case Command::PickList: {
      json picks = json::array(), rejected = json::array();
      for (const auto& p : r.picks)
        picks.push_back(pickJson(p));
      for (const auto& c : r.rejected)
        rejected.push_back(grasp::toJson(c));
      j["picks"] = picks;
      j["rejected"] = rejected;
      j["cycle"] = r.cycle;
      break;
    }
    case Command::SetRecipe:
      j["recipe"] = r.recipe;
      j["recipe_index"] = r.recipe_index;
      break;
    case Command::Status:
      j["busy"] = r.busy;
      j["recipe"] = r.recipe;
      j["recipe_index"] = r.recipe_index;
      j["recipes"] = r.recipes;
      j["cycle"] = r.cycle;
      j["remaining"] = r.count;
      j["last_error"] = r.last_error;
      j["calibration"] = r.calibration.empty() ? json(nullptr) : json(r.calibration);
      j["base_frame"] = r.base_frame;
      j["needs_flange_pose"] = r.needs_flange_pose;
      break;
    case Command::None:
      break;
    }
  }
  // Replacement characters keep a message with bad UTF-8 (an echoed name) from throwing.
  return j.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
}

Eigen::Vector3d BinaryAnswer::position_mm() const {
  return Eigen::Vector3d(fields[8], fields[9], fields[10]) / kPositionScale;
}

Eigen::Quaterniond BinaryAnswer::rotation() const {
  return Eigen::Quaterniond(fields[11] / kUnitScale, fields[12] / kUnitScale,
                            fields[13] / kUnitScale, fields[14] / kUnitScale);
}

std::optional<BinaryAnswer> decodeBinaryResponse(std::string_view bytes) {
  if (bytes.size() != kBinaryResponseSize || getInt(bytes, 0) != kMagic)
    return std::nullopt;
  BinaryAnswer a;
  for (std::size_t i = 0; i < a.fields.size(); ++i)
    a.fields[i] = getInt(bytes, i);
  return a;
}

Eigen::Vector3d eulerZyxDeg(const Eigen::Matrix3d& R) {
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  const double sy = std::clamp(-R(2, 0), -1.0, 1.0);
  const double ry = std::asin(sy);
  if (std::abs(sy) > 1.0 - 1e-12) // gimbal lock: rx and rz turn about one axis; put it in rz
    return Eigen::Vector3d(0.0, ry * kDeg, std::atan2(-R(0, 1), R(1, 1)) * kDeg);
  return Eigen::Vector3d(std::atan2(R(2, 1), R(2, 2)) * kDeg, ry * kDeg,
                         std::atan2(R(1, 0), R(0, 0)) * kDeg);
}

} // namespace scanpick::core::link
