#pragma once
/// @file TargetDetection.h
/// The calibration target in one scan: spheres fitted (SphereFit.h), matched to the layout by
/// their pairwise distances, and the target's pose from the matched centres (Kabsch / Umeyama
/// without scale).

#include "core/calib/CalibTarget.h"
#include "core/calib/SphereFit.h"
#include "core/cloud/PointCloud.h"

#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace scanpick::core::calib {

/// How the target is found in a scan.
struct TargetDetectParams {
  SphereFitParams spheres;
  /// Fitted spheres match the layout when every distance between two of them is within this of
  /// the layout's distance, mm.
  double match_tolerance_mm = 2.0;
  /// At least this many of the layout's spheres must be found (at least 3).
  int min_spheres = 3;
};

/// The target seen in one scan.
struct TargetObservation {
  /// Target frame → scan (camera) frame: maps target coordinates (mm) into the camera frame.
  Eigen::Isometry3d T_camera_target = Eigen::Isometry3d::Identity();
  /// Per sphere of the layout (same order): its fitted centre in the camera frame (mm), or none
  /// when that sphere was not found.
  std::vector<std::optional<Eigen::Vector3d>> centres_camera_mm;
  /// Per sphere of the layout: RMS distance of its points from the fitted sphere (mm; 0 when not
  /// found) and its point count.
  std::vector<double> sphere_rms_mm;
  std::vector<int> sphere_points;
  /// RMS distance between the fitted centres and the layout's centres placed at T_camera_target,
  /// mm: how well the scan agrees with the target's geometry.
  double fit_rms_mm = 0;
  [[nodiscard]] int found() const;
};

/// The assignment of fitted spheres to the layout's spheres (index into `fits` per layout
/// sphere, -1 = not found) that matches the most spheres (at least 3) with every pairwise distance
/// within `tolerance_mm`, the smallest distance errors breaking ties. Empty when no 3 spheres
/// match.
std::vector<int> matchSpheres(const std::vector<Eigen::Vector3d>& fits, const TargetLayout& layout,
                              double tolerance_mm);

/// The rigid transform (no scale) that best maps `from` onto `to` in the least-squares sense
/// (Umeyama), i.e. `to ≈ T * from`. Needs at least 3 non-collinear pairs.
Eigen::Isometry3d rigidFit(const std::vector<Eigen::Vector3d>& from,
                           const std::vector<Eigen::Vector3d>& to);

/// Finds the target in `scan` (camera frame, mm). Throws Error when fewer than
/// params.min_spheres of its spheres are found or match the layout, saying how many spheres of
/// which radius were found and what to check (in view, in range, --units, the target file).
TargetObservation detectTarget(const PointCloud& scan, const TargetLayout& layout,
                               const TargetDetectParams& params = {});

} // namespace scanpick::core::calib
