#pragma once
/// @file SphereFit.h
/// Spheres of a known radius found in a scan: the large planes (the target's plate, a table) are
/// removed, the rest is split into clusters, and each cluster that could be a sphere gets a
/// RANSAC sphere (PCL's SACMODEL_SPHERE, radius limited around the known one) and then a
/// least-squares centre with the radius held at the known value.

#include "core/cloud/PointCloud.h"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace scanpick::core::calib {

/// How fitSpheres looks for spheres. Defaults suit a PhoXi-class sensor (σ ≈ 0.1 mm, points
/// 0.3-1 mm apart) and balls of 20-50 mm.
struct SphereFitParams {
  /// A plane is removed when at least this fraction of the remaining points lie within
  /// plane_threshold_mm of it and they lie flat (RMS distance at most 0.4 × plane_threshold_mm,
  /// where a slice through the spheres' tops, filled evenly, has 0.58 ×): the plate and a table.
  double plane_min_fraction = 0.1;
  /// Point-to-plane distance of a plane's points, mm: well above the sensor's noise (at least
  /// 4 σ) so that the flatness test above holds.
  double plane_threshold_mm = 1.0;
  int max_planes = 3; ///< at most this many planes are removed
  /// Points closer than this join one cluster, mm; 0 = a fifth of the sphere radius.
  double cluster_tolerance_mm = 0;
  /// A sphere needs at least this many points within sphere_threshold_mm of its surface.
  int min_sphere_points = 40;
  double sphere_threshold_mm = 0.5; ///< distance of a sphere's points from its surface, mm
  /// RANSAC accepts radii within this fraction of the known radius.
  double radius_tolerance = 0.15;
  /// The points must cover a cap at least this wide (half-angle seen from the centre, degrees):
  /// a small patch pins no centre.
  double min_cap_deg = 25;
  std::uint64_t seed = 1; ///< RANSAC sampling seed: same scan + same seed = same spheres
};

/// A sphere found in a scan.
struct SphereFit {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero(); ///< scan (camera) frame, mm
  int points = 0;                                      ///< points on its surface (inliers)
  double rms_mm = 0; ///< RMS distance of those points from the sphere of the known radius
  /// What the RANSAC radius was (the refinement holds the known radius), mm.
  double ransac_radius_mm = 0;
};

/// Finds spheres of `radius_mm` in `scan` (mm, any frame; organized or not; NaNs ignored),
/// largest (most points) first. Finds none (an empty list) rather than throwing when there are
/// none. Throws Error only for a non-positive radius.
std::vector<SphereFit> fitSpheres(const PointCloud& scan, double radius_mm,
                                  const SphereFitParams& params = {});

/// Least-squares centre of a sphere of known `radius_mm` through `points_mm` (Gauss-Newton from
/// `start_mm`), using only points within `threshold_mm` of the current sphere's surface at each
/// step. Returns the centre; `inliers` and `rms_mm` describe the final inlier set.
Eigen::Vector3d refineSphereCentre(const std::vector<Eigen::Vector3d>& points_mm,
                                   const Eigen::Vector3d& start_mm, double radius_mm,
                                   double threshold_mm, int& inliers, double& rms_mm);

} // namespace scanpick::core::calib
