#pragma once
/// @file CalibJson.h
/// The hand-eye calibration's files (docs/calibration.md): the target file, the poses file (the
/// scans and the robot's flange poses) and the calibration result.

#include "core/calib/CalibTarget.h"
#include "core/calib/HandEye.h"

#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace scanpick::core::calib {

/// Version of the calibration result file ("format": "scanpick-handeye").
inline constexpr int kCalibrationFileVersion = 1;

/// A rigid transform from JSON, either a 4 × 4 matrix (four rows of four numbers, last row
/// 0 0 0 1) or {"x", "y", "z", "qw", "qx", "qy", "qz"} (position, unit quaternion); also
/// {"matrix": 4 × 4}. Translations are multiplied by `mm_per_unit`. Throws Error naming `what` for
/// anything else, a matrix whose rotation part is not a rotation (within 1e-3) or a quaternion
/// whose length is not 1 (within 1e-3; it is normalized).
Eigen::Isometry3d poseFromJson(const nlohmann::json& j, double mm_per_unit,
                               const std::string& what);

/// {"matrix": 4 × 4 rows, "x", "y", "z" (mm), "qw", "qx", "qy", "qz"}.
nlohmann::json poseToJson(const Eigen::Isometry3d& T);

/// Reads a target: {"name", "sphere_radius_mm", "spheres_mm": [[x, y, z], ...], "plate_mm":
/// [x, y, thickness]} (name and plate optional), then validateTarget(min_gap_mm). Throws Error
/// naming `source` and the key.
TargetLayout targetFromJson(const nlohmann::json& j, const std::string& source, double min_gap_mm);
nlohmann::json toJson(const TargetLayout& layout);
/// Reads and checks a target file (targetFromJson).
TargetLayout loadTarget(const std::filesystem::path& path, double min_gap_mm);

/// One entry of the poses file.
struct PoseEntry {
  std::filesystem::path scan; ///< the scan taken at this pose (relative paths: to the file)
  Eigen::Isometry3d T_base_flange = Eigen::Isometry3d::Identity(); ///< mm
};

/// Reads a poses file: a list [{"scan": PATH, "T_base_flange": pose}, ...] or {"poses": [...]};
/// each pose as poseFromJson, its translation in units of `mm_per_unit`. Scan paths are taken
/// relative to the poses file's folder. Throws Error naming the entry and what to fix.
std::vector<PoseEntry> loadPoseList(const std::filesystem::path& path, double mm_per_unit);

/// The result file: format, version, mode, the two poses under their names, the RMS residuals,
/// the residual of every pose (rejected ones with their reason) and the target used.
nlohmann::json toJson(const HandEyeResult& result, const TargetLayout& layout);

/// Writes toJson(result, layout) to `path` atomically (the destination is replaced only when
/// complete). Throws Error on failure.
void saveCalibration(const std::filesystem::path& path, const HandEyeResult& result,
                     const TargetLayout& layout);

/// Reads a result file's mode and poses (residuals are not read back). Throws Error for another
/// format, a newer version or a missing pose.
HandEyeResult loadCalibration(const std::filesystem::path& path);

} // namespace scanpick::core::calib
