#pragma once
/// @file FeatureMatcher.h
/// Feature matching, thesis §3.4 (Algorithm 8): pairs of model features (M1, M2) are matched to
/// pairs of scene features (T1, T2) by predicting T2 from the M1→T1 alignment and searching the
/// roll about T1's axis (the toroid of Figure 3.5); the transform of the best-scoring pair is the
/// pose of the part.
///
/// Beyond the thesis (each documented where it is done):
/// - the toroid is tested exactly: for each scene feature in the spherical shell |T2 − T1| ≈
///   |M2 − M1| (found by binary search on a per-T1 distance table) the roll that brings the
///   predicted position onto it is solved in closed form, so no candidate falls between two roll
///   steps. `roll_step_deg` is the roll resolution: hypotheses of one (M1, T1) whose rolls fall in
///   the same roll_step_deg bin are scored once (the closest T2 wins), which bounds the work;
/// - an M2 that is parallel to M1 and lies on M1's axis constrains no roll and is skipped (the
///   thesis's two-parallel-lines ambiguity);
/// - the transform is a least-squares fit over the two pairs (RigidFit.h), and the winner is
///   refined on all its confirmed pairs (Umeyama, then a Gauss-Newton fit in which a line's
///   position along itself, which occlusion moves, hardly counts: refineOnFeatureGeometry);
/// - a scene feature confirms at most one model feature when scoring;
/// - the outer loop over M1 runs in parallel (TBB); ties are broken by (M1, T1, sign, roll bin)
///   order, so results never depend on scheduling.

#include "core/common/Progress.h"
#include "core/features/Feature.h"
#include "core/params/Parameters.h"

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace scanpick::core {

/// One pose hypothesis of the model in a scene (cluster).
struct MatchCandidate {
  /// Maps model coordinates into scene coordinates (mm).
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  /// Confirmed model features ÷ model features, in [0, 1] (the thesis's score).
  double score = 0.0;
  /// Mean distance (mm) between transformed model centres and their confirming scene centres.
  double residual_mm = 0.0;
  /// Confirmed (model feature index, scene feature index) pairs, by model index.
  std::vector<std::pair<int, int>> matched_features;
  /// The seed pairs (M1, T1) and (M2, T2) that produced the hypothesis.
  std::pair<int, int> seed1{-1, -1}, seed2{-1, -1};
  /// Point-level verification of the pose (PoseVerifier), or -1 when not verified.
  double coverage = -1.0;
};

/// Point-level check of a pose beyond the thesis: returns a quality in [0, 1] (e.g. the share
/// of visible model points confirmed by scene points). Must be thread-safe and deterministic.
using PoseVerifier = std::function<double(const Eigen::Isometry3d& T_scene_model)>;

/// Scores `T_scene_model`: each model feature (in index order) is moved into the scene and
/// confirmed by the closest still unused scene feature of the same type whose centre is within
/// Δp, size within Δl and axis within Δo. `scene_available` (empty = all) masks out scene features
/// already taken by another instance.
MatchCandidate scoreTransformation(const FeatureList& model, const FeatureList& scene,
                                   const Eigen::Isometry3d& T_scene_model,
                                   const MatchingParams& params,
                                   const std::vector<char>& scene_available = {});

/// Scores each pose of `T_scene_model` as scoreTransformation does and, with two or more
/// confirmed pairs, refines it on them as the search refines its winners (poses found otherwise,
/// e.g. by surface voting, then get the accuracy of the feature fit). The scene is indexed once
/// for all poses, which are handled in parallel. Returns the scored (refined) candidates, in order.
std::vector<MatchCandidate> refineOnFeatures(const FeatureList& model, const FeatureList& scene,
                                             const std::vector<Eigen::Isometry3d>& T_scene_model,
                                             const MatchingParams& params);

/// Algorithm 8 on one scene (cluster): the best-scoring transform, refined on its confirmed pairs,
/// or nullopt when no pair of pairs matches (fewer than two model or scene features, or no
/// compatible descriptors). No score threshold is applied here. Deterministic.
/// With `verify` and `params.hypotheses` > 1 (beyond the thesis), up to that many distinct poses
/// confirming at least (best count − 1) features are kept, each refined and verified, and the
/// best verified one wins (ties: more features, then search order); its `coverage` is set.
/// Throws Cancelled when `progress` asks to stop.
std::optional<MatchCandidate>
findBestTransformation(const FeatureList& model, const FeatureList& scene,
                       const MatchingParams& params, const std::vector<char>& scene_available = {},
                       const ProgressFn& progress = {}, const PoseVerifier& verify = {});

/// Multi-instance matching on one cluster (k-means may merge touching parts): takes the best
/// candidate, removes its confirmed scene features, and searches again, up to
/// `params.max_instances_per_cluster` times while the score reaches `params.score_threshold`.
/// With `verify` (beyond the thesis), candidates whose coverage is below `params.min_coverage`
/// are not returned (their features are still used up). Returns the accepted candidates, best
/// first (by coverage when verified, else by score).
std::vector<MatchCandidate> matchFeatures(const FeatureList& model, const FeatureList& scene,
                                          const MatchingParams& params,
                                          const ProgressFn& progress = {},
                                          const PoseVerifier& verify = {});

} // namespace scanpick::core
