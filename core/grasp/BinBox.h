#pragma once
/// @file BinBox.h
/// The bin's inner box (floor and walls), estimated from a scan as planes, and the test of a
/// point against it.

#include "core/cloud/PointCloud.h"

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace scanpick::core::grasp {

/// The inside of a bin. Bin frame: origin on the floor at the centre between the walls, +z up
/// (into the bin), x and y along the wall normals. Inside is 0 <= z, |x| <= half_size_mm.x(),
/// |y| <= half_size_mm.y(); below the rim (z < rim_height_mm) everything outside that is wall or
/// beyond it. A wall that was not found leaves its side open (no limit there).
struct BinBox {
  Eigen::Isometry3d T_scene_bin = Eigen::Isometry3d::Identity(); ///< bin frame → scene (mm)
  Eigen::Vector2d half_size_mm = Eigen::Vector2d::Zero();        ///< inner half sizes along x and y
  double rim_height_mm = 0.0; ///< top of the walls above the floor
  bool floor_found = false;   ///< false: no floor limit
  /// Walls at +x, -x, +y, -y of the bin frame that were found (others are open).
  std::array<bool, 4> walls_found{};
};

/// What a point collides with in the bin: "" (nothing), "bin floor", "bin wall +x" ... A point
/// on the boundary (within `margin_mm` inside it) counts as colliding.
std::string binCollision(const BinBox& bin, const Eigen::Vector3d& p_scene_mm,
                         double margin_mm = 0.0);

/// How estimateBin looks for the bin.
struct BinEstimateParams {
  /// Up in the scene frame (unit): the floor's normal is near it, the walls' normals are
  /// perpendicular to it. Default: towards a camera looking down its +z axis.
  Eigen::Vector3d up = -Eigen::Vector3d::UnitZ();
  double distance_mm = 3.0;        ///< RANSAC inlier distance of a plane point (mm)
  double angle_tol_deg = 10.0;     ///< how far a floor / wall normal may be off up / horizontal
  double min_plane_share = 0.03;   ///< smallest plane, as a share of the sampled points
  int max_planes = 8;              ///< planes searched at most
  int iterations = 400;            ///< RANSAC iterations per plane
  std::size_t max_samples = 30000; ///< points sampled (evenly) from the scan
  std::uint64_t seed = 1;          ///< RANSAC seed: same scan + seed = same bin
  bool operator==(const BinEstimateParams&) const = default;
};

/// Finds the bin in `scene_mm` (scene frame, mm): planes by sequential RANSAC on an even sample of
/// the valid points; walls are the planes perpendicular to up (turned to face the bin's inside,
/// opposite walls paired along the first wall's normal and across it); the floor is the lowest
/// plane facing up whose points lie between the walls (a table around the bin does not); without
/// one, the floor is put at the lowest wall point. The rim is the highest wall point. Returns
/// nothing when no wall is found (a table, not a bin). Deterministic for a given seed. Throws
/// Error for a non-unit `up` or out-of-range parameters.
std::optional<BinBox> estimateBin(const PointCloud& scene_mm, const BinEstimateParams& params = {});

} // namespace scanpick::core::grasp
