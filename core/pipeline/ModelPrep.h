#pragma once
/// @file ModelPrep.h
/// What the Recognizer prepares once per taught view and keeps while views alternate from scene
/// to scene (verification points, ICP model, surface pair table, axis of revolution, near
/// symmetries), and how a detection's near symmetries are then resolved. Internal to the
/// Recognizer (core/pipeline/Recognizer.cpp), in its own file to keep that one small.

#include "core/matching/FeatureMatcher.h"
#include "core/matching/PointPairVoting.h"
#include "core/matching/RevolutionAxis.h"
#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/pipeline/Detection.h"
#include "core/pipeline/NearSymmetry.h"
#include "core/pipeline/PoseVerification.h"
#include "core/refine/RefineModel.h"
#include "core/refine/SurfaceEnds.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace scanpick::core::detail {

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
  /// Otherwise, the axis about which it is one but for a detail (a cup's handle), if it is so,
  /// and the detail's points (indices into verify->points).
  std::optional<RevolutionAxis> near_axis;
  std::vector<std::uint32_t> near_axis_detail;
  /// With `axis` or `near_axis`: the outer radius of the surface they turn (its detail left out)
  /// and where its wall ends along the axis in the taught cloud (AxialEnds).
  double wall_radius_mm = 0;
  AxialEnds wall_ends;
  /// With views joined (TaughtModel::joined_views), the detail as all of them saw it, in this
  /// view's frame, with this view's body (null otherwise): a cup's handle from every side, where
  /// this view alone saw it from one.
  std::shared_ptr<const VerifyModel> joined_detail;
  /// With views joined, the body as all of them saw it (their points on the surface this view
  /// turns about its near axis, in this view's frame, with the body they make turned about it):
  /// a cup's mouth and its bottom, which a side view alone does not hold. Null otherwise.
  std::shared_ptr<const VerifyModel> joined_body;
  /// Per near symmetry (`symmetries[k]`), the points of joined_body it moves off that body and
  /// those its inverse does (as NearSymmetry::differing and differing_inverse): a cup turned end
  /// over end puts its bottom where its mouth was.
  struct BodyDiffering {
    std::vector<std::uint32_t> differing, differing_inverse;
  };
  std::vector<BodyDiffering> joined_body_differing;
  std::shared_ptr<const RefineModel> refine; ///< when ICP or surface voting needs it
  /// With views joined and refinement on, the ICP model of all of them in this view's frame: the
  /// other views hold the surfaces that pin down what this one alone leaves loose (a plate seen
  /// face-on slides in its own plane).
  std::shared_ptr<const RefineModel> joined_refine;
  /// With views joined, the points of all of them in this view's frame (each view's with normals
  /// facing its own teach camera); null without joined views.
  std::shared_ptr<const VerifyModel> joined_points;
  double surface_sampling_mm = 0;              ///< of `pairs`
  std::shared_ptr<const PointPairModel> pairs; ///< when surface voting is on
  /// Near symmetries, and what they were found with (unset when not searched).
  std::optional<SymmetryKey> symmetry_key;
  std::vector<NearSymmetry> symmetries;
};

/// Moves a pose closer to the scene (ICP).
using PosePolisher = std::function<Eigen::Isometry3d(const Eigen::Isometry3d&)>;

/// Whether matching with these parameters uses a prepared model (verification or refinement).
bool needsModelPrep(const RecognitionParams& params);

/// The cached preparation of `model` for these parameters, made (and cached, replacing the
/// oldest of at most 8) when missing or lacking what the parameters need.
std::shared_ptr<const ModelPrep> prepareModel(std::vector<std::shared_ptr<const ModelPrep>>& preps,
                                              const std::shared_ptr<const TaughtModel>& model,
                                              const RecognitionParams& params);

/// Whether the scan confirms enough of the detail of a view that is a surface of revolution but
/// for it (ModelPrep::near_axis_detail) at `T_scene_model`: if not (the handle of a cup is hidden
/// or turned away), nothing in the scan tells the turn about the axis.
bool seesDetail(const ModelPrep& prep, const VerifyScene& scene,
                const Eigen::Isometry3d& T_scene_model, double tolerance_mm);

/// A pose turned about its view's near axis to where its detail (a cup's handle) is confirmed.
struct DetailTurn {
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  double coverage = 0.0;         ///< verification score of the turned pose
  double detail_confirmed = 0.0; ///< (confirmed − violations) ÷ detail points, turned
  double detail_as_found = 0.0;  ///< the same before the turn
  bool refined = false;          ///< ICP polished the turned pose
};

/// The turn about the view's near axis (1° steps, the detail's points alone) whose detail the scan
/// confirms most, polished by ICP; nothing when the view has no near axis, the best turn confirms
/// less than a quarter of the detail or not a clear share more than `T_scene_model`, or it
/// verifies clearly worse than `coverage` (the pose's own score). Failing that, with `ask_joined`
/// and views joined, the turn the joined detail says (ModelPrep::joined_detail), which keeps
/// `coverage` unless it verifies better.
std::optional<DetailTurn> turnByDetail(const ModelPrep& prep, const VerifyScene& scene,
                                       const MatchingParams& params, const PoseVerifier& verify,
                                       const PosePolisher& polish,
                                       const Eigen::Isometry3d& T_scene_model, double coverage,
                                       bool ask_joined = true);

/// Puts `detection` at the turned pose: its pose, coverage, score and polish from `turn`; the
/// features and alternatives of the pose it had no longer hold.
void takeTurn(Detection& detection, const DetailTurn& turn);

/// For each detection of a view that is a surface of revolution but for a detail (a cup's handle),
/// finds the turn about the axis the detail says: turns of 1° are tallied on the detail's points
/// alone (the rest of the view lies on the same surface at any turn; only which of it the
/// projector lit differs), and the detection takes the turn whose detail the scan confirms most,
/// when that confirms a clear share more than the turn found; `polish` (ICP) then finishes it.
std::vector<Detection> resolveDetailTurns(std::vector<Detection> detections, const ModelPrep& prep,
                                          const VerifyScene& scene, const MatchingParams& params,
                                          const PoseVerifier& verify, const PosePolisher& polish);

/// For each detection and each near symmetry S of the view, tries the turned pose T·S (polished by
/// ICP). The differing points decide: where one pose puts material and the other does not, the
/// scan looking through clearly more of one pose's points than of the other's rules it out (the
/// lip of a hook turned 180° about its plate's normal floats where the scan sees the arm behind
/// it). Confirmed points tell less: both poses' differing points can lie near other surface of the
/// part. The detection takes the turned pose when the scan rules its own out; when neither is
/// ruled out (the differing points are hidden or unseen) and the turned pose verifies too, it is
/// reported as an alternative. With views joined (ModelPrep::joined_body), the points of their
/// body that T and T·S place differently decide first, at any turn of a detail: confirmed minus
/// contradicted, slid along the near axis to where they fit best, a clear share better rules the
/// other pose out (a cup seen into its mouth is not the cup turned end over end, whose bottom the
/// scan would see through). Failing that, a detection whose detail is confirmed at no turn takes
/// T·S when T·S's detail is confirmed. A symmetry under which the view repeats itself (too few
/// differing points to tell) always gives an alternative: T·S as it is.
std::vector<Detection> resolveNearSymmetries(std::vector<Detection> detections,
                                             const ModelPrep& prep, const VerifyScene& scene,
                                             const MatchingParams& params,
                                             const PoseVerifier& verify,
                                             const PosePolisher& polish);

} // namespace scanpick::core::detail
