#pragma once
/// @file FloorRemoval.h
/// Removal of the dominant planes of a scene (bin floor, table, walls) with RANSAC, §3.3.

#include "core/cloud/PointCloud.h"
#include "core/common/Progress.h"
#include "core/params/Parameters.h"

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace scanpick::core {

/// What removeFloor removed and what it kept.
struct FloorRemovalResult {
  /// The scene without the plane points. Same size and organization as the input when the input
  /// is organized (removed points become NaN, other channels are kept); unorganized otherwise.
  PointCloud remaining;
  /// `remaining` with the bin's walls and rim back in (same size and organization): the surfaces
  /// a pose must not pass through, for verification and refinement. Empty when no wall was
  /// removed.
  PointCloud remaining_with_walls;
  /// The removed planes, largest first: (a, b, c, d) with a unit normal, a x + b y + c z + d = 0 in
  /// millimetres, the normal pointing towards the camera (the origin).
  std::vector<Eigen::Vector4f> planes;
  /// The plane the parts rest on, one of `planes`: the bin's floor when one was removed (the
  /// ground around a bin lies below it), else the largest plane; none when no plane was removed.
  std::optional<Eigen::Vector4f> resting_plane;
  std::size_t removed_points = 0; ///< valid points that were removed
};

/// Finds up to `params.max_planes` planes one after the other with RANSAC (PCL's plane model,
/// inlier distance `params.distance_mm`, sampled on at most 60k points for speed and then refined
/// by least squares and applied to every point) and removes each one that holds at least
/// `params.min_plane_fraction` of the scene's valid points; the search stops at the first plane
/// that is too small. Then, with `params.bin_floor_fraction` > 0, removes the floor of a bin
/// standing on the first plane (beyond the thesis): the plane parallel to it that holds at least
/// that fraction of the points and has at most 2 % of the remaining points behind it (which the
/// rim of the bin's walls and the parts' flat faces have: the floor lies behind them), fitted by
/// least squares to the points within 5 mm of that height. With `params.bin_walls`, in a scene
/// (no `part`) the bin's walls then go too: up to four planes parallel to the bin floor's normal
/// (RANSAC, inlier distance `params.distance_mm`), each with at most 2 % of the points above the
/// floor behind it but its rim (a part's face inside the bin has the bin's far side behind it),
/// with the points within `params.distance_mm` of it or behind it up to its rim; and the rim of a
/// wall whose face the scan does not see (the projector's shadow) across from each wall found.
/// `params.enabled == false` or `max_planes == 0` returns a copy.
/// `part` (empty, or one flag per point) marks the part an operator cropped to teach; the floors
/// removed are then the ones it rests on. A plane with more than 2 % of the valid points around
/// the part (along the plane, within 1.5 x the part's radius of its centre) farther than 3 x
/// `params.distance_mm` beyond it is a face of a part, not a floor (a large plate's top face can
/// outnumber the table around it; a room beyond the table's edge is not around the part): its
/// points are left out of the search and the plane is searched again, at most kFloorRetries times.
/// A bin floor is removed only when more of its points lie outside the part than in it: the top
/// face of a plate lying on a table, or of a flange, looks like a bin's floor but lies within the
/// part. Deterministic for a given `seed`. Throws Error for an inconsistent cloud or mask,
/// Cancelled when `progress` asks to stop.
FloorRemovalResult removeFloor(const PointCloud& scene_mm, const FloorParams& params,
                               std::uint64_t seed, const ProgressFn& progress = {},
                               const std::vector<char>& part = {});

/// How many planes removeFloor (with a part) may set aside as faces of parts.
inline constexpr int kFloorRetries = 3;

} // namespace scanpick::core
