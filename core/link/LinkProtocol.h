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
inline constexpr std::size_t kBinaryRequestSize = 32; ///< 8 int32
/// Binary "trigger at flange pose" (command 6) is longer: 12 int32.
inline constexpr std::size_t kBinaryTriggerAtSize = 48;
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
  /// Binary only: trigger with the flange pose at which the scene is taken (eye-in-hand cells).
  /// JSON sends "trigger" with "flange_pose"; answered as a trigger.
  TriggerAt = 6,
};
/// "trigger", "next", "picks", "set_recipe", "status" (TriggerAt: "trigger").
const char* toString(Command command);
/// The size of a binary request with this command code: kBinaryTriggerAtSize for TriggerAt,
/// else kBinaryRequestSize.
std::size_t binaryRequestSize(std::int32_t command);

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
  /// The cell's camera rides on the flange (eye-in-hand calibration): a trigger must carry the
  /// flange pose.
  NoFlangePose = 17,
  CaptureFailed = 20, ///< the camera gave no scene
  CellFailed = 21,    ///< recognition or planning failed
  RecipeFailed = 22,  ///< unknown recipe, or it could not be loaded
  Internal = 29,      ///< a bug: please report it
};
const char* toString(Status status); ///< "ok", "no-picks", "busy", ...

/// A decoded request.
struct Request {
  Command command = Command::None;
  std::int32_t id = 0;            ///< echoed in the answer
  std::string recipe;             ///< SetRecipe over JSON: the recipe's name
  std::int32_t recipe_index = -1; ///< SetRecipe over binary: the recipe's index
  bool binary = false;            ///< it came as a binary message (answer in kind)
  /// Trigger: the flange pose at which the scene is taken, in the robot base: x, y, z (mm), qw,
  /// qx, qy, qz (unit quaternion). Needed by eye-in-hand cells, refused by the others.
  std::optional<std::array<double, 7>> flange_pose;
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

/// The flange pose of a request as a transform (mm).
Eigen::Isometry3d flangePose(const std::array<double, 7>& pose);

/// Decodes one binary request (exactly binaryRequestSize(command) bytes, else Malformed). Never
/// throws. TriggerAt: field 3 the rotation convention (0 rotation vector, 1 Euler angles as in the
/// answers' fields 15-17), fields 4-6 the flange position (0.1 µm), 7-9 its rotation (0.0001°),
/// 10-11 reserved (0).
Decoded decodeBinaryRequest(std::string_view bytes);
/// Decodes one JSON request line (without or with its newline): {"cmd": NAME, "id": INT,
/// "recipe": NAME, "flange_pose": [x, y, z, rx, ry, rz] (mm, rotation vector in degrees) or
/// [x, y, z, qw, qx, qy, qz]}. Unknown keys, wrong types, an id outside int32, a flange pose
/// other than with trigger or not a finite pose are Malformed; an unknown cmd is UnknownCommand.
/// Never throws.
Decoded decodeJsonRequest(std::string_view line);

/// Encodes a request (for clients and tests). A flange pose goes as a rotation vector
/// (binary: TriggerAt with convention 0).
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
  /// The detection's pose (model → the frame of T_tool), mm.
  Eigen::Isometry3d T_part = Eigen::Isometry3d::Identity();
  /// With a hand-eye calibration: the tool and the detection in the robot base frame, mm.
  /// Binary answers then carry T_base_tool in place of T_tool.
  std::optional<Eigen::Isometry3d> T_base_tool, T_base_part;
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
  std::string calibration;        ///< status: the calibration file's name (empty: none)
  bool base_frame = false;        ///< status: picks carry base-frame poses
  bool needs_flange_pose = false; ///< status: triggers must carry the flange pose
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
