#pragma once
/// @file CellService.h
/// The robot link's requests served on a cell: the pick list of the last trigger, handed out
/// pick by pick, recipe switches and the cell's status.

#include "core/link/CellBackend.h"
#include "core/link/LinkProtocol.h"

#include <atomic>
#include <memory>
#include <mutex>

namespace scanpick::core::link {

/// Serves requests on a backend. handle() is called for one request at a time (the server's
/// worker); status() may be called from any thread at any time, also during handle().
class CellService {
public:
  /// Throws Error for a null backend.
  explicit CellService(std::shared_ptr<CellBackend> backend);

  /// Answers `request`: Trigger runs a cycle (its failure is answered with the failure's status
  /// and clears the pick list), NextPick hands out the next pick (NoPicks when none is left,
  /// NotTriggered before the first trigger and after a recipe change), PickList gives them all,
  /// SetRecipe switches by name (JSON) or index (binary). Never throws.
  Response handle(const Request& request);
  /// The cell's state (busy, recipe, cycle, picks left, last error). Never throws.
  [[nodiscard]] Response status(std::int32_t id) const;

private:
  // The commands handle() serves; each fills `r` or throws CellFailure or Error.
  void trigger(const Request& request, Response& r);
  void handOutPicks(const Request& request, Response& r);
  void setRecipe(const Request& request, Response& r);

  std::shared_ptr<CellBackend> m_backend;
  mutable std::mutex m_mutex; ///< guards what follows
  CycleResult m_cycle;
  bool m_triggered = false;
  std::size_t m_next = 0;
  std::uint64_t m_cycles = 0;
  std::string m_last_error;
  std::vector<std::string> m_recipes;
  std::size_t m_recipe = 0;
  double m_elapsed_ms = 0.0;
  std::string m_calibration; ///< the backend's, read once
  bool m_needs_flange_pose = false;
  std::atomic<bool> m_busy{false};
};

} // namespace scanpick::core::link
