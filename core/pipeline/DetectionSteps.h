#pragma once
/// @file DetectionSteps.h
/// The steps the Recognizer takes with its detections once matching has found them: surface
/// voting's poses verified and refined, the rotations matching cannot tell apart resolved, ICP
/// refinement, and what each detection reports at its pose. Internal to the Recognizer
/// (core/pipeline/Recognizer.cpp), in its own file to keep that one small.

#include "core/ambiguity/AmbiguityResolution.h"
#include "core/common/Detection.h"
#include "core/features/Feature.h"
#include "core/matching/PointPairVoting.h"
#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/refine/SceneIndex.h"
#include "core/verification/PoseVerification.h"

#include <functional>
#include <vector>

namespace scanpick::core::detail {

/// A refined pose whose coverage is lower by less than this is still kept (keepsRefinedPose).
inline constexpr double kIcpCoverageSlack = 0.01;

/// Whether an ICP pose replaces the one it started from, by their verification scores: ICP can
/// slide a part seen edge-on along its extrusion, which loses much more; a better pose can lose
/// a point or two of the strided verification sample at the 1 mm edge. One rule for the surface
/// poses' refinement during matching and for refine.enabled.
bool keepsRefinedPose(double coverage_before, double coverage_after);

/// Refines each detection that ICP has not refined yet, with the view's joined ICP model when it
/// has one (ModelPrep::joined_refine), and keeps the refined pose when it verifies as well
/// (keepsRefinedPose; always without `verify`). Then slides each pose along the directions ICP
/// hardly pins to where the scan's surface ends (params.axial_ends for a surface of revolution,
/// params.outline_ends for other views; core/refine/SurfaceEnds.h), kept by the same rule, and
/// refines each alternative pose as a pose of its own in the same way (ICP also with narrower
/// pair distances, the best verified pose taken: an alternative starts a millimetre or two off).
/// Best first again.
std::vector<Detection> refineDetections(std::vector<Detection> detections, const ModelPrep& prep,
                                        const SceneIndex& scene_index, const RefineParams& params,
                                        const PoseVerifier& verify);

/// The rotations matching cannot tell apart (about a view's near axis, which its asymmetric
/// feature shows; its near symmetries) of `detections` (sorted best first, none of them within
/// `min_distance_mm` of a better one): resolved by the scan, best first again, duplicates the
/// rotations made dropped.
std::vector<Detection> resolveDetectionAmbiguities(std::vector<Detection> detections,
                                                   const ModelPrep& prep, const VerifyScene& scene,
                                                   const MatchingParams& params,
                                                   const PoseVerifier& verify,
                                                   const PoseRefiner& refine,
                                                   double min_distance_mm);

/// What each detection reports at its pose: its centre, its grip points in the scene frame and the
/// axes about which the scan does not see its rotation (Detection::free_turn_axis; `scene`: null
/// without verification).
std::vector<Detection> placeDetections(std::vector<Detection> detections, const TaughtModel& model,
                                       const ModelPrep* prep, const VerifyScene* scene,
                                       double tolerance_mm);

/// Another try for a pose that verified under the minimum but at least half of it: may replace
/// the detection's pose and coverage.
using PoseRescue = std::function<void(Detection&)>;

/// Surface voting's poses as detections (cluster -1), each refined into the version that
/// verifies best: as voted, fitted on the scene features it confirms, or (with `refine`, ICP)
/// refined, or else `rescue`d; kept when the coverage reaches params.min_coverage. Best first.
std::vector<Detection>
surfaceDetections(const PointPairModel& model_pairs, const OrientedPoints& scene_points,
                  const ScenePairs* scene_pairs, const FeatureList& model_features,
                  const std::vector<FeatureList>& object_features, const MatchingParams& params,
                  double cluster_mm, const PoseVerifier& verify, const PoseRefiner& refine,
                  const PoseRescue& rescue, const ProgressFn& progress);

} // namespace scanpick::core::detail
