#include "core/link/PlanningCell.h"

namespace scanpick::core::link {

PlanningCell::PlanningCell(SceneSource source, std::vector<CellRecipe> recipes,
                           std::optional<calib::CameraCalibration> calibration)
    : m_source(std::move(source)), m_recipes(std::move(recipes)),
      m_calibration(std::move(calibration)) {
  if (!m_source)
    throw Error("a cell needs a scene source (a camera)");
  if (m_recipes.empty())
    throw Error("a cell needs at least one recipe");
  for (const auto& r : m_recipes) {
    if (!r.detect)
      throw Error("recipe '" + r.name + "' has no detector");
    if (m_calibration && !r.T_robot_scene.isApprox(Eigen::Isometry3d::Identity(), 0.0))
      throw Error("recipe '" + r.name +
                  "' places the camera in the robot frame itself "
                  "(robot_from_camera) and the cell has the calibration " +
                  m_calibration->file + ": give one of the two");
  }
}

std::string PlanningCell::calibration() const {
  return m_calibration ? m_calibration->file : std::string();
}

bool PlanningCell::needsFlangePose() const {
  return m_calibration && m_calibration->needsFlangePose();
}

CycleResult PlanningCell::runCycle(const CycleInput& input) {
  const CellRecipe& recipe = m_recipes[m_current];
  // The flange pose is checked before the capture: a refused trigger takes no scene.
  std::optional<Eigen::Isometry3d> T_base_camera;
  if (m_calibration) {
    if (m_calibration->needsFlangePose() && !input.T_base_flange)
      throw CellFailure(Status::NoFlangePose,
                        "the camera rides on the flange (eye-in-hand calibration " +
                            m_calibration->file +
                            "): send the flange pose with the trigger (JSON \"flange_pose\", "
                            "binary command 6)");
    try {
      T_base_camera = calib::baseFromCamera(*m_calibration, input.T_base_flange);
    } catch (const Error& e) {
      throw CellFailure(Status::Malformed, e.what());
    }
  } else if (input.T_base_flange) {
    throw CellFailure(Status::Malformed,
                      "this cell has no hand-eye calibration: leave the flange pose out (serve "
                      "--calibration FILE gives the cell one)");
  }
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
    const Detection& d = detections.at(std::size_t(c.detection));
    p.T_part = recipe.T_robot_scene * d.T_scene_model;
    if (T_base_camera) {
      p.T_base_tool = *T_base_camera * c.T_scene_tool;
      p.T_base_part = *T_base_camera * d.T_scene_model;
    }
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
