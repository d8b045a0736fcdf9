#include "core/link/PlanningCell.h"

namespace scanpick::core::link {

PlanningCell::PlanningCell(SceneSource source, std::vector<CellRecipe> recipes)
    : m_source(std::move(source)), m_recipes(std::move(recipes)) {
  if (!m_source)
    throw Error("a cell needs a scene source (a camera)");
  if (m_recipes.empty())
    throw Error("a cell needs at least one recipe");
  for (const auto& r : m_recipes)
    if (!r.detect)
      throw Error("recipe '" + r.name + "' has no detector");
}

CycleResult PlanningCell::runCycle() {
  const CellRecipe& recipe = m_recipes[m_current];
  PointCloud scene;
  try {
    scene = m_source();
  } catch (const std::exception& e) {
    throw CellFailure(Status::CaptureFailed, std::string("capture failed: ") + e.what());
  }
  const std::vector<Detection> detections = recipe.detect(scene);
  std::optional<grasp::BinBox> bin;
  if (recipe.bin)
    bin = grasp::estimateBin(scene, *recipe.bin);
  const grasp::PickList list =
      grasp::planGrasps(scene, detections, recipe.models, recipe.gripper, bin, recipe.planning);
  CycleResult out;
  out.detections = int(detections.size());
  for (std::size_t i = 0; i < list.picks.size(); ++i) {
    const auto& c = list.picks[i];
    Pick p;
    p.rank = int(i);
    p.detection = c.detection;
    p.grasp = c.grasp;
    p.grip = c.grip;
    p.T_tool = recipe.T_robot_scene * c.T_scene_tool;
    p.approach_length_mm = recipe.planning.approach_length_mm;
    p.score = c.score;
    p.tilt_deg = c.tilt_deg;
    p.occlusion = c.occlusion;
    out.picks.push_back(std::move(p));
  }
  out.rejected = list.rejected;
  return out;
}

std::vector<std::string> PlanningCell::recipes() const {
  std::vector<std::string> names;
  for (const auto& r : m_recipes)
    names.push_back(r.name);
  return names;
}

void PlanningCell::setRecipe(std::size_t index) {
  if (index >= m_recipes.size())
    throw CellFailure(Status::RecipeFailed, "no recipe " + std::to_string(index) +
                                                ": the cell has " +
                                                std::to_string(m_recipes.size()) + " (0 to " +
                                                std::to_string(m_recipes.size() - 1) + ")");
  m_current = index;
}

} // namespace scanpick::core::link
