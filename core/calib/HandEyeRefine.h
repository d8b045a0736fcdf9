#pragma once
/// @file HandEyeRefine.h
/// The two numerical steps of the hand-eye solve (HandEye.h), on the common form
/// B_i = X⁻¹ · M_i · Y: OpenCV's closed-form first solution and the least-squares refinement on
/// the sphere centres. Internal to core/calib; calibrateHandEye is the interface.

#include <Eigen/Geometry>
#include <vector>

namespace scanpick::core::calib::detail {

/// One sphere seen at one pose: its centre in the target frame and its fitted centre in the
/// camera frame, mm.
struct CentrePair {
  Eigen::Vector3d target_mm;
  Eigen::Vector3d camera_mm;
};

/// The data of one pose in the common form.
struct PoseData {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity(); ///< T_base_flange or its inverse
  Eigen::Isometry3d B = Eigen::Isometry3d::Identity(); ///< T_camera_target (Kabsch fit)
  std::vector<CentrePair> centres;
};

/// X and Y of B_i = X⁻¹ · M_i · Y.
struct Solution {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d Y = Eigen::Isometry3d::Identity();
};

/// OpenCV's calibrateRobotWorldHandEye with `shah` (true) or Li's method (false), from at least 3
/// poses. False when OpenCV fails or returns something that is not a rigid transform.
bool openCvSolution(const std::vector<PoseData>& poses, bool shah, Solution& solution);

/// Levenberg-Marquardt on the sphere-centre residuals X⁻¹ · M_i · Y · s_k − c_ik over all poses
/// (12 unknowns: a turn and a shift of X and of Y, each applied on the right). Returns the sum of
/// squared residuals, mm².
double refineSolution(const std::vector<PoseData>& poses, Solution& solution, int max_iterations);

} // namespace scanpick::core::calib::detail
