#include "core/link/CellService.h"

#include <chrono>

namespace scanpick::core::link {

CellService::CellService(std::shared_ptr<CellBackend> backend) : m_backend(std::move(backend)) {
  if (!m_backend)
    throw Error("a cell service needs a cell");
  m_recipes = m_backend->recipes();
  m_recipe = m_backend->recipe();
  m_calibration = m_backend->calibration();
  m_needs_flange_pose = m_backend->needsFlangePose();
}

Response CellService::status(std::int32_t id) const {
  const std::lock_guard lock(m_mutex);
  Response r;
  r.command = Command::Status;
  r.id = id;
  r.busy = m_busy.load();
  r.recipes = m_recipes;
  r.recipe_index = std::int32_t(m_recipe);
  r.recipe = m_recipe < m_recipes.size() ? m_recipes[m_recipe] : "";
  r.cycle = m_cycles;
  r.count = m_triggered ? std::int32_t(m_cycle.picks.size() - m_next) : 0;
  r.detections = m_cycle.detections;
  r.last_error = m_last_error;
  r.elapsed_ms = m_elapsed_ms;
  r.calibration = m_calibration;
  r.base_frame = !m_calibration.empty();
  r.needs_flange_pose = m_needs_flange_pose;
  return r;
}

/// Runs a cycle; its picks replace the old list, which is cleared before the scan begins.
void CellService::trigger(const Request& request, Response& r) {
  {
    // The old list is void from here on: the bin is being scanned anew.
    const std::lock_guard lock(m_mutex);
    m_cycle = {};
    m_triggered = true;
    m_next = 0;
  }
  CycleInput input;
  if (request.flange_pose)
    input.T_base_flange = flangePose(*request.flange_pose);
  CycleResult cycle = m_backend->runCycle(input);
  const std::lock_guard lock(m_mutex);
  m_cycle = std::move(cycle);
  ++m_cycles;
  m_last_error.clear();
  r.count = std::int32_t(m_cycle.picks.size());
  r.detections = m_cycle.detections;
  r.cycle = m_cycles;
  r.status = m_cycle.picks.empty() ? Status::NoPicks : Status::Ok;
  if (m_cycle.picks.empty())
    r.message = std::to_string(m_cycle.detections) +
                " part(s) found, none pickable (the pick list says why)";
}

/// NextPick: the next pick of the last trigger's list; PickList: the whole list and the rejects.
void CellService::handOutPicks(const Request& request, Response& r) {
  const std::lock_guard lock(m_mutex);
  r.cycle = m_cycles;
  r.detections = m_cycle.detections;
  if (!m_triggered) {
    r.status = Status::NotTriggered;
    r.message = "no pick list yet: send trigger first";
    return;
  }
  if (request.command == Command::NextPick) {
    if (m_next >= m_cycle.picks.size()) {
      r.status = Status::NoPicks;
      r.message = m_last_error.empty() ? "no picks left: trigger again"
                                       : "no picks: the last trigger failed: " + m_last_error;
      return;
    }
    r.picks.push_back(m_cycle.picks[m_next++]);
    r.count = std::int32_t(m_cycle.picks.size() - m_next);
  } else {
    r.picks = m_cycle.picks;
    r.rejected = m_cycle.rejected;
    r.count = std::int32_t(r.picks.size());
    r.status = r.picks.empty() ? Status::NoPicks : Status::Ok;
  }
}

/// Switches to the recipe named (JSON) or numbered (binary) in the request; the pick list is
/// cleared until the next trigger.
void CellService::setRecipe(const Request& request, Response& r) {
  std::size_t index = 0;
  if (request.binary) {
    index = std::size_t(std::max(0, request.recipe_index));
  } else {
    index = m_recipes.size();
    for (std::size_t i = 0; i < m_recipes.size(); ++i)
      if (m_recipes[i] == request.recipe)
        index = i;
    if (index == m_recipes.size()) {
      std::string names;
      for (const auto& n : m_recipes)
        names += (names.empty() ? "" : ", ") + n;
      throw CellFailure(Status::RecipeFailed,
                        "unknown recipe '" + request.recipe + "': use one of [" + names + "]");
    }
  }
  if (index >= m_recipes.size())
    throw CellFailure(Status::RecipeFailed, "no recipe " + std::to_string(index) +
                                                ": the cell has " +
                                                std::to_string(m_recipes.size()));
  m_backend->setRecipe(index);
  const std::lock_guard lock(m_mutex);
  m_recipe = index;
  m_triggered = false;
  m_cycle = {};
  m_next = 0;
  r.recipe = m_recipes[index];
  r.recipe_index = std::int32_t(index);
  r.count = std::int32_t(m_recipes.size());
}

Response CellService::handle(const Request& request) {
  if (request.command == Command::Status)
    return status(request.id);
  Response r;
  r.command = request.command;
  r.id = request.id;
  m_busy = true;
  const auto start = std::chrono::steady_clock::now();
  const auto fail = [&](Status status, const std::string& message) {
    r.status = status;
    r.message = message;
    const std::lock_guard lock(m_mutex);
    m_last_error = message;
  };
  try {
    switch (request.command) {
    case Command::Trigger:
    case Command::TriggerAt:
      trigger(request, r);
      break;
    case Command::NextPick:
    case Command::PickList:
      handOutPicks(request, r);
      break;
    case Command::SetRecipe:
      setRecipe(request, r);
      break;
    default:
      r.status = Status::UnknownCommand;
      r.message = "unknown command";
    }
  } catch (const CellFailure& e) {
    fail(e.status(), e.what());
  } catch (const Error& e) {
    fail(Status::CellFailed, e.what());
  } catch (const std::exception& e) {
    fail(Status::Internal, std::string("internal error: ") + e.what() + " (please report it)");
  }
  r.elapsed_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  {
    const std::lock_guard lock(m_mutex);
    if (request.command == Command::Trigger)
      m_elapsed_ms = r.elapsed_ms;
  }
  m_busy = false;
  return r;
}

} // namespace scanpick::core::link
