/// @file Recognizer.cpp
/// Recognition as a chain of stages: the scene analysed (SceneAnalysis.cpp), the model prepared
/// (ModelPrep.h), then per view feature matching and surface voting into verified detections,
/// duplicates suppressed, ambiguous rotations resolved, refined and placed (DetectionSteps.h).

#include "core/pipeline/Recognizer.h"

#include "core/ambiguity/AmbiguityResolution.h"
#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/common/ParallelProgress.h"
#include "core/matching/FeatureMatcher.h"
#include "core/matching/PointPairVoting.h"
#include "core/pipeline/DetectionSteps.h"
#include "core/pipeline/ProgressShares.h"
#include "core/pipeline/StageMemo.h"
#include "core/refine/PoseRefinement.h"
#include "core/verification/PoseVerification.h"

#include <algorithm>
#include <chrono>
#include <limits>

namespace scanpick::core {
namespace {

using detail::kIcpCoverageSlack;
using detail::kPartScoreMargin;
using detail::ModelPrep;
using detail::placeDetections;
using detail::PoseRefiner;
using detail::PoseRescue;
using detail::refineDetections;
using detail::resolveDetectionAmbiguities;
using detail::StageMemo;
using detail::surfaceDetections;

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void requireModel(const std::shared_ptr<const TaughtModel>& model, const char* action) {
  if (!model)
    throw Error(std::string("no model to ") + action +
                ": teach a part or open a .spmodel file first");
}

/// `scene` with its index for verification and ICP made when the analysis did not need one.
SceneAnalysis withIndex(const SceneAnalysis& scene, const RecognitionParams& params) {
  SceneAnalysis out = scene;
  if (!out.index) {
    SceneIndexOptions options;
    options.normal_radius_mm = params.keypoints.normal_radius_mm;
    options.sensor = scene.sensor;
    out.index = std::make_shared<const SceneIndex>(*scene.preprocessed, options);
  }
  return out;
}

/// A view of a part in one analysed scene: its preparation and how its poses are verified and
/// refined there. Refers into the analysis and the parameters it is made with, which must outlive
/// it and the verifiers and refiners it hands out.
struct ViewInScene {
  const TaughtModel& model;
  std::shared_ptr<const ModelPrep> prep; ///< null: the parameters need no preparation
  const RecognitionParams& params;       ///< the view's (TaughtModel::view_params applied)
  VerifyScene scene;
  EdgeCheck edges;

  ViewInScene(const TaughtModel& m, std::shared_ptr<const ModelPrep> p,
              const RecognitionParams& view_params, const SceneAnalysis& analysis)
      : model(m), prep(std::move(p)), params(view_params),
        scene(analysis.verifyScene()), edges{analysis.edge_keypoints.get(),
                                             view_params.matching.edge_tolerance_mm} {}

  [[nodiscard]] bool verifying() const { return params.matching.verify_tolerance_mm > 0 && prep; }
  /// Point-level verification; a search that drops every pose scoring under `drop_below` may skip
  /// those poses' edge check (verifyPose). Empty without verification.
  [[nodiscard]] PoseVerifier verifier(double drop_below = 0.0) const {
    if (!verifying())
      return {};
    return [this, drop_below](const Eigen::Isometry3d& T) {
      return verifyPose(*prep->verify, scene, T, params.matching.verify_tolerance_mm, edges,
                        drop_below);
    };
  }
  /// ICP where the view was prepared for it, else the pose unchanged; empty without preparation.
  [[nodiscard]] PoseRefiner refiner() const {
    if (!prep)
      return {};
    return [this](const Eigen::Isometry3d& T) {
      return prep->refine ? refinePose(*prep->refine, *scene.index, T, params.refine).T_scene_model
                          : T;
    };
  }
};

/// Feature matching (Algorithm 8) of the view in each object of the scene: one detection per
/// candidate, scored by its coverage with verification, else by its feature score (progress:
/// kProgressShares.feature_matching).
std::vector<Detection> featureDetections(const ViewInScene& view, const SceneAnalysis& scene,
                                         const PoseVerifier& verify, const ProgressFn& progress) {
  const MatchingParams& matching = view.params.matching;
  // The pooled search keeps the poses reaching the minimum coverage, and nothing else of them.
  const PoseVerifier verify_pooled =
      matching.pool_size > 0 ? view.verifier(matching.min_coverage) : verify;
  const std::vector<FeatureList>& features = *scene.features;
  const auto t0 = Clock::now();
  std::vector<std::vector<MatchCandidate>> candidates(features.size());
  parallelForWithProgress(
      features.size(), subProgress(progress, kProgressShares.feature_matching), [&](std::size_t i) {
        candidates[i] =
            matchFeatures(view.model.features, features[i], matching, {}, verify_pooled);
      });
  logger()->debug("feature matching: {} model features, {:.0f} ms", view.model.features.size(),
                  msSince(t0));
  std::vector<Detection> out;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    for (const auto& c : candidates[i]) {
      Detection d;
      d.T_scene_model = c.T_scene_model;
      d.feature_score = c.score;
      d.coverage = c.coverage;
      d.score = verify ? c.coverage : c.score;
      d.matched_features = c.matched_features;
      d.cluster = static_cast<int>(i);
      out.push_back(std::move(d));
    }
  return out;
}

/// For a view that is a surface of revolution but for an asymmetric feature: a pose found rotated
/// about its axis, its asymmetric feature (a cup's handle) where the scan has none, takes the
/// rotation that feature says when that verifies. (Its own asymmetric feature only: a rotation the
/// joined one says keeps the coverage the pose was found with.) Empty otherwise.
PoseRescue asymmetryRescue(const ViewInScene& view, const PoseVerifier& verify,
                           const PoseRefiner& refine) {
  if (!verify || !view.prep->near_axis)
    return {};
  return [&view, &verify, &refine](Detection& d) {
    const auto rotation =
        detail::rotationByAsymmetry(*view.prep, view.scene, view.params.matching, verify, refine,
                                    d.T_scene_model, d.coverage, false);
    if (rotation && rotation->coverage > d.coverage)
      detail::applyRotation(d, *rotation);
  };
}

/// Surface point pair voting of the view over the whole sampled scene (progress:
/// kProgressShares.surface_voting). A voted pose under half the minimum coverage is neither
/// refined nor rescued, and ICP's pose replaces it only within kIcpCoverageSlack: under that, its
/// score only has to stay under.
std::vector<Detection> votedDetections(const ViewInScene& view, const SceneAnalysis& scene,
                                       const OrientedPoints& sampled, const ScenePairs* pairs,
                                       const PoseRefiner& refine, const PoseRescue& rescue,
                                       const ProgressFn& progress) {
  const MatchingParams& matching = view.params.matching;
  const PoseVerifier verify_voted = view.verifier(0.5 * matching.min_coverage - kIcpCoverageSlack);
  return surfaceDetections(*view.prep->pairs, sampled, pairs, view.model.features, *scene.features,
                           matching, kVoteClusterShare * view.model.diameter_mm, verify_voted,
                           refine, rescue, subProgress(progress, kProgressShares.surface_voting));
}

/// What surface voting needs of the scene for one view: the scene sampled and paired (the memo's,
/// shared with the other views that vote alike), or nothing when the view does not vote.
struct VotingScene {
  std::shared_ptr<const OrientedPoints> sampled;
  std::shared_ptr<const ScenePairs> pairs; ///< null: the view pairs as it votes
};

/// The memo's scene (analyzeScene has run on it) sampled and paired for the view of `prep`.
VotingScene votingScene(StageMemo& memo, const ModelPrep& prep, const RecognitionParams& params,
                        const ProgressFn& progress) {
  const PointPairModel& view = *prep.pairs;
  PairKeySet keys;
  keys.add(view);
  VotingScene out;
  out.pairs = memo.pairScene(*memo.pre_key, params.matching.surface_sampling_mm,
                             std::max(1, params.matching.surface_reference_stride),
                             view.quantizer(), view.diameter(), std::move(keys), false,
                             subProgress(progress, kProgressShares.scene_pairing));
  out.sampled = memo.surface_scene;
  return out;
}

/// With views joined, which of two poses of one instance the view found, verified alike (within
/// kSameInstanceTie), the whole part bears out better (wholePartScore, clearly: kPartScoreMargin):
/// the view's own points may verify a pose that puts the part's other sides into the floor or
/// where the scan sees none of them as well as the right one. Only ties are asked: a bin is full of
/// surface facing the camera, on which a pose clearly worse on the view's own points can still
/// score well on the whole part. Empty without joined views or verification.
SameInstanceArbiter wholePartArbiter(const ViewInScene& view) {
  if (!view.verifying() || !view.prep->joined_points)
    return {};
  auto scored = std::make_shared<std::vector<std::pair<Eigen::Matrix4d, double>>>();
  return [&view, scored](const Detection& kept, const Detection& candidate) {
    const auto score = [&](const Eigen::Isometry3d& T) {
      for (const auto& [pose, s] : *scored)
        if (pose == T.matrix())
          return s;
      const double s =
          wholePartScore(*view.prep->joined_points, view.scene, T,
                         view.params.matching.verify_tolerance_mm, &view.prep->joined_sample);
      scored->emplace_back(T.matrix(), s);
      return s;
    };
    return kept.score - candidate.score <= kSameInstanceTie &&
           score(candidate.T_scene_model) > score(kept.T_scene_model) + kPartScoreMargin;
  };
}

/// The detections of the view in the scene: feature matching and surface voting, best first,
/// duplicates suppressed (the pose the whole part bears out better kept, wholePartArbiter), the
/// rotations matching cannot tell apart resolved when `resolve_ambiguities`, at most
/// params.matching.max_detections, refined when params.refine.enabled, and placed (centres, grip
/// points, free rotation axes). Adds the matching and refinement times to `timings`.
std::vector<Detection> findDetections(const ViewInScene& view, const SceneAnalysis& scene,
                                      const VotingScene& voting, bool resolve_ambiguities,
                                      const ProgressFn& progress, StageTimings& timings) {
  const auto t_match = Clock::now();
  const PoseVerifier verify = view.verifier();
  std::vector<Detection> detections = featureDetections(view, scene, verify, progress);
  // ICP where the model was prepared for it (refinement, surface voting, near symmetries).
  const PoseRefiner refine = view.refiner();
  if (voting.sampled) {
    const PoseRescue rescue = asymmetryRescue(view, verify, refine);
    for (auto& d : votedDetections(view, scene, *voting.sampled, voting.pairs.get(), refine, rescue,
                                   progress))
      detections.push_back(std::move(d));
  }
  sortBestFirst(detections);
  const double duplicate_mm = kDuplicateShare * view.model.diameter_mm;
  detections = suppressDuplicates(std::move(detections), duplicate_mm, wholePartArbiter(view));
  const MatchingParams& matching = view.params.matching;
  if (resolve_ambiguities && view.prep)
    detections = resolveDetectionAmbiguities(std::move(detections), *view.prep, view.scene,
                                             matching, verify, refine, duplicate_mm);
  if (matching.max_detections > 0 &&
      detections.size() > static_cast<std::size_t>(matching.max_detections))
    detections.resize(static_cast<std::size_t>(matching.max_detections));
  timings.matching_ms += msSince(t_match);
  if (view.params.refine.enabled && view.prep) {
    const auto t0 = Clock::now();
    detections = refineDetections(std::move(detections), *view.prep, *scene.index,
                                  view.params.refine, verify);
    timings.refine_ms = msSince(t0);
  }
  return placeDetections(std::move(detections), view.model, view.prep.get(),
                         verify ? &view.scene : nullptr, matching.verify_tolerance_mm);
}

} // namespace

void Recognizer::setModel(std::shared_ptr<const TaughtModel> model) {
  const std::lock_guard lock(m_mutex);
  m_model = std::move(model);
}

std::shared_ptr<const TaughtModel> Recognizer::model() const {
  const std::lock_guard lock(m_mutex);
  return m_model;
}

detail::StageMemo Recognizer::memoSnapshot() const {
  const std::lock_guard lock(m_mutex);
  return m_memo ? *m_memo : StageMemo{};
}

void Recognizer::storePreparations(const StageMemo& memo) {
  // Only the preparations go back: a recognition running meanwhile may have memoized scene stages.
  const std::lock_guard lock(m_mutex);
  m_memo = std::make_shared<StageMemo>(m_memo ? *m_memo : StageMemo{});
  m_memo->model_preps = memo.model_preps;
}

std::shared_ptr<const detail::ModelPrep>
Recognizer::prepared(const std::shared_ptr<const TaughtModel>& model,
                     const RecognitionParams& params) {
  StageMemo memo = memoSnapshot();
  auto prep = detail::prepareModel(memo.model_preps, model, params);
  storePreparations(memo);
  return prep;
}

void Recognizer::prepare(const RecognitionParams& requested) {
  prepare(model(), requested);
}

void Recognizer::prepare(const std::shared_ptr<const TaughtModel>& model,
                         const RecognitionParams& requested) {
  requireModel(model, "prepare");
  const RecognitionParams params = withViewParams(requested, model->view_params);
  if (detail::needsModelPrep(params))
    (void)prepared(model, params);
}

std::size_t Recognizer::preparedModels() const {
  const std::lock_guard lock(m_mutex);
  return m_memo ? m_memo->model_preps.size() : 0;
}

RecognitionResult Recognizer::recognize(const PointCloud& scene_mm, const SensorModel& sensor,
                                        const RecognitionParams& requested,
                                        const ProgressFn& progress) {
  return recognize(model(), scene_mm, sensor, requested, progress);
}

RecognitionResult Recognizer::recognize(const std::shared_ptr<const TaughtModel>& model,
                                        const PointCloud& scene_mm, const SensorModel& sensor,
                                        const RecognitionParams& requested,
                                        const ProgressFn& progress) {
  return run(model, scene_mm, sensor, requested, progress, true);
}

RecognitionResult Recognizer::detect(const std::shared_ptr<const TaughtModel>& model,
                                     const PointCloud& scene_mm, const SensorModel& sensor,
                                     const RecognitionParams& requested,
                                     const ProgressFn& progress) {
  return run(model, scene_mm, sensor, requested, progress, false);
}

RecognitionResult Recognizer::run(const std::shared_ptr<const TaughtModel>& model,
                                  const PointCloud& scene_mm, const SensorModel& sensor,
                                  const RecognitionParams& requested, const ProgressFn& progress,
                                  bool resolve_ambiguities) {
  const auto t_start = Clock::now();
  requireModel(model, "recognize");
  StageMemo memo = memoSnapshot();
  const RecognitionParams params = withViewParams(requested, model->view_params);
  scene_mm.validate();
  if (!scene_mm.hasValidPoint())
    throw Error("the scene has no valid point (empty or all NaN): check the scan file or the "
                "camera capture");
  RecognitionResult result;
  auto scene = std::make_shared<const SceneAnalysis>(
      detail::analyzeScene(memo, scene_mm, sensor, params, requested, progress, result.timings));
  result.scene = scene;
  std::shared_ptr<const ModelPrep> prep;
  VotingScene voting;
  const auto t0 = Clock::now();
  if (scene->index)
    prep = detail::prepareModel(memo.model_preps, model, params);
  if (prep && prep->pairs && params.matching.verify_tolerance_mm > 0 &&
      params.matching.surface_sampling_mm > 0)
    voting = votingScene(memo, *prep, params, progress);
  result.timings.matching_ms += msSince(t0);
  {
    const std::lock_guard lock(m_mutex);
    m_memo = std::make_shared<StageMemo>(memo);
  }
  const ViewInScene view(*model, prep, params, *scene);
  result.detections =
      findDetections(view, *scene, voting, resolve_ambiguities, progress, result.timings);
  reportProgress(progress, kProgressShares.after_matching.end);
  result.timings.total_ms = msSince(t_start);
  reportProgress(progress, kProgressShares.after_matching.end);
  return result;
}

std::vector<Detection> Recognizer::refine(const std::shared_ptr<const TaughtModel>& model,
                                          std::vector<Detection> detections,
                                          const SceneAnalysis& scene,
                                          const RecognitionParams& requested) {
  requireModel(model, "refine");
  const RecognitionParams params = withViewParams(requested, model->view_params);
  if (!params.refine.enabled || detections.empty())
    return detections;
  const SceneAnalysis at = withIndex(scene, params);
  const ViewInScene view(*model, prepared(model, params), params, at);
  const PoseVerifier verify = view.verifier();
  detections =
      refineDetections(std::move(detections), *view.prep, *at.index, params.refine, verify);
  return placeDetections(std::move(detections), *model, view.prep.get(),
                         verify ? &view.scene : nullptr, params.matching.verify_tolerance_mm);
}

std::vector<Detection>
Recognizer::resolveAmbiguities(const std::shared_ptr<const TaughtModel>& model,
                               std::vector<Detection> detections, const SceneAnalysis& scene,
                               const RecognitionParams& requested) {
  requireModel(model, "resolve ambiguities");
  const RecognitionParams params = withViewParams(requested, model->view_params);
  if (!detail::needsModelPrep(params) || !(params.matching.verify_tolerance_mm > 0) ||
      detections.empty())
    return detections;
  const SceneAnalysis at = withIndex(scene, params);
  const ViewInScene view(*model, prepared(model, params), params, at);
  if (!view.prep->near_axis && view.prep->symmetries.empty())
    return detections;
  const PoseVerifier verify = view.verifier();
  sortBestFirst(detections);
  detections =
      resolveDetectionAmbiguities(std::move(detections), *view.prep, view.scene, params.matching,
                                  verify, view.refiner(), kDuplicateShare * model->diameter_mm);
  return placeDetections(std::move(detections), *model, view.prep.get(), &view.scene,
                         params.matching.verify_tolerance_mm);
}

PartScorer Recognizer::partScorer(const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                  const std::shared_ptr<const SceneAnalysis>& scene,
                                  const RecognitionParams& requested) {
  // What each view is scored with: its preparation's whole part, every few of its points, and the
  // view's verification tolerance.
  struct ViewPart {
    std::shared_ptr<const VerifyModel> points; ///< null: the view has no joined views
    std::vector<std::uint32_t> every;
    double tolerance_mm = 0.0;
  };
  std::vector<ViewPart> views(models.size());
  for (std::size_t m = 0; m < models.size(); ++m) {
    requireModel(models[m], "score on the whole part");
    const RecognitionParams params = withViewParams(requested, models[m]->view_params);
    const auto prep = prepared(models[m], params);
    ViewPart& view = views[m];
    view.tolerance_mm = params.matching.verify_tolerance_mm;
    if (!prep->joined_points || !(view.tolerance_mm > 0))
      continue;
    view.points = prep->joined_points;
    view.every = prep->joined_sample;
  }
  // The scorer keeps the analysis its VerifyScene points into alive.
  const auto at = std::make_shared<const SceneAnalysis>(withIndex(*scene, requested));
  return [at, views = std::move(views), verify_scene = at->verifyScene()](const Detection& d) {
    if (d.model_index < 0 || static_cast<std::size_t>(d.model_index) >= views.size())
      throw Error("a detection names view " + std::to_string(d.model_index) + " of " +
                  std::to_string(views.size()));
    const ViewPart& view = views[static_cast<std::size_t>(d.model_index)];
    if (!view.points)
      return std::numeric_limits<double>::quiet_NaN();
    return wholePartScore(*view.points, verify_scene, d.T_scene_model, view.tolerance_mm,
                          &view.every);
  };
}

} // namespace scanpick::core
