#include "core/pipeline/DetectionSteps.h"

#include "core/common/Log.h"
#include "core/matching/FeatureMatcher.h"
#include "core/pipeline/Recognizer.h"
#include "core/refine/PoseRefinement.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
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

namespace {

/// The scene's points within the view's diameter of `centre_mm` and, when `normals` is given,
/// their normals into it.
std::vector<Eigen::Vector3f> pointsNear(const ModelPrep& prep, const SceneIndex& scene,
                                        const Eigen::Vector3d& centre_mm,
                                        std::vector<Eigen::Vector3f>* normals = nullptr) {
  const auto reach_sq = static_cast<float>(prep.model->diameter_mm * prep.model->diameter_mm);
  const Eigen::Vector3f centre = centre_mm.cast<float>();
  std::vector<Eigen::Vector3f> near;
  for (std::size_t i = 0; i < scene.points().size(); ++i)
    if ((scene.points()[i] - centre).squaredNorm() <= reach_sq) {
      near.push_back(scene.points()[i]);
      if (normals)
        normals->push_back(scene.normals()[i]);
    }
  return near;
}

/// Largest slide along the axis (mm): ICP leaves a pose a few tenths of a millimetre off there; a
/// larger difference means an end is hidden.
constexpr double kMaxWallSlideMm = 2.0;
/// The two ends' slides must agree this closely (mm) for their mean to count.
constexpr double kMaxWallEndsDisagreementMm = 0.5;

/// `T_scene_model` slid along its view's axis to where the scan shows the ends of the view's wall
/// (ModelPrep::wall_ends); nothing when the view is no surface of revolution or the scan or the
/// view does not show its ends.
std::optional<Eigen::Isometry3d> slidToWallEnds(const ModelPrep& prep, const SceneIndex& scene,
                                                const Eigen::Isometry3d& T_scene_model) {
  if (!(prep.axis || prep.near_axis) || !(prep.wall_ends.low_mm || prep.wall_ends.high_mm))
    return std::nullopt;
  const RevolutionAxis& axis = prep.axis ? *prep.axis : *prep.near_axis;
  const Eigen::Vector3d point = T_scene_model * axis.point_mm;
  const Eigen::Vector3d direction = T_scene_model.linear() * axis.direction;
  const double far = std::numeric_limits<double>::infinity();
  const double low = prep.wall_ends.low_mm ? *prep.wall_ends.low_mm - kMaxWallSlideMm : -far;
  const double high = prep.wall_ends.high_mm ? *prep.wall_ends.high_mm + kMaxWallSlideMm : far;
  std::vector<Eigen::Vector3f> normals;
  const std::vector<Eigen::Vector3f> near = pointsNear(prep, scene, point, &normals);
  const AxialEnds ends = findAxialEnds(near, point, direction, prep.wall_radius_mm,
                                       scene.options().viewpoint_mm, low, high, {}, normals);
  const std::optional<double> shift =
      axialShift(prep.wall_ends, ends, kMaxWallSlideMm, kMaxWallEndsDisagreementMm);
  if (!shift)
    return std::nullopt;
  return Eigen::Translation3d(*shift * direction) * T_scene_model;
}

/// A scene point counts as on the part when the view has a point this close at the pose (mm).
constexpr double kOnPartMm = 1.5;
/// Directions (of translation) whose point-to-plane curvature is below this share of the strongest
/// are the ones ICP hardly pins. With the outline slide on, ICP itself holds its directions (of
/// its six) below this share as they came.
constexpr double kWeakRatio = 0.01;
/// Directions up to this share ICP pins, but loosely (a plate seen edge-on, along its length):
/// the outline moves a pose along them only when both of its sides agree within
/// kFirmAgreementMm.
constexpr double kLooseRatio = 0.1;
constexpr double kFirmAgreementMm = 0.1;

/// `T_scene_model` moved, along each direction ICP hardly pins (and each it pins loosely, where
/// both sides of the outline agree within kFirmAgreementMm), to where the scene's points end as the
/// view's do (outlineShift); nothing when no such direction or no end tells.
std::optional<Eigen::Isometry3d> slidToOutline(const ModelPrep& prep, const SceneIndex& scene,
                                               const Eigen::Isometry3d& T_scene_model) {
  if (!prep.refine)
    return std::nullopt;
  const RefineModel& model = *prep.refine;
  const Eigen::Isometry3d T_model_scene = T_scene_model.inverse();
  const Eigen::Vector3d camera_model = T_model_scene * scene.options().viewpoint_mm;
  // The translation block of point-to-plane ICP's normal matrix, over the confirmed visible points.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  const auto inlier_sq = static_cast<float>(kOnPartMm * kOnPartMm);
  for (std::size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3d p = model.points()[i].cast<double>();
    const Eigen::Vector3d n = model.normals()[i].cast<double>();
    if (n.dot(camera_model - p) <= 0 ||
        scene.nearest((T_scene_model * p).cast<float>(), inlier_sq) < 0)
      continue;
    A += n * n.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(A);
  const double strongest = eigen.eigenvalues()(2);
  if (!(strongest > 0))
    return std::nullopt;
  // The scene's points on the part, in the model frame.
  std::vector<Eigen::Vector3f> on_part;
  for (const auto& p : pointsNear(prep, scene, T_scene_model * Eigen::Vector3d::Zero())) {
    const Eigen::Vector3f q = (T_model_scene * p.cast<double>()).cast<float>();
    if (model.surface().nearest(q, inlier_sq) >= 0)
      on_part.push_back(q);
  }
  std::vector<const std::vector<Eigen::Vector3f>*> other_views;
  for (const JoinedView& view : prep.model->joined_views)
    other_views.push_back(&view.cloud_mm.points_mm);
  Eigen::Vector3d move_model = Eigen::Vector3d::Zero();
  bool moved = false;
  for (int k = 0; k < 2; ++k) {
    const double ratio = eigen.eigenvalues()(k) / strongest;
    if (ratio >= kLooseRatio)
      break;
    OutlineShiftOptions options;
    if (ratio >= kWeakRatio)
      options.max_disagreement_mm = kFirmAgreementMm;
    const Eigen::Vector3d direction = eigen.eigenvectors().col(k).normalized();
    if (const auto shift = outlineShift(prep.model->cloud_mm.points_mm, on_part, direction,
                                        other_views, options)) {
      move_model += *shift * direction;
      moved = true;
    }
  }
  if (!moved)
    return std::nullopt;
  return T_scene_model * Eigen::Translation3d(move_model);
}

/// Puts `d` at the refined pose `T_scene_model`, with its `coverage` as its score when given;
/// its alternatives T·S move with it to T'·S (the same move, taken in the scene frame).
void moveTo(Detection& d, const Eigen::Isometry3d& T_scene_model, std::optional<double> coverage) {
  const Eigen::Isometry3d move = T_scene_model * d.T_scene_model.inverse();
  for (auto& T_alternative : d.alternative_poses)
    T_alternative = move * T_alternative;
  d.T_scene_model = T_scene_model;
  d.refined = true;
  if (coverage) {
    d.coverage = *coverage;
    d.score = *coverage;
  }
}

/// An alternative pose refined as a pose of its own (the rotation that made it fits the view onto
/// itself only to a millimetre or two): ICP, and with `verify` also ICP with twice its final pair
/// distance and with the final distance itself (from that far off, pairs as far apart as the ICP
/// distance can hold a neighbour's surface and pull the pose away), the best verified pose taken
/// when it verifies as well as the start (keepsRefinedPose). Returns the pose and its score, when
/// verified.
std::pair<Eigen::Isometry3d, std::optional<double>>
refinedAlternative(const RefineModel& icp_model, const SceneIndex& scene_index,
                   const Eigen::Isometry3d& T_alternative, const RefineParams& params,
                   const PoseVerifier& verify) {
  Eigen::Isometry3d refined =
      refinePose(icp_model, scene_index, T_alternative, params).T_scene_model;
  if (!verify)
    return {refined, std::nullopt};
  const double before = verify(T_alternative);
  double after = verify(refined);
  for (const double distance_mm :
       {2.0 * params.min_correspondence_mm, params.min_correspondence_mm}) {
    if (!(distance_mm < params.max_correspondence_mm))
      continue;
    RefineParams narrow = params;
    narrow.max_correspondence_mm = distance_mm;
    const Eigen::Isometry3d T =
        refinePose(icp_model, scene_index, T_alternative, narrow).T_scene_model;
    if (const double score = verify(T); score > after) {
      after = score;
      refined = T;
    }
  }
  if (keepsRefinedPose(before, after))
    return {refined, after};
  return {T_alternative, before};
}

} // namespace

std::vector<Detection> refineDetections(std::vector<Detection> detections, const ModelPrep& prep,
                                        const SceneIndex& scene_index, const RefineParams& params,
                                        const PoseVerifier& verify) {
  const RefineModel& icp_model = prep.joined_refine ? *prep.joined_refine : *prep.refine;
  const bool revolution = prep.axis || prep.near_axis;
  // Where the outline places the directions ICP hardly pins, ICP leaves them as they came: on
  // them it drifts on the few points of edges and walls (a plate seen from below, started at its
  // true pose, ends up to 2 mm off along its length). Not for the alternative poses below: they
  // start a millimetre or two off, and ICP brings them nearer first.
  const double stable_share = !revolution && params.outline_ends ? kWeakRatio : kIcpStableShare;
  tbb::parallel_for(std::size_t{0}, detections.size(), [&](std::size_t k) {
    Detection& d = detections[k];
    std::optional<double> icp_coverage; // the ICP pose's score, when it was kept
    if (!d.refined) {                   // else a surface-voting pose ICP has refined already
      const RefinementResult r =
          refinePose(icp_model, scene_index, d.T_scene_model, params, {}, stable_share);
      const auto coverage = verify ? std::optional(verify(r.T_scene_model)) : std::nullopt;
      logger()->trace("ICP of detection {}: coverage {:.3f} -> {:.3f}, moved {:.2f} mm, {} "
                      "iterations, converged {}",
                      k, d.coverage, coverage.value_or(d.coverage),
                      (r.T_scene_model.translation() - d.T_scene_model.translation()).norm(),
                      r.iterations, r.converged);
      if (!coverage || keepsRefinedPose(d.coverage, *coverage)) {
        moveTo(d, r.T_scene_model, coverage);
        icp_coverage = coverage;
      }
    }
    // The slides are checked by this view's verification at both poses (the detection's score
    // may come from the views' merge), and the score stays: a slide is a fraction of a millimetre.
    // `verified`: T's score by this view's verification when it is known already.
    const auto slid = [&](const Eigen::Isometry3d& T,
                          std::optional<double> verified) -> std::optional<Eigen::Isometry3d> {
      std::optional<Eigen::Isometry3d> moved;
      if (revolution && params.axial_ends)
        moved = slidToWallEnds(prep, scene_index, T);
      else if (!revolution && params.outline_ends)
        moved = slidToOutline(prep, scene_index, T);
      if (!moved || (verify && !keepsRefinedPose(verified ? *verified : verify(T), verify(*moved))))
        return std::nullopt;
      logger()->trace("detection {} slid {:.3f} mm to where its surface ends", k,
                      (moved->translation() - T.translation()).norm());
      return moved;
    };
    if (const auto T = slid(d.T_scene_model, icp_coverage))
      moveTo(d, *T, std::nullopt);
    // Each alternative pose is refined as a pose of its own: the rotation that made it fits the
    // view onto itself only to a millimetre or two.
    for (auto& T_alternative : d.alternative_poses) {
      const auto [refined, verified] =
          refinedAlternative(icp_model, scene_index, T_alternative, params, verify);
      T_alternative = refined;
      if (const auto T = slid(T_alternative, verified))
        T_alternative = *T;
    }
  });
  sortBestFirst(detections);
  return detections;
}

std::vector<Detection> resolveDetectionAmbiguities(std::vector<Detection> detections,
                                                   const ModelPrep& prep, const VerifyScene& scene,
                                                   const MatchingParams& params,
                                                   const PoseVerifier& verify,
                                                   const PoseRefiner& refine,
                                                   double min_distance_mm) {
  if (!verify)
    return detections;
  if (prep.near_axis) {
    const auto t0 = Clock::now();
    detections =
        detail::resolveAxisRotations(std::move(detections), prep, scene, params, verify, refine);
    logger()->debug("the rotation about the axis of {} detections: {:.0f} ms", detections.size(),
                    msSince(t0));
  }
  if (!prep.symmetries.empty()) {
    detections =
        detail::resolveNearSymmetries(std::move(detections), prep, scene, params, verify, refine);
    sortBestFirst(detections);
    detections = suppressDuplicates(std::move(detections), min_distance_mm);
  }
  return detections;
}

std::vector<Detection> placeDetections(std::vector<Detection> detections, const TaughtModel& model,
                                       const ModelPrep* prep, const VerifyScene* scene,
                                       double tolerance_mm) {
  // The rotation about the view's axis is not seen at a pose where the view is a surface of
  // revolution, or one but for an asymmetric feature that the scan does not confirm there.
  const auto freeTurnAt = [&](const Eigen::Isometry3d& T) -> std::optional<FreeTurnAxis> {
    if (!prep || !(prep->axis || (scene && prep->near_axis &&
                                  !detail::seesAsymmetry(*prep, *scene, T, tolerance_mm))))
      return std::nullopt;
    const RevolutionAxis& axis = prep->axis ? *prep->axis : *prep->near_axis;
    return FreeTurnAxis{T * axis.point_mm, T.linear() * axis.direction};
  };
  // A view that is a surface of revolution but for an asymmetric feature is placed by its axis:
  // rotated about it by that feature, the view's own origin moves round the axis, the instance
  // does not.
  const std::optional<RevolutionAxis> placing_axis =
      prep ? prep->near_axis : std::optional<RevolutionAxis>();
  for (auto& d : detections) {
    d.centre_mm = placing_axis ? d.T_scene_model * placing_axis->point_mm
                               : Eigen::Vector3d(d.T_scene_model.translation());
    d.grip_points_scene.clear();
    for (const auto& g : model.grip_points)
      d.grip_points_scene.push_back(transformed(g, d.T_scene_model));
    d.free_turn_axis = freeTurnAt(d.T_scene_model);
    d.alternative_free_turn_axes.clear();
    for (const auto& T_alternative : d.alternative_poses)
      d.alternative_free_turn_axes.push_back(freeTurnAt(T_alternative));
    if (std::none_of(d.alternative_free_turn_axes.begin(), d.alternative_free_turn_axes.end(),
                     [](const auto& axis) { return axis.has_value(); }))
      d.alternative_free_turn_axes.clear();
  }
  return detections;
}

std::vector<Detection>
surfaceDetections(const PointPairModel& model_pairs, const OrientedPoints& scene_points,
                  const ScenePairs* scene_pairs, const FeatureList& model_features,
                  const std::vector<FeatureList>& object_features, const MatchingParams& params,
                  double cluster_mm, const PoseVerifier& verify, const PoseRefiner& refine,
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
    if (refine && d.coverage >= 0.5 * params.min_coverage) {
      const Eigen::Isometry3d T = refine(d.T_scene_model);
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
  logger()->debug("surface voting: {} poses verified and refined, {} kept, {:.0f} ms in all",
                  poses.size(), out.size(), msSince(t0));
  return out;
}

} // namespace scanpick::core::detail
