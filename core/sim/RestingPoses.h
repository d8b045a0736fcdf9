#pragma once
/// @file RestingPoses.h
/// The sides a part comes to rest on when it is dropped onto a table: the faces of its convex hull
/// that hold its centre of mass, merged up to its symmetries, each with the probability that a
/// random drop ends on it (the simulator's physics, the same as buildScene's).

#include "core/common/Progress.h"
#include "core/sim/Part.h"

#include <cstdint>
#include <vector>

namespace scanpick::core {

/// One distinct way the part rests on a table.
struct RestingPose {
  /// Rotation of the part frame that puts the part on the table with this side down, in the
  /// convention of Part::R_table_part and teachSideTurn (a teach scene turns the part by
  /// yaw · R_table_part): the shortest turn from Part::R_table_part that points
  /// `down_normal_part` along -z (world), so the part's usual pose keeps Part::R_table_part.
  Eigen::Matrix3d R_table_part = Eigen::Matrix3d::Identity();
  /// Outward unit normal of the hull face the part stands on, part frame.
  Eigen::Vector3d down_normal_part = -Eigen::Vector3d::UnitZ();
  /// Share of the drops that ended on this side (or one of its symmetric copies), 0-1.
  double probability = 0;
  /// Area of the hull face (one copy), mm².
  double face_area_mm2 = 0;
  /// Hull faces this side stands for, itself included (>= 1): its copies under the part's
  /// symmetries and the faces merged with it (RestingPoseParams::same_side_deg).
  int symmetric_copies = 1;
};

/// How resting poses are found. The defaults are what `synth --resting-side` and
/// `scanpick-cli resting-sides` use.
struct RestingPoseParams {
  std::uint64_t seed = 0; ///< drives the drops' orientations: same part + same seed, same result
  int drops = 200;        ///< physics drops that estimate the probabilities (0 = none: all 0)
  /// Gap between the part's lowest point and the table when a drop starts, mm.
  double drop_height_mm = 10.0;
  /// Simulated time a drop may take to come to rest, s.
  double settle_time_s = 4.0;
  /// Hull faces whose normals differ by less than this are one face, degrees (tessellation and
  /// hull round-off split flat faces).
  double coplanar_tolerance_deg = 1.0;
  /// Stable faces whose outward normals differ by less than this, directly or through one of the
  /// part's symmetries, are one side, degrees: the camera sees the part from nearly the same
  /// direction on either (e.g. neighbouring facets of a tessellated rim the part rolls on).
  /// Merging is transitive, so a rim of such facets is one side.
  double same_side_deg = 12.0;
  /// A face is stable only if the centre of mass must tip by at least this angle before it
  /// passes over the face's nearest edge, degrees: knife-edge faces are not stable.
  double min_tip_angle_deg = 1.0;

  bool operator==(const RestingPoseParams&) const = default;
};

/// The part's stable hull faces, merged up to its symmetries (Part::symmetry) and into sides
/// (RestingPoseParams::same_side_deg), without drops:
/// probability 0 each, sorted by face area (largest first). The centre of mass is the one the
/// simulator's physics gives the part (Part::center_mm, uniform mass about the bounding-box
/// centre). Throws Error for a part without vertices or a flat one (no volume hull).
std::vector<RestingPose> stableRestingPoses(const Part& part, const RestingPoseParams& params = {});

/// stableRestingPoses with probabilities from `params.drops` drops (random orientation, seeded)
/// onto a table, each classified by the stable face whose outward normal points closest to
/// straight down when it has settled. Sorted by probability (highest first), then face area,
/// then normal. Deterministic for a given part and params. Throws Error for bad params (drops
/// outside 0-100000, heights or times out of range, angles outside 0-45°) or a part
/// stableRestingPoses refuses; progress covers the drops (Cancelled when it asks to stop).
std::vector<RestingPose> restingPoses(const Part& part, const RestingPoseParams& params = {},
                                      const ProgressFn& progress = {});

} // namespace scanpick::core
