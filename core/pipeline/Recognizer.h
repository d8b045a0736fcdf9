#pragma once
/// @file Recognizer.h
/// The recognition pipeline of §3.5: floor removal → downsampling → split into objects → per
/// object keypoints → features → matching (Algorithm 8, several instances per object; beyond the
/// thesis, with matching.surface_sampling_mm, also surface point pair voting over the whole
/// scene) → duplicate suppression → detections with grip points. Each stage's output is cached, keyed by
/// the scene's content and that stage's parameters, so changing a matching tolerance re-runs the
/// matching only (the GUI's live tuning relies on this).

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Progress.h"
#include "core/features/Feature.h"
#include "core/keypoints/Keypoints.h"
#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/pipeline/Detection.h"

#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace scanpick::core {

/// Wall-clock time of each stage of the last run, milliseconds (0 for a stage served from cache).
struct StageTimings {
  double preprocess_ms = 0, clustering_ms = 0, keypoints_ms = 0, features_ms = 0,
         matching_ms = 0, refine_ms = 0, total_ms = 0;
};

/// What one recognition produced, intermediate results included (for previews).
struct RecognitionResult {
  std::vector<Detection> detections;  ///< best first
  StageTimings timings;
  /// The scene after floor removal and downsampling.
  std::shared_ptr<const PointCloud> preprocessed;
  std::size_t floor_points_removed = 0;
  /// One cloud per object (cluster), then per object its keypoints and features.
  std::shared_ptr<const std::vector<PointCloud>> objects;
  std::shared_ptr<const std::vector<Keypoints>> object_keypoints;
  std::shared_ptr<const std::vector<FeatureList>> object_features;
};

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

  /// Prepares the model for matching as recognize() would with these parameters (verification
  /// points, ICP model, surface pair table, axis fit, near symmetries), so that the first scene
  /// does not pay for it: a cell prepares a model once, when it loads it. Nothing is done when
  /// the parameters need no preparation (no verification, refinement or surface voting). Throws
  /// Error without a model.
  void prepare(const RecognitionParams& params);
  /// As above, for `model` instead of the recognizer's own (see recognize). Throws Error for a
  /// null `model`.
  void prepare(const std::shared_ptr<const TaughtModel>& model, const RecognitionParams& params);

  /// Refines `detections` of `model` found in `scene_mm` by the last recognize() call (its scene
  /// stages cached), as recognize() does with params.refine.enabled: ICP from each detection not
  /// polished yet, kept when it verifies as well; then their centres, grip points and free turns
  /// again. Nothing is done when params.refine.enabled is false. Throws Error without a model or
  /// when `scene_mm` is not the scene last recognized with these parameters.
  void refine(const std::shared_ptr<const TaughtModel>& model, std::vector<Detection>& detections,
              const PointCloud& scene_mm, const SensorModel& sensor,
              const RecognitionParams& params);

  /// How many model preparations the cache holds (at most 8: views alternate scene after scene).
  [[nodiscard]] std::size_t preparedModels() const;

  /// Forgets every cached stage.
  void clearCache();

private:
  struct Cache;
  /// A copy of the cache, taken under the lock.
  [[nodiscard]] Cache cacheSnapshot() const;
  mutable std::mutex m_mutex;
  std::shared_ptr<const TaughtModel> m_model;
  std::shared_ptr<Cache> m_cache;
};

/// Recognizer::prepare for each of `models` (views of one part), in turn; the recognizer's own
/// model is left as it is. Returns the wall time it took, milliseconds.
double prepareViews(Recognizer& recognizer,
                    const std::vector<std::shared_ptr<const TaughtModel>>& models,
                    const RecognitionParams& params);

/// Finds any of several models in one scene: views of one part, each taught from a scan of
/// another side it can rest on (one model sees one side only). The scene stages run once (the
/// recognizer's cache), matching per model; detections are merged best first, and one whose
/// position (Detection::centre_mm) lies within 0.3 × the larger model diameter of a better one's
/// is dropped (the same instance seen through another view). With params.refine.enabled the
/// detections left are refined after the merge (Recognizer::refine), so that ICP polishes the
/// detections reported and cannot change which of them the merge keeps. Views that know their
/// place in the part should be joined first (joinViews, TaughtModel.h). Detection::model_index
/// names the model.
/// The recognizer's own model is left as it is.
/// Throws as Recognizer::recognize, and Error for an empty `models`.
RecognitionResult recognizeViews(Recognizer& recognizer,
                                 const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                 const PointCloud& scene_mm, const SensorModel& sensor,
                                 const RecognitionParams& params, const ProgressFn& progress = {});

/// Highest score first; equal scores keep their order.
void sortBestFirst(std::vector<Detection>& detections);

/// Where a detection lies, for suppressDuplicates (scene frame, mm).
using DetectionPosition = std::function<Eigen::Vector3d(const Detection&)>;

/// Removes duplicates: detections (sorted best first) whose positions are closer than
/// `min_distance_mm` to a better one's are dropped; the position is `position`'s, or the model
/// origin when it is empty. Keeps the input order otherwise.
std::vector<Detection> suppressDuplicates(std::vector<Detection> detections, double min_distance_mm,
                                          const DetectionPosition& position = {});

} // namespace scanpick::core
