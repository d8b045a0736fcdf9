#pragma once
/// @file LinkProtocol.h
/// The robot link's messages and their two encodings (docs/robot-link.md): JSON lines for PCs, and
/// fixed-size little-endian int32 messages for robot controllers and PLCs. Pure functions: no
/// sockets, no state.

#include "core/grasp/GraspPlanner.h"

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace scanpick::core::link {

/// "SPK1" as a little-endian int32: the first field of every binary message.
inline constexpr std::int32_t kMagic = 0x314B5053;
inline constexpr std::size_t kBinaryRequestSize = 32;  ///< 8 int32
inline constexpr std::size_t kBinaryResponseSize = 96; ///< 24 int32
/// Longest JSON request line, newline included; a longer one is answered TooLong.
inline constexpr std::size_t kMaxJsonLine = 4096;
/// Binary positions are millimetres x this (units of 0.1 µm).
inline constexpr double kPositionScale = 10000.0;
/// Binary quaternion components and scores are x this.
inline constexpr double kUnitScale = 1000000.0;
/// Binary angles are degrees x this (units of 0.0001°).
inline constexpr double kAngleScale = 10000.0;

/// What a client asks. The numbers are the binary command codes.
enum class Command : std::int32_t {
  None = 0,      ///< in answers to messages that could not be decoded
  Trigger = 1,   ///< capture a scene, recognize and plan: a new pick list
  NextPick = 2,  ///< the next pick of the list (each pick is handed out once)
  PickList = 3,  ///< the whole pick list of the last trigger
  SetRecipe = 4, ///< switch recipe (JSON: by name; binary: by index)
  Status = 5,    ///< the cell's state; answered even while the cell is busy
};
const char* toString(Command command); ///< "trigger", "next", "picks", "set_recipe", "status"

/// Status codes of answers (binary field 3, JSON "code"). 0 is success; 1-9 are normal outcomes;
/// 10-19 are errors in the request; 20-29 are failures of the cell.
enum class Status : std::int32_t {
  Ok = 0,
  NoPicks = 1,      ///< nothing (left) to pick: trigger again
  Busy = 2,         ///< the cell is serving another request: retry later
  NotTriggered = 3, ///< next/picks before any trigger (or after a recipe change)
  BadMagic = 10,    ///< not a scanpick message (the connection is then closed)
  UnknownCommand = 11,
  Malformed = 12,      ///< bad field, bad JSON, non-zero reserved field ...
  Incomplete = 13,     ///< a message began but did not end in time (the connection is closed)
  TooLong = 14,        ///< JSON line over kMaxJsonLine bytes (the connection is closed)
  TooManyClients = 15, ///< the server's client limit is reached (the connection is closed)
  OutOfRange = 16,     ///< a value does not fit the binary message (position beyond ±214 m)
  CaptureFailed = 20,  ///< the camera gave no scene
  CellFailed = 21,     ///< recognition or planning failed
  RecipeFailed = 22,   ///< unknown recipe, or it could not be loaded
  Internal = 29,       ///< a bug: please report it
};
const char* toString(Status status); ///< "ok", "no-picks", "busy", ...

/// A decoded request.
struct Request {
  Command command = Command::None;
  std::int32_t id = 0;            ///< echoed in the answer
  std::string recipe;             ///< SetRecipe over JSON: the recipe's name
  std::int32_t recipe_index = -1; ///< SetRecipe over binary: the recipe's index
  bool binary = false;            ///< it came as a binary message (answer in kind)
  bool operator==(const Request&) const = default;
};

/// The result of decoding one message: a request, or the status to answer with and why.
struct Decoded {
  std::optional<Request> request;
  Status error = Status::Ok;
  std::string message;
  std::int32_t id = 0;             ///< the request id, when it could be read
  Command command = Command::None; ///< the command, when it could be read
};

/// Decodes one binary request (exactly kBinaryRequestSize bytes, else Malformed). Never throws.
Decoded decodeBinaryRequest(std::string_view bytes);
/// Decodes one JSON request line (without or with its newline): {"cmd": NAME, "id": INT,
/// "recipe": NAME}. Unknown keys, wrong types, an id outside int32 are Malformed; an unknown
/// cmd is UnknownCommand. Never throws.
Decoded decodeJsonRequest(std::string_view line);

/// Encodes a request (for clients and tests).
std::string encodeBinaryRequest(const Request& request);
std::string encodeJsonRequest(const Request& request);

/// One pick as the link reports it.
struct Pick {
  int rank = -1;      ///< 0 = first in the list
  int detection = -1; ///< index of the detection in this cycle
  int grasp = -1;     ///< index of the grasp point in its model
  std::string grip;   ///< the grasp point's name
  /// Tool pose at the grasp, in the frame the cell reports (the robot's when the recipe gives
  /// the camera's pose in it; else the camera's), mm.
  Eigen::Isometry3d T_tool = Eigen::Isometry3d::Identity();
  double approach_length_mm = 0.0; ///< the pre-grasp pose is T_tool moved back this far along z
  double score = 0.0, tilt_deg = 0.0, occlusion = 0.0;
};

/// An answer. Which fields mean something depends on the command (docs/robot-link.md).
struct Response {
  Command command = Command::None;
  std::int32_t id = 0;
  Status status = Status::Ok;
  std::string message;    ///< for the operator; JSON only
  std::int32_t count = 0; ///< picks in the list (trigger, picks) or left (next, status)
  std::int32_t detections = 0;
  std::uint64_t cycle = 0;                     ///< triggers served so far
  double elapsed_ms = 0.0;                     ///< time the request took in the cell
  std::vector<Pick> picks;                     ///< next: one; picks: all
  std::vector<grasp::GraspCandidate> rejected; ///< picks over JSON: the rejected grasps
  bool busy = false;
  std::string recipe;
  std::int32_t recipe_index = -1;
  std::vector<std::string> recipes;
  std::string last_error;
};

/// Binary answer: one kBinaryResponseSize message, or for PickList one per pick (at least one),
/// each carrying the count. Fields that do not fit an int32 make that message OutOfRange.
std::string encodeBinaryResponse(const Response& response);
/// JSON answer: one line ending in '\n'.
std::string encodeJsonResponse(const Response& response);

/// One binary answer message as a client reads it (decodeBinaryResponse).
struct BinaryAnswer {
  std::array<std::int32_t, 24> fields{};
  [[nodiscard]] std::int32_t status() const { return fields[3]; }
  [[nodiscard]] std::int32_t command() const { return fields[1]; }
  [[nodiscard]] std::int32_t id() const { return fields[2]; }
  [[nodiscard]] std::int32_t count() const { return fields[4]; }
  [[nodiscard]] Eigen::Vector3d position_mm() const;
  [[nodiscard]] Eigen::Quaterniond rotation() const;
};
/// Reads one binary answer (exactly kBinaryResponseSize bytes with the magic); nothing otherwise.
std::optional<BinaryAnswer> decodeBinaryResponse(std::string_view bytes);

/// Euler angles (degrees) of R = Rz(rz) · Ry(ry) · Rx(rx), as (rx, ry, rz): KUKA's (C, B, A),
/// Fanuc's (W, P, R). At ry = ±90° rx is 0.
Eigen::Vector3d eulerZyxDeg(const Eigen::Matrix3d& R);

} // namespace scanpick::core::link
