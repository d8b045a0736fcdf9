#pragma once
/// @file CalibTarget.h
/// The hand-eye calibration target: a flat plate with three or more spheres standing out of it,
/// which any depth sensor sees (no texture or colour needed). Its frame ("target frame"): origin
/// at the centre of the plate's top face, z along the top face's normal (towards the spheres),
/// x along the plate's long side. docs/calibration.md describes the default target.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scanpick::core::calib {

/// A calibration target: where its spheres' centres are and how big they are.
struct TargetLayout {
  std::string name = "scanpick-spheres-4";
  /// Sphere centres in the target frame, mm. At least 3, not collinear, all pairwise distances
  /// different by at least 2 × match_tolerance_mm (TargetDetectParams) so that matching fitted
  /// spheres to the layout by their distances is unambiguous.
  std::vector<Eigen::Vector3d> sphere_centres_mm;
  double sphere_radius_mm = 12.5; ///< all spheres have this radius, mm
  /// The plate, for drawing and simulation only (detection does not rely on it): its size along
  /// x and y and its thickness (below z = 0), mm.
  double plate_x_mm = 200, plate_y_mm = 160, plate_thickness_mm = 10;

  bool operator==(const TargetLayout&) const = default;
};

/// The built-in target: a 200 × 160 × 10 mm plate with four 25 mm balls whose centres stand
/// 7.5 mm above the plate (sunk 5 mm into it), at (-70, -55), (70, -45), (60, 45), (-45, 60) mm.
/// The six distances between them (90.6 to 164.0 mm) differ by at least 8.3 mm.
TargetLayout defaultTarget();

/// The smallest difference between two of the layout's pairwise sphere distances, mm (infinity
/// for fewer than three spheres).
double smallestDistanceGap_mm(const TargetLayout& layout);

/// Checks a layout: at least 3 spheres, a positive radius, spheres not overlapping, not
/// collinear, and pairwise distances that differ by at least `min_gap_mm`. Throws Error saying
/// what is wrong and how to fix the target file.
void validateTarget(const TargetLayout& layout, double min_gap_mm);

} // namespace scanpick::core::calib
