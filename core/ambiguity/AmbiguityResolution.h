#pragma once
/// @file AmbiguityResolution.h
/// How the rotations of a detection that matching cannot tell apart are resolved by the scan.
///
/// Module core/ambiguity (scanpick::core_ambiguity), symmetry and ambiguity resolution. Contract:
/// given a view prepared once (ModelPrep: its axis of revolution, or near axis and asymmetric
/// feature, its near symmetries, NearSymmetry.h) and detections of it in a scan, each scored by
/// the scan's hypothesis verification (core/verification), it decides the rotations feature
/// matching cannot tell apart: the rotation about a near axis that the asymmetric feature (a cup's
/// handle) shows, and which of a pose and its rotation by a near symmetry the scan rules out.
/// Detections come back rotated, or with the poses the scan cannot tell apart as alternatives;
/// their order and duplicates are the caller's.
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

/// Refines a pose locally against the scene (ICP).
using PoseRefiner = std::function<Eigen::Isometry3d(const Eigen::Isometry3d&)>;

/// Whether the scan confirms enough of the asymmetric feature of a view that is a surface of
/// revolution but for it (ModelPrep::near_axis_asymmetry) at `T_scene_model`: if not (the handle
/// of a cup is hidden or faces away), nothing in the scan tells the rotation about the axis.
bool seesAsymmetry(const ModelPrep& prep, const VerifyScene& scene,
                   const Eigen::Isometry3d& T_scene_model, double tolerance_mm);

/// A pose rotated about its view's near axis to where its asymmetric feature (a cup's handle) is
/// confirmed.
struct AxisRotation {
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  double coverage = 0.0;            ///< verification score of the rotated pose
  double asymmetry_confirmed = 0.0; ///< (confirmed − violations) ÷ asymmetric points, rotated
  double asymmetry_as_found = 0.0;  ///< the same before the rotation
  bool refined = false;             ///< ICP refined the rotated pose
};

/// The rotation about the view's near axis (1° steps, the asymmetric points alone) whose
/// asymmetric feature the scan confirms most, refined by ICP; nothing when the view has no near
/// axis, the best rotation confirms less than a quarter of the asymmetric feature or not a clear
/// share more than `T_scene_model`, or it verifies clearly worse than `coverage` (the pose's own
/// score). Failing that, with `ask_joined` and views joined, the rotation the joined asymmetric
/// feature says (ModelPrep::joined_asymmetry), which keeps `coverage` unless it verifies better.
std::optional<AxisRotation> rotationByAsymmetry(const ModelPrep& prep, const VerifyScene& scene,
                                                const MatchingParams& params,
                                                const PoseVerifier& verify,
                                                const PoseRefiner& refine,
                                                const Eigen::Isometry3d& T_scene_model,
                                                double coverage, bool ask_joined = true);

/// Puts `detection` at the rotated pose: its pose, coverage, score and refinement from
/// `rotation`; the features and alternatives of the pose it had no longer hold.
void applyRotation(Detection& detection, const AxisRotation& rotation);

/// For each detection of a view that is a surface of revolution but for an asymmetric feature (a
/// cup's handle), finds the rotation about the axis the asymmetric feature says: rotations of 1°
/// are tallied on the asymmetric points alone (the rest of the view lies on the same surface at
/// any rotation; only which of it the projector lit differs), and the detection takes the rotation
/// whose asymmetric feature the scan confirms most, when that confirms a clear share more than the
/// rotation found; `refine` (ICP) then finishes it.
std::vector<Detection> resolveAxisRotations(std::vector<Detection> detections,
                                            const ModelPrep& prep, const VerifyScene& scene,
                                            const MatchingParams& params,
                                            const PoseVerifier& verify, const PoseRefiner& refine);

/// For each detection and each near symmetry S of the view, tries the rotated pose T·S (refined
/// by ICP). The differing points decide: where one pose puts material and the other does not, the
/// scan looking through clearly more of one pose's points than of the other's rules it out (the
/// lip of a hook rotated 180° about its plate's normal floats where the scan sees the arm behind
/// it). Confirmed points tell less: both poses' differing points can lie near other surface of the
/// part. The detection takes the rotated pose when the scan rules its own out; when neither is
/// ruled out (the differing points are hidden or unseen) and the rotated pose verifies too, it is
/// reported as an alternative. With views joined (ModelPrep::joined_revolved_surface), the points
/// of their revolved surface that T and T·S place differently decide first, at any rotation about
/// the near axis: confirmed minus contradicted, slid along the near axis to where they fit best, a
/// clear share better rules the other pose out (a cup seen into its mouth is not the cup flipped
/// end over end, whose bottom the scan would see through). Failing that, a detection whose
/// asymmetric feature is confirmed at no rotation takes T·S when T·S's asymmetric feature is
/// confirmed. A symmetry under which the view repeats itself (too few differing points to tell)
/// always gives an alternative: T·S as it is.
std::vector<Detection> resolveNearSymmetries(std::vector<Detection> detections,
                                             const ModelPrep& prep, const VerifyScene& scene,
                                             const MatchingParams& params,
                                             const PoseVerifier& verify, const PoseRefiner& refine);

} // namespace scanpick::core::detail
