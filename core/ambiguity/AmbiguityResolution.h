#pragma once
/// @file AmbiguityResolution.h
/// How the turns of a detection that matching cannot tell are resolved by the scan.
///
/// Module core/ambiguity (scanpick::core_ambiguity), symmetry and ambiguity resolution. Contract:
/// given a view prepared once (ModelPrep: its axis of revolution, or near axis and detail, its
/// near symmetries, NearSymmetry.h) and detections of it in a scan, each scored by the scan's
/// verification (core/verification), it decides the turns feature matching cannot tell: the turn
/// about a near axis that the detail (a cup's handle) shows, and which of a pose and its turn by a
/// near symmetry the scan rules out. Detections come back turned, or with the poses the scan
/// cannot tell apart as alternatives; their order and duplicates are the caller's.
/// The view's preparation (ModelPrep, prepareModel) lives here and not in core/pipeline: most of
/// what it holds is there to resolve these ambiguities and this module takes it, so with it in the
/// pipeline the two modules would depend on each other. The pipeline uses this module; it uses
/// verification, matching, refine, model and features, and nothing of the Recognizer.

#include "core/ambiguity/ModelPrep.h"
#include "core/common/Detection.h"
#include "core/matching/FeatureMatcher.h"
#include "core/params/Parameters.h"
#include "core/verification/PoseVerification.h"

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <vector>

namespace scanpick::core::detail {

/// Moves a pose closer to the scene (ICP).
using PosePolisher = std::function<Eigen::Isometry3d(const Eigen::Isometry3d&)>;

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
