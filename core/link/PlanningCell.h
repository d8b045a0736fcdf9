#pragma once
/// @file PlanningCell.h
/// A cell made of a scene source, a detector per recipe and the grasp planner: what
/// `scanpick-cli serve` runs (with a camera and the recognizer) and what the tests run (with
/// scenes and detections made in code).

#include "core/calib/BaseFrame.h"
#include "core/cloud/PointCloud.h"
#include "core/common/Detection.h"
#include "core/grasp/BinBox.h"
#include "core/grasp/GraspPlanner.h"
#include "core/link/CellBackend.h"

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::link {

/// Gives the next scene (scene frame, mm). Throws on failure (answered CaptureFailed).
using SceneSource = std::function<PointCloud()>;
/// Finds the parts in a scene; each detection's model_index names one of the recipe's models.
/// Throws Error on failure (answered CellFailed).
using Detector = std::function<std::vector<Detection>(const PointCloud& scene_mm)>;

/// One recipe of a cell: what to find and how to pick it.
struct CellRecipe {
  std::string name;
  Detector detect;
  std::vector<grasp::GraspModel> models; ///< by Detection::model_index
  grasp::Gripper gripper;
  grasp::GraspPlanParams planning;
  /// Estimate the bin from each scene with these parameters; unset: no bin checks.
  std::optional<grasp::BinEstimateParams> bin;
  /// The scene (camera) frame in the robot's base frame as the recipe gives it
  /// (robot_from_camera): picks are reported in the robot frame. Identity (default): picks are in
  /// the camera frame. A cell with a hand-eye calibration needs it left at identity.
  Eigen::Isometry3d T_robot_scene = Eigen::Isometry3d::Identity();
};

/// The cell: each cycle takes a scene from the source, detects, estimates the bin when the
/// recipe asks, and plans. With a hand-eye calibration each pick also carries the tool and the
/// part in the robot base frame (eye-in-hand: from the flange pose the trigger gives).
class PlanningCell : public CellBackend {
public:
  /// Throws Error without a source, without recipes, for a recipe without a detector, and for a
  /// calibration together with a recipe that places the camera itself (T_robot_scene).
  PlanningCell(SceneSource source, std::vector<CellRecipe> recipes,
               std::optional<calib::CameraCalibration> calibration = std::nullopt);
  CycleResult runCycle(const CycleInput& input) override;
  [[nodiscard]] std::vector<std::string> recipes() const override;
  void setRecipe(std::size_t index) override;
  [[nodiscard]] std::size_t recipe() const override { return m_current; }
  [[nodiscard]] std::string calibration() const override;
  [[nodiscard]] bool needsFlangePose() const override;

private:
  SceneSource m_source;
  std::vector<CellRecipe> m_recipes;
  std::optional<calib::CameraCalibration> m_calibration;
  std::size_t m_current = 0;
};

} // namespace scanpick::core::link
