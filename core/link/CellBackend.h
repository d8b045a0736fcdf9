#pragma once
/// @file CellBackend.h
/// What the robot link asks of a picking cell: run a cycle (capture, recognize, plan) and switch
/// recipes. The server and its tests do not know cameras or recognizers, only this.

#include "core/common/Error.h"
#include "core/link/LinkProtocol.h"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::link {

/// A failure of the cell that has its own status code (CaptureFailed, RecipeFailed ...). Other
/// core::Error exceptions from a backend are answered CellFailed.
class CellFailure : public Error {
public:
  CellFailure(Status status, const std::string& message) : Error(message), m_status(status) {}
  [[nodiscard]] Status status() const { return m_status; }

private:
  Status m_status;
};

/// What one cycle produced.
struct CycleResult {
  std::vector<Pick> picks;                     ///< ranked, rank = position
  std::vector<grasp::GraspCandidate> rejected; ///< with reasons, for the JSON pick list
  int detections = 0;
};

/// What a trigger tells the cell about the scene it is to take.
struct CycleInput {
  /// The flange pose at which the scene is taken, in the robot base (mm): needed by an
  /// eye-in-hand cell, refused by the others.
  std::optional<Eigen::Isometry3d> T_base_flange;
};

/// A cell. Called from one thread at a time (the server's worker).
class CellBackend {
public:
  CellBackend() = default;
  CellBackend(const CellBackend&) = delete;
  CellBackend& operator=(const CellBackend&) = delete;
  virtual ~CellBackend() = default;
  /// Captures a scene, recognizes and plans. Throws CellFailure or Error on failure:
  /// NoFlangePose when the cell needs input.T_base_flange and it is missing, Malformed when it is
  /// given and the cell cannot use it (both before any capture).
  virtual CycleResult runCycle(const CycleInput& input) = 0;
  /// Names of the recipes the cell can switch to (binary set recipe: by index in this list).
  [[nodiscard]] virtual std::vector<std::string> recipes() const = 0;
  /// Switches to recipes()[index]. Throws CellFailure (RecipeFailed) when it cannot.
  virtual void setRecipe(std::size_t index) = 0;
  /// Index of the current recipe in recipes().
  [[nodiscard]] virtual std::size_t recipe() const = 0;
  /// The hand-eye calibration file's name when picks carry base-frame poses; empty otherwise.
  [[nodiscard]] virtual std::string calibration() const { return {}; }
  /// Triggers must carry the flange pose (eye-in-hand calibration).
  [[nodiscard]] virtual bool needsFlangePose() const { return false; }
};

} // namespace scanpick::core::link
