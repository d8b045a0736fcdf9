#pragma once
/// @file ModelPrep.h
/// What the Recognizer prepares once per taught view and keeps while views alternate from scene
/// to scene (verification points, ICP model, surface pair table, axis of revolution, near
/// symmetries). The resolution of a detection's ambiguous rotations takes it
/// (AmbiguityResolution.h, which says why both live in core/ambiguity); the Recognizer
/// (core/pipeline) makes and caches it.

#include "core/ambiguity/NearSymmetry.h"
#include "core/matching/PointPairVoting.h"
#include "core/matching/RevolutionAxis.h"
#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/refine/RefineModel.h"
#include "core/refine/SurfaceEnds.h"
#include "core/verification/PoseVerification.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace scanpick::core::detail {

/// About this many of the whole part's points compare two of its poses (ModelPrep::joined_sample).
inline constexpr std::size_t kJoinedSamplePoints = 2000;
/// One pose of an instance is clearly better than another when the whole part scores this much
/// higher at it (wholePartScore): in the merge of views and among a view's duplicates.
inline constexpr double kPartScoreMargin = 0.05;

/// What a view's near symmetries were found with (findNearSymmetries' parameters).
struct SymmetryKey {
  double overlap = 0.0;
  double tolerance_mm = 0.0;
  RefineParams icp;
  bool operator==(const SymmetryKey&) const = default;
};

/// A model prepared for verification, refinement and surface voting.
struct ModelPrep {
  std::shared_ptr<const TaughtModel> model;
  int points = 0;              ///< refine.model_points it was prepared with
  double normal_radius_mm = 0; ///< keypoints.normal_radius_mm it was prepared with
  std::shared_ptr<const VerifyModel> verify;
  /// The axis about which the model is a surface of revolution, if it is one.
  std::optional<RevolutionAxis> axis;
  /// Otherwise, the axis about which it is one but for an asymmetric feature (a cup's handle), if
  /// it is so, and the asymmetric feature's points (indices into verify->points).
  std::optional<RevolutionAxis> near_axis;
  std::vector<std::uint32_t> near_axis_asymmetry;
  /// With `axis` or `near_axis`: the outer radius of the surface revolved about them (its
  /// asymmetric feature left out) and where its wall ends along the axis in the taught cloud
  /// (AxialEnds).
  double wall_radius_mm = 0;
  AxialEnds wall_ends;
  /// With views joined (TaughtModel::joined_views), the asymmetric feature as all of them saw it,
  /// in this view's frame, with this view's revolved surface (null otherwise): a cup's handle from
  /// every side, where this view alone saw it from one.
  std::shared_ptr<const VerifyModel> joined_asymmetry;
  /// With views joined, the rotationally symmetric surface as all of them saw it (their points on
  /// the surface this view revolves about its near axis, in this view's frame, with the revolved
  /// surface they make): a cup's mouth and its bottom, which a side view alone does not hold.
  /// Null otherwise.
  std::shared_ptr<const VerifyModel> joined_revolved_surface;
  /// Per near symmetry (`symmetries[k]`), the points of joined_revolved_surface it moves off that
  /// surface and those its inverse does (as NearSymmetry::differing and differing_inverse): a cup
  /// flipped end over end puts its bottom where its mouth was.
  struct RevolvedSurfaceDiffering {
    std::vector<std::uint32_t> differing, differing_inverse;
  };
  std::vector<RevolvedSurfaceDiffering> joined_revolved_surface_differing;
  std::shared_ptr<const RefineModel> refine; ///< when ICP or surface voting needs it
  /// With views joined and refinement on, the ICP model of all of them in this view's frame: the
  /// other views hold the surfaces that pin down what this one alone leaves loose (a plate seen
  /// face-on slides in its own plane).
  std::shared_ptr<const RefineModel> joined_refine;
  /// With views joined, the points of all of them in this view's frame (each view's with normals
  /// facing its own teach camera); null without joined views.
  std::shared_ptr<const VerifyModel> joined_points;
  /// About kJoinedSamplePoints of joined_points, evenly strided (indices): what compares two poses
  /// of the whole part (wholePartScore).
  std::vector<std::uint32_t> joined_sample;
  double surface_sampling_mm = 0;              ///< of `pairs`
  std::shared_ptr<const PointPairModel> pairs; ///< when surface voting is on
  /// Near symmetries, and what they were found with (unset when not searched).
  std::optional<SymmetryKey> symmetry_key;
  std::vector<NearSymmetry> symmetries;
};

/// Whether matching with these parameters uses a prepared model (verification or refinement).
bool needsModelPrep(const RecognitionParams& params);

/// The cached preparation of `model` for these parameters, made (and cached, replacing the
/// oldest of at most 8) when missing or lacking what the parameters need.
std::shared_ptr<const ModelPrep> prepareModel(std::vector<std::shared_ptr<const ModelPrep>>& preps,
                                              const std::shared_ptr<const TaughtModel>& model,
                                              const RecognitionParams& params);

} // namespace scanpick::core::detail
