#pragma once
/// @file BaseFrame.h
/// Poses in the robot's base frame from a hand-eye calibration (docs/calibration.md, "Poses in
/// the robot base frame"): what `scanpick-cli recognize --calibration` and the robot link use.
///
/// Eye-to-hand: T_base_part = T_base_camera · T_camera_part.
/// Eye-in-hand: T_base_part = T_base_flange · T_flange_camera · T_camera_part, with the flange
/// pose at which the scan was taken.
///
/// Lengths are mm; flange rotations given as a rotation vector are in degrees.

#include "core/calib/HandEye.h"

#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::calib {

/// What turning camera-frame poses into base-frame poses needs of a calibration file.
struct CameraCalibration {
  HandEyeMode mode = HandEyeMode::EyeToHand;
  /// T_base_camera (eye-to-hand) or T_flange_camera (eye-in-hand), mm.
  Eigen::Isometry3d T_camera = Eigen::Isometry3d::Identity();
  std::string file; ///< the file's name (no folder), for results and status answers

  /// Eye-in-hand: every scan needs the flange pose it was taken at.
  [[nodiscard]] bool needsFlangePose() const { return mode == HandEyeMode::EyeInHand; }
};

/// Reads a calibration file written by `scanpick-cli calibrate` (loadCalibration) and checks its
/// camera pose. Throws Error naming the file for another format, a newer version, a missing or
/// non-finite pose and a rotation that is not orthonormal (within 1e-3).
CameraCalibration loadCameraCalibration(const std::filesystem::path& path);

/// The camera in the base for one scan: eye-to-hand T_base_camera; eye-in-hand
/// T_base_flange · T_flange_camera. Throws Error for an eye-in-hand calibration without a flange
/// pose ("give the flange pose ...") and for a flange pose given with an eye-to-hand one (the
/// camera does not move with the flange: a wrong calibration file is the likely cause).
Eigen::Isometry3d baseFromCamera(const CameraCalibration& calibration,
                                 const std::optional<Eigen::Isometry3d>& T_base_flange);

/// A pose from a position (mm) and a rotation vector (axis × angle, degrees): the flange pose
/// convention of `recognize --flange-pose` and the robot link.
Eigen::Isometry3d poseFromRotationVector(const Eigen::Vector3d& position_mm,
                                         const Eigen::Vector3d& rotation_vector_deg);

/// A flange pose from 6 numbers x, y, z (mm), rx, ry, rz (rotation vector, degrees), or 7 numbers
/// x, y, z (mm), qw, qx, qy, qz (unit quaternion, w first, as in calibrate's poses file; its
/// length must be 1 within 1e-3). Throws Error naming `what` for another count, a non-finite
/// number or a quaternion of another length.
Eigen::Isometry3d flangePoseFromNumbers(const std::vector<double>& numbers,
                                        const std::string& what);

/// flangePoseFromNumbers of a comma-separated list ("400,-20,550,180,0,0"). Throws Error naming
/// `what` for text that is not such a list.
Eigen::Isometry3d parseFlangePose(const std::string& text, const std::string& what);

/// {"matrix": 4 × 4 rows, "position_mm": [x, y, z], "quaternion_wxyz": [w, x, y, z]} with w ≥ 0.
nlohmann::json basePoseJson(const Eigen::Isometry3d& T);

} // namespace scanpick::core::calib
