#include "core/pipeline/DetectionSteps.h"

#include "core/common/Log.h"
#include "core/matching/FeatureMatcher.h"
#include "core/pipeline/Recognizer.h"
#include "core/refine/PoseRefinement.h"

#include <algorithm>
#include <chrono>
#include <tbb/parallel_for.h>

namespace scanpick::core::detail {
namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
} // namespace

bool keepsRefinedPose(double coverage_before, double coverage_after) {
  return coverage_after >= coverage_before - kIcpCoverageSlack;
}

void refineDetections(std::vector<Detection>& detections, const ModelPrep& prep,
                      const SceneIndex& scene_index, const RefineParams& params,
                      const PoseVerifier& verify) {
  tbb::parallel_for(std::size_t{0}, detections.size(), [&](std::size_t k) {
    Detection& d = detections[k];
    if (d.refined)
      return; // a surface-voting pose ICP has polished already
    const RefinementResult r = refinePose(prep.joined_refine ? *prep.joined_refine : *prep.refine,
                                          scene_index, d.T_scene_model, params);
    if (!verify) {
      d.T_scene_model = r.T_scene_model;
      d.refined = true;
      return;
    }
    const double coverage = verify(r.T_scene_model);
    logger()->trace("ICP of detection {}: coverage {:.3f} -> {:.3f}, moved {:.2f} mm, {} "
                    "iterations, converged {}",
                    k, d.coverage, coverage,
                    (r.T_scene_model.translation() - d.T_scene_model.translation()).norm(),
                    r.iterations, r.converged);
    if (keepsRefinedPose(d.coverage, coverage)) {
      // An alternative T·S becomes T'·S: the same move, taken in the scene frame.
      const Eigen::Isometry3d move = r.T_scene_model * d.T_scene_model.inverse();
      for (auto& T_alternative : d.alternative_poses)
        T_alternative = move * T_alternative;
      d.T_scene_model = r.T_scene_model;
      d.refined = true;
      d.coverage = coverage;
      d.score = coverage;
    }
  });
  sortBestFirst(detections);
}

void resolveDetectionTurns(std::vector<Detection>& detections, const ModelPrep& prep,
                           const VerifyScene& scene, const MatchingParams& params,
                           const PoseVerifier& verify, const PosePolisher& polish,
                           double min_distance_mm) {
  if (!verify)
    return;
  if (prep.near_axis) {
    const auto t0 = Clock::now();
    detail::resolveDetailTurns(detections, prep, scene, params, verify, polish);
    logger()->debug("the handle's turn of {} detections: {:.0f} ms", detections.size(),
                    msSince(t0));
  }
  if (!prep.symmetries.empty()) {
    detail::resolveNearSymmetries(detections, prep, scene, params, verify, polish);
    sortBestFirst(detections);
    detections = suppressDuplicates(std::move(detections), min_distance_mm);
  }
}

void placeDetections(std::vector<Detection>& detections, const TaughtModel& model,
                     const ModelPrep* prep, const VerifyScene* scene, double tolerance_mm) {
  // The turn about the view's axis is not seen at a pose where the view is a surface of
  // revolution, or one but for a detail that the scan does not confirm there.
  const auto freeTurnAt = [&](const Eigen::Isometry3d& T) -> std::optional<FreeTurnAxis> {
    if (!prep || !(prep->axis || (scene && prep->near_axis &&
                                  !detail::seesDetail(*prep, *scene, T, tolerance_mm))))
      return std::nullopt;
    const RevolutionAxis& axis = prep->axis ? *prep->axis : *prep->near_axis;
    return FreeTurnAxis{T * axis.point_mm, T.linear() * axis.direction};
  };
  // A view that is a surface of revolution but for a detail is placed by its axis: turned about it
  // by its detail, the view's own origin moves round the axis, the instance does not.
  const std::optional<RevolutionAxis> placing_axis =
      prep ? prep->near_axis : std::optional<RevolutionAxis>();
  for (auto& d : detections) {
    d.centre_mm = placing_axis ? d.T_scene_model * placing_axis->point_mm
                               : Eigen::Vector3d(d.T_scene_model.translation());
    d.grip_points_scene.clear();
    for (const auto& g : model.grip_points)
      d.grip_points_scene.push_back({g.name, d.T_scene_model * g.position_mm});
    d.free_turn_axis = freeTurnAt(d.T_scene_model);
    d.alternative_free_turn_axes.clear();
    for (const auto& T_alternative : d.alternative_poses)
      d.alternative_free_turn_axes.push_back(freeTurnAt(T_alternative));
    if (std::none_of(d.alternative_free_turn_axes.begin(), d.alternative_free_turn_axes.end(),
                     [](const auto& axis) { return axis.has_value(); }))
      d.alternative_free_turn_axes.clear();
  }
}

std::vector<Detection>
surfaceDetections(const PointPairModel& model_pairs, const OrientedPoints& scene_points,
                  const ScenePairs* scene_pairs, const FeatureList& model_features,
                  const std::vector<FeatureList>& object_features, const MatchingParams& params,
                  double cluster_mm, const PoseVerifier& verify, const PosePolisher& polish,
                  const PoseRescue& rescue, const ProgressFn& progress) {
  VotingOptions options;
  options.reference_stride = params.surface_reference_stride;
  options.max_poses = params.surface_poses;
  options.cluster_distance_mm = cluster_mm;
  const auto t0 = Clock::now();
  const std::vector<VotedPose> poses = scene_pairs
                                           ? model_pairs.vote(*scene_pairs, options, progress)
                                           : model_pairs.vote(scene_points, options, progress);
  logger()->debug("surface voting: {} model points ({} pairs, {:.1f} mm across), {} scene points "
                  "({}), {} poses, {:.0f} ms",
                  model_pairs.pointCount(), model_pairs.pairCount(), model_pairs.diameter(),
                  scene_points.points.size(), scene_pairs ? "paired before" : "paired now",
                  poses.size(), msSince(t0));
  FeatureList scene_features;
  for (const auto& f : object_features)
    scene_features.insert(scene_features.end(), f.begin(), f.end());
  std::vector<Eigen::Isometry3d> voted;
  for (const auto& pose : poses)
    voted.push_back(pose.T_scene_model);
  const std::vector<MatchCandidate> fits =
      refineOnFeatures(model_features, scene_features, voted, params);
  std::vector<Detection> out(poses.size());
  tbb::parallel_for(std::size_t{0}, poses.size(), [&](std::size_t k) {
    Detection& d = out[k];
    d.cluster = -1;
    d.T_scene_model = voted[k];
    d.coverage = verify(d.T_scene_model);
    const MatchCandidate& fitted = fits[k];
    d.feature_score = fitted.score;
    if (fitted.matched_features.size() >= 2) {
      const double coverage = verify(fitted.T_scene_model);
      if (coverage > d.coverage) {
        d.T_scene_model = fitted.T_scene_model;
        d.coverage = coverage;
        d.matched_features = fitted.matched_features;
      }
    }
    // ICP only where the surface already half agrees: it cannot rescue a wrong pose, and it is
    // the costly step.
    if (polish && d.coverage >= 0.5 * params.min_coverage) {
      const Eigen::Isometry3d T = polish(d.T_scene_model);
      const double coverage = verify(T);
      if (keepsRefinedPose(d.coverage, coverage)) {
        d.T_scene_model = T;
        d.coverage = coverage;
        d.refined = true;
      }
    }
    if (rescue && d.coverage < params.min_coverage && d.coverage >= 0.5 * params.min_coverage)
      rescue(d);
    d.score = d.coverage;
  });
  for (std::size_t k = 0; k < out.size(); ++k)
    logger()->trace("surface pose {}: {} votes at ({:.1f}, {:.1f}, {:.1f}) mm, coverage {:.3f}, {} "
                    "features{}",
                    k, poses[k].votes, out[k].T_scene_model.translation().x(),
                    out[k].T_scene_model.translation().y(), out[k].T_scene_model.translation().z(),
                    out[k].coverage, out[k].matched_features.size(), out[k].refined ? ", ICP" : "");
  std::erase_if(out, [&](const Detection& d) { return d.coverage < params.min_coverage; });
  sortBestFirst(out);
  logger()->debug("surface voting: {} poses verified and polished, {} kept, {:.0f} ms in all",
                  poses.size(), out.size(), msSince(t0));
  return out;
}

} // namespace scanpick::core::detail
