#pragma once
/// @file ViewAmbiguities.h
/// What a taught view's own surface cannot pin, found once at teach from the view alone (and the
/// views joined to it): the rotation about an axis of revolution, the same but for an asymmetric
/// feature (a cup's handle), and near symmetries (a plate's half turn). Recognition reports these
/// on each detection (free_turn_axis, alternative_poses) where the scan does not tell them
/// (AmbiguityResolution.h); this is the same analysis (the view's ModelPrep), said before any
/// scan so that the operator knows what a detection of this view may leave open.

#include "core/ambiguity/ModelPrep.h"
#include "core/matching/RevolutionAxis.h"

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core {

/// A rotation S (model frame → model frame) under which a view nearly repeats itself.
struct ViewSymmetry {
  double angle_deg = 0.0;                             ///< (0, 180]
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();    ///< unit, model frame
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero(); ///< on the axis, nearest the model origin
  double overlap = 0.0;        ///< share of the view S puts back on its surface (NearSymmetry)
  double differing_share = 0;  ///< share of the view's points that S moves off its surface
  bool repeats_itself = false; ///< too few differ for any scan to tell (repeatsItself)
};

/// What the view's surface leaves open. Model frame (the teach camera's axes).
struct ViewAmbiguities {
  /// The view is a surface of revolution about this axis: no scan tells its rotation about it.
  std::optional<RevolutionAxis> revolution_axis;
  /// Or it is one but for an asymmetric feature of this share of its points, which a scan must
  /// show to tell the rotation about this axis.
  std::optional<RevolutionAxis> near_axis;
  double asymmetric_share = 0.0;
  /// Whether near symmetries were searched (matching.symmetry_overlap > 0 with verification), and
  /// those found, rotations about the axis above left out.
  bool symmetries_searched = false;
  double symmetry_overlap = 0.0; ///< the share a rotation must put back to be one
  std::vector<ViewSymmetry> symmetries;
};

/// The ambiguities of a prepared view.
ViewAmbiguities viewAmbiguities(const detail::ModelPrep& prep);

/// The ambiguities of `view`, prepared as recognition with `params` prepares it (its own
/// view_params folded in).
ViewAmbiguities analyzeViewAmbiguities(const std::shared_ptr<const TaughtModel>& view,
                                       const RecognitionParams& params);

/// Each ambiguity in a sentence for the operator, with what a detection reports for it; one
/// sentence saying the surface pins every rotation when there is none.
std::vector<std::string> describeAmbiguities(const ViewAmbiguities& ambiguities);

} // namespace scanpick::core
