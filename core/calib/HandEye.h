#pragma once
/// @file HandEye.h
/// Hand-eye calibration from N robot poses and the calibration target seen at each of them.
///
/// Eye-to-hand: the camera stands still and the robot carries the target on its flange. Unknowns:
/// the camera in the robot base (T_base_camera) and the target on the flange (T_flange_target);
/// at pose i, T_camera_target_i = T_base_camera⁻¹ · T_base_flange_i · T_flange_target.
///
/// Eye-in-hand: the camera rides on the flange and the target stands still. Unknowns: the camera
/// on the flange (T_flange_camera) and the target in the base (T_base_target); at pose i,
/// T_camera_target_i = T_flange_camera⁻¹ · T_base_flange_i⁻¹ · T_base_target.
///
/// Both are the robot-world/hand-eye equation B_i = X⁻¹ · M_i · Y with X the camera's pose (in
/// the base or the flange), M_i the robot pose (eye-to-hand) or its inverse (eye-in-hand) and Y
/// the target's pose (on the flange or in the base). OpenCV's calibrateRobotWorldHandEye (Shah)
/// gives the first solution; Levenberg-Marquardt over all poses then minimizes the distances
/// between the fitted sphere centres and where X and Y put the target's spheres, which is what
/// picking depends on. Poses that disagree with the rest are rejected one by one and the solve is
/// repeated without them.
///
/// All lengths are mm, angles degrees unless a name says otherwise.

#include "core/calib/CalibTarget.h"
#include "core/calib/TargetDetection.h"

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace scanpick::core::calib {

enum class HandEyeMode { EyeToHand, EyeInHand };

/// "eye-to-hand" / "eye-in-hand".
std::string modeName(HandEyeMode mode);
/// Inverse of modeName; throws Error naming the two modes.
HandEyeMode modeFromName(const std::string& name);

/// How the solve checks its input and rejects poses.
struct HandEyeParams {
  /// Motion check: two poses count as rotated against each other when they differ by at least
  /// this angle, and the rotations between poses must turn about axes at least
  /// min_axis_spread_deg apart (rotations about one axis leave the calibration undetermined).
  double min_rotation_deg = 5.0;
  double min_axis_spread_deg = 10.0;
  /// Outlier poses: a pose is rejected when its residual exceeds the median of all poses' by
  /// more than outlier_mad_factor × the scaled median absolute deviation (1.4826 × MAD) and by
  /// more than the floor (outlier_floor_mm for the sphere centres' RMS, outlier_floor_deg for the
  /// rotation); the floors keep a set of very consistent poses from losing good ones to noise.
  double outlier_mad_factor = 3.0;
  double outlier_floor_mm = 0.3;
  double outlier_floor_deg = 0.1;
  /// At most this fraction of the poses may be rejected; more means the data are inconsistent
  /// and the solve fails.
  double max_rejected_fraction = 0.34;
  /// The solve fails when the poses it keeps still miss the solution by more than this RMS
  /// (sphere centres, mm): poses that all disagree a little are not caught by the outlier test.
  double max_rms_mm = 2.0;
  int max_iterations = 100; ///< Levenberg-Marquardt iterations per solve
};

/// One pose: what the robot reported and what the camera saw.
struct HandEyeSample {
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity(); ///< flange → base, mm
  TargetObservation observation;                                   ///< the target in the camera
};

/// How well one pose agrees with the solution.
struct PoseResidual {
  int index = 0;      ///< 0-based index of the pose in the input
  double rms_mm = 0;  ///< RMS distance between fitted and predicted sphere centres
  double max_mm = 0;  ///< largest such distance
  double rot_deg = 0; ///< angle between the fitted and the predicted target orientation
  bool rejected = false;
  std::string reason; ///< why it was rejected (empty when used)
};

/// The calibration.
struct HandEyeResult {
  HandEyeMode mode = HandEyeMode::EyeToHand;
  /// The camera's pose: T_base_camera (eye-to-hand) or T_flange_camera (eye-in-hand).
  Eigen::Isometry3d T_camera = Eigen::Isometry3d::Identity();
  /// The target's pose: T_flange_target (eye-to-hand) or T_base_target (eye-in-hand).
  Eigen::Isometry3d T_target = Eigen::Isometry3d::Identity();
  /// Per input pose, in input order; residuals of rejected poses are against the final solution.
  std::vector<PoseResidual> residuals;
  double rms_mm = 0;  ///< RMS sphere-centre residual over the poses used
  double rms_deg = 0; ///< RMS rotation residual over the poses used
  int poses_used = 0;

  /// "T_base_camera" or "T_flange_camera"; "T_flange_target" or "T_base_target".
  [[nodiscard]] std::string cameraName() const;
  [[nodiscard]] std::string targetName() const;
};

/// Solves the calibration. Throws Error for too few poses (at least 3, with rotations about
/// non-parallel axes), motion that leaves it undetermined (too little rotation, one rotation
/// axis), a sample without 3 sphere centres, and data that stay inconsistent (more than
/// max_rejected_fraction of the poses rejected, or an RMS above max_rms_mm).
HandEyeResult calibrateHandEye(HandEyeMode mode, const std::vector<HandEyeSample>& samples,
                               const TargetLayout& layout, const HandEyeParams& params = {});

/// Checks, before any scan is read, that `T_base_flange` are enough poses (at least 3) and move
/// enough (checkMotion); throws Error saying what to record.
void checkPoses(const std::vector<Eigen::Isometry3d>& T_base_flange, const HandEyeParams& params);

/// Checks that `T_base_flange` poses move enough for a calibration (params.min_rotation_deg,
/// params.min_axis_spread_deg); throws Error saying how to move the robot.
void checkMotion(const std::vector<Eigen::Isometry3d>& T_base_flange, const HandEyeParams& params);

/// The angle of a rotation, degrees (0..180).
double rotationAngle_deg(const Eigen::Matrix3d& R);

} // namespace scanpick::core::calib
