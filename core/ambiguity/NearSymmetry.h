#pragma once
/// @file NearSymmetry.h
/// Near symmetries of a taught view (beyond the thesis, which names symmetric parts as a limit):
/// rotations that put most of the view back onto its own surface, such as a hook plate rotated 180°
/// about its normal, where only the lip and the stem differ. Two poses of the part related by such
/// a rotation verify almost equally well; only the points that differ can tell them apart.

#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/refine/RefineModel.h"
#include "core/verification/PoseVerification.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace scanpick::core {

/// One near symmetry S of a view (model frame → model frame): pose T and pose T·S of the part put
/// most of the view in the same place.
struct NearSymmetry {
  Eigen::Isometry3d S_model = Eigen::Isometry3d::Identity();
  /// Share of the view's points that S puts back on its surface (within the tolerance, normals
  /// agreeing within 60°), [0, 1], among those S leaves where the teach camera could see them
  /// (facing it, not behind the view's own surface): a tilted plate's near rim rotated to its far
  /// side, or a face rotated into the shadow of the part's own stem, is no difference.
  double overlap = 0.0;
  /// Points p of the view (indices into VerifyModel::points) that S moves clearly (3 x tolerance)
  /// off its surface where the teach camera would have seen them: where pose T·S puts material and
  /// pose T does not. Tested at pose T·S. Few or none: the view repeats itself under S.
  std::vector<std::uint32_t> differing;
  /// Points p that S⁻¹ moves clearly off the surface: where pose T puts material and pose T·S does
  /// not. Tested at pose T. (The same as `differing` for a 180° rotation.)
  std::vector<std::uint32_t> differing_inverse;
};

/// The view's near symmetries: the most voted poses of the view against itself (surface point
/// pair voting, PointPairVoting.h, with each point's own neighbourhood left out so that the
/// identity does not win every vote) that rotate it by 30° or more, each kept as voted or refined
/// by ICP (`icp`) onto the view itself, whichever overlaps more, when it puts at least
/// `min_overlap` of the view's points back on its surface (within `tolerance_mm`). `view` are the
/// verification points of `model`; `refine_model` is built from `model` with its teach camera as
/// the viewpoint, and its surface() is the surface the rotations are fitted to. With views joined
/// (TaughtModel::joined_views), a rotation within 5° of 180° is made an exact 180° rotation and
/// its axis placed where the outline of all the views' points maps onto itself: fitted onto
/// itself, a view leaves a plate's 180° rotation a degree or two and a millimetre or two off.
/// Deterministic. Empty when min_overlap <= 0.
std::vector<NearSymmetry> findNearSymmetries(const TaughtModel& model, const VerifyModel& view,
                                             const RefineModel& refine_model,
                                             const RefineParams& icp, double tolerance_mm,
                                             double min_overlap);

/// The fewest differing points (NearSymmetry::differing) that tell two poses apart: 2 % of the
/// view's `view_points`, and 8; a handful at the view's edges is noise.
std::size_t minDistinguishingPoints(std::size_t view_points);

/// Whether the view repeats itself under `symmetry`: too few points differ either way
/// (minDistinguishingPoints) for any scan to tell pose T from T·S.
bool repeatsItself(const NearSymmetry& symmetry, std::size_t view_points);

/// The share of the points `tally` looked at that the scan contradicts (sees clearly behind):
/// violations ÷ the points not hidden, in [0, 1]; NaN when fewer than `min_seen` are not hidden
/// (nothing to tell).
double contradictedShare(const PointTally& tally, std::size_t min_seen);

} // namespace scanpick::core
