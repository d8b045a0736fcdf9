#pragma once
/// @file Recognizer.h
/// The recognition pipeline of §3.5: floor removal → downsampling → split into objects → per
/// object keypoints → features → matching (Algorithm 8, several instances per object; beyond the
/// thesis, with matching.surface_sampling_mm, also surface point pair voting over the whole
/// scene) → duplicate suppression → detections with grip points. Each stage's output is cached,
/// keyed by the scene's content and that stage's parameters, so changing a matching tolerance
/// re-runs the matching only (the GUI's live tuning relies on this).

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Detection.h"
#include "core/common/Progress.h"
#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/pipeline/SceneAnalysis.h"

#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace scanpick::core {

namespace detail {
struct StageMemo;
struct ModelPrep;
} // namespace detail

/// Wall-clock time of each stage of the last run, milliseconds (0 for a stage served from cache).
struct StageTimings {
  double preprocess_ms = 0, clustering_ms = 0, keypoints_ms = 0, features_ms = 0, matching_ms = 0,
         refine_ms = 0, total_ms = 0;
};

/// What one recognition produced, the scene analysis included (for previews and later stages).
struct RecognitionResult {
  std::vector<Detection> detections; ///< best first
  StageTimings timings;
  /// What the scene stages made of the scan (preprocessed cloud, objects, keypoints, features,
  /// the indexes verification uses); it refers to the scan given to recognize().
  std::shared_ptr<const SceneAnalysis> scene;
};

/// A detection's score on the whole part (Recognizer::partScorer).
using PartScorer = std::function<double(const Detection&)>;

/// Runs recognition of one taught model. recognize() may be called from any thread; concurrent
/// calls are allowed (the cache is locked only while read or written).
class Recognizer {
public:
  Recognizer() = default;
  explicit Recognizer(std::shared_ptr<const TaughtModel> model) : m_model(std::move(model)) {}

  /// Sets the model to find (matching is re-run; cached scene stages are kept).
  void setModel(std::shared_ptr<const TaughtModel> model);
  [[nodiscard]] std::shared_ptr<const TaughtModel> model() const;

  /// Finds the model in `scene_mm` (camera frame, mm), with `params` except for the matching
  /// parameters the model sets for itself (TaughtModel::view_params). Throws Error without a
  /// model, for a scene with no valid point or an inconsistent cloud; Cancelled when `progress`
  /// asks to stop.
  /// Same scene + parameters (seed included) = identical result, cached or not.
  RecognitionResult recognize(const PointCloud& scene_mm, const SensorModel& sensor,
                              const RecognitionParams& params, const ProgressFn& progress = {});
  /// As above, for `model` instead of the recognizer's own, which stays as it is: the views of a
  /// part share one recognizer's cache without taking turns as its model (recognizeViews), so a
  /// window may recognize while it prepares. Throws Error for a null `model`.
  RecognitionResult recognize(const std::shared_ptr<const TaughtModel>& model,
                              const PointCloud& scene_mm, const SensorModel& sensor,
                              const RecognitionParams& params, const ProgressFn& progress = {});
  /// As recognize(model, …), but the rotations matching cannot tell apart are left as matching
  /// found them (resolveAmbiguities resolves them): recognizeViews resolves them after the views'
  /// merge, once per instance.
  RecognitionResult detect(const std::shared_ptr<const TaughtModel>& model,
                           const PointCloud& scene_mm, const SensorModel& sensor,
                           const RecognitionParams& params, const ProgressFn& progress = {});

  /// Prepares the model for matching as recognize() would with these parameters (verification
  /// points, ICP model, surface pair table, axis fit, near symmetries), so that the first scene
  /// does not pay for it: a cell prepares a model once, when it loads it. Nothing is done when
  /// the parameters need no preparation (no verification, refinement or surface voting). Throws
  /// Error without a model.
  void prepare(const RecognitionParams& params);
  /// As above, for `model` instead of the recognizer's own (see recognize). Throws Error for a
  /// null `model`.
  void prepare(const std::shared_ptr<const TaughtModel>& model, const RecognitionParams& params);

  /// `detections` of `model` in `scene` (RecognitionResult::scene) refined as recognize() does with
  /// params.refine.enabled: ICP from each detection not refined yet, kept when it verifies as
  /// well; then their centres, grip points and free rotation axes again. Returned as they are when
  /// params.refine.enabled is false. `params`: those the scene was analysed with. Throws Error
  /// without a model.
  [[nodiscard]] std::vector<Detection> refine(const std::shared_ptr<const TaughtModel>& model,
                                              std::vector<Detection> detections,
                                              const SceneAnalysis& scene,
                                              const RecognitionParams& params);

  /// The rotations matching cannot tell apart of `detections` of `model` in `scene` resolved as
  /// recognize() does: the rotation about the view's near axis that its asymmetric feature (a
  /// cup's handle) says, and its near symmetries; then their centres, grip points and free
  /// rotation axes again, best first. Returned as they are without verification or without such
  /// ambiguities. Throws Error as refine() does.
  [[nodiscard]] std::vector<Detection>
  resolveAmbiguities(const std::shared_ptr<const TaughtModel>& model,
                     std::vector<Detection> detections, const SceneAnalysis& scene,
                     const RecognitionParams& params);

  /// Scores detections of the views `models` (Detection::model_index naming the view) on the
  /// whole part in `scene`: of the points of the view and of the views joined to it
  /// (TaughtModel::joined_views) at the detection's pose, every few of them (about
  /// kJoinedSamplePoints, ModelPrep::joined_sample), (confirmed − violations) ÷ those the camera
  /// should see (tallyPoints; neither hidden, turned away nor shadowed). Two views' poses of one
  /// instance verify each on its own view's points, so their scores do not compare; these do. The
  /// scorer gives NaN for a view without joined views, throws Error for a view index out of range,
  /// and keeps `scene` alive (and so needs the scan it refers to). Throws Error without a model.
  [[nodiscard]] PartScorer partScorer(const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                      const std::shared_ptr<const SceneAnalysis>& scene,
                                      const RecognitionParams& params);

  /// How many model preparations the cache holds (at most 8: views alternate scene after scene).
  [[nodiscard]] std::size_t preparedModels() const;

private:
  /// recognize() (`resolve_ambiguities`) or detect().
  RecognitionResult run(const std::shared_ptr<const TaughtModel>& model, const PointCloud& scene_mm,
                        const SensorModel& sensor, const RecognitionParams& params,
                        const ProgressFn& progress, bool resolve_ambiguities);
  /// A copy of the memo, taken under the lock.
  [[nodiscard]] detail::StageMemo memoSnapshot() const;
  /// Stores `memo`'s model preparations, keeping the memoized scene stages.
  void storePreparations(const detail::StageMemo& memo);
  /// `model` prepared for `params` (a view's), from the memo or made and stored there.
  [[nodiscard]] std::shared_ptr<const detail::ModelPrep>
  prepared(const std::shared_ptr<const TaughtModel>& model, const RecognitionParams& params);
  mutable std::mutex m_mutex;
  std::shared_ptr<const TaughtModel> m_model;
  std::shared_ptr<detail::StageMemo> m_memo;
};

/// Recognizer::prepare for each of `models` (views of one part), in turn; the recognizer's own
/// model is left as it is. Returns the wall time it took, milliseconds.
double prepareViews(Recognizer& recognizer,
                    const std::vector<std::shared_ptr<const TaughtModel>>& models,
                    const RecognitionParams& params);

/// Finds any of several models in one scene: views of one part, each taught from a scan of
/// another side it can rest on (one model sees one side only). The scene stages run once (the
/// recognizer's cache), matching per model; detections are merged best first by
/// mergeViewDetections within kViewMergeShare × the larger model diameter (the same instance seen
/// through another view). The rotations matching cannot tell apart (a cup's handle, near
/// symmetries) are resolved after the merge (Recognizer::resolveAmbiguities), once per instance,
/// and the merge then run again for the detections a rotation moved. With params.refine.enabled
/// the detections left are refined after that (Recognizer::refine), so that ICP refines the
/// detections reported, and
/// merged once more: a refined pose may land on an instance another view's detection holds. Views
/// that know their place in the part should be joined first (joinViews, TaughtModel.h): only then
/// are two parts lying close together told apart. Detection::model_index names the model. The
/// recognizer's own model is left as it is. Throws as Recognizer::recognize, and Error for an empty
/// `models`.
RecognitionResult recognizeViews(Recognizer& recognizer,
                                 const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                 const PointCloud& scene_mm, const SensorModel& sensor,
                                 const RecognitionParams& params, const ProgressFn& progress = {});

/// Highest score first; equal scores keep their order.
void sortBestFirst(std::vector<Detection>& detections);

/// Detections of one view whose origins lie closer than this share of the part's diameter
/// (TaughtModel::diameter_mm) are one instance (suppressDuplicates): a wrong rotation of a view on
/// an instance keeps its origin within about a third of the part, a neighbour's lies farther.
inline constexpr double kDuplicateShare = 0.35;
/// Detections of different views whose Detection::centre_mm lie closer than this share of the
/// larger diameter are candidates for one instance (mergeViewDetections): two views' origins
/// (their points' centroids) lie apart on one part.
inline constexpr double kViewMergeShare = 0.45;
/// Surface voting's poses closer than this share of the diameter are clustered as one.
inline constexpr double kVoteClusterShare = 0.14;

/// Two detections near each other are one instance when this share of the later one's part points
/// lie within kSameSurfaceMm of the earlier one's (mergeViewDetections; the shares measured are in
/// docs/design-notes.md, "Merging the views' detections").
inline constexpr double kSameInstanceShare = 0.2;
/// The share for two detections whose centres lie farther apart than the merge distance but within
/// the part's diameter (two views seeing opposite sides of one instance share most of it).
inline constexpr double kSameInstanceFarShare = 0.5;
inline constexpr double kSameSurfaceMm = 3.0;
/// About this many of a candidate's part points are compared (mergeViewDetections).
inline constexpr std::size_t kSameInstanceSample = 400;
/// Two views' poses of one instance closer than this (the part's origin, and its rotation) are
/// the same pose: either is kept (mergeViewDetections).
inline constexpr double kSameInstanceMm = 3.0;
inline constexpr double kSameInstanceDeg = 3.0;
/// Two views' differing poses of one instance whose scores lie this close are a tie that their own
/// verification cannot break (mergeViewDetections asks its `prefer`).
inline constexpr double kSameInstanceTie = 0.01;

/// Whether `candidate`, a later (lower-scoring) detection of the instance `kept` is, should take
/// its place (mergeViewDetections).
using SameInstanceArbiter = std::function<bool(const Detection& kept, const Detection& candidate)>;

/// Merges the detections of several views of one part (`detections` sorted best first,
/// Detection::model_index naming the view in `models`): a detection whose Detection::centre_mm
/// lies within `min_distance_mm` of a kept one's is dropped as the same instance, except where the
/// views are joined (TaughtModel::joined_views), which give each view the part's other sides: then
/// a detection whose centre lies within the whole part's size (the diagonal of the box around the
/// joined views' points, the larger of the two views') is dropped only when
/// its part's points, at its pose, lie on the kept one's surface (kSameInstanceShare within
/// kSameSurfaceMm; kSameInstanceFarShare beyond `min_distance_mm`). Parts cannot pass through each
/// other, so two lying
/// close together share little of their surface, while a view's pose of an instance another view
/// found, right or wrong, shares a face or more. Where the two poses differ (kSameInstanceMm,
/// kSameInstanceDeg), `prefer` (when set) may give the later one the earlier one's place (and its
/// place in the order). Keeps the input order otherwise. Throws Error for a model index out of
/// range.
std::vector<Detection>
mergeViewDetections(std::vector<Detection> detections,
                    const std::vector<std::shared_ptr<const TaughtModel>>& models,
                    double min_distance_mm, const SameInstanceArbiter& prefer = {});

/// Removes duplicates: detections (sorted best first) whose model origins (scene frame) lie
/// closer than `min_distance_mm` to a better one's are dropped. Where the two poses differ
/// (kSameInstanceMm, kSameInstanceDeg), `prefer` (when set) may give the later one the earlier
/// one's place (and its place in the order). Keeps the input order otherwise.
std::vector<Detection> suppressDuplicates(std::vector<Detection> detections, double min_distance_mm,
                                          const SameInstanceArbiter& prefer = {});

} // namespace scanpick::core
