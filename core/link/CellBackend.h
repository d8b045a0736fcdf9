#pragma once
/// @file CellBackend.h
/// What the robot link asks of a picking cell: run a cycle (capture, recognize, plan) and switch
/// recipes. The server and its tests do not know cameras or recognizers, only this.

#include "core/common/Error.h"
#include "core/link/LinkProtocol.h"

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

/// A cell. Called from one thread at a time (the server's worker).
class CellBackend {
public:
  CellBackend() = default;
  CellBackend(const CellBackend&) = delete;
  CellBackend& operator=(const CellBackend&) = delete;
  virtual ~CellBackend() = default;
  /// Captures a scene, recognizes and plans. Throws CellFailure or Error on failure.
  virtual CycleResult runCycle() = 0;
  /// Names of the recipes the cell can switch to (binary set recipe: by index in this list).
  [[nodiscard]] virtual std::vector<std::string> recipes() const = 0;
  /// Switches to recipes()[index]. Throws CellFailure (RecipeFailed) when it cannot.
  virtual void setRecipe(std::size_t index) = 0;
  /// Index of the current recipe in recipes().
  [[nodiscard]] virtual std::size_t recipe() const = 0;
};

} // namespace scanpick::core::link
