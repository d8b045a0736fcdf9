/// @file RecognizeViews.cpp
/// Several views of one part in one scene: each view recognized with the recognizer's shared
/// scene stages, their detections merged, and the merged ones refined.

#include "core/common/Error.h"
#include "core/common/Progress.h"
#include "core/pipeline/Recognizer.h"

#include <algorithm>
#include <chrono>
#include <iterator>

namespace scanpick::core {
namespace {
double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

double prepareViews(Recognizer& recognizer,
                    const std::vector<std::shared_ptr<const TaughtModel>>& models,
                    const RecognitionParams& params) {
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& model : models)
    recognizer.prepare(model, params);
  return msSince(t0);
}

RecognitionResult recognizeViews(Recognizer& recognizer,
                                 const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                 const PointCloud& scene_mm, const SensorModel& sensor,
                                 const RecognitionParams& params, const ProgressFn& progress) {
  if (models.empty())
    throw Error("no model to recognize: give at least one .spmodel");
  RecognitionResult merged;
  double diameter_mm = 0.0;
  // Refinement waits for the merge (Recognizer::refine).
  RecognitionParams unrefined = params;
  unrefined.refine.enabled = false;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double begin = double(m) / double(models.size());
    RecognitionResult r =
        recognizer.recognize(models[m], scene_mm, sensor, unrefined,
                             subProgress(progress, begin, begin + 1.0 / double(models.size())));
    diameter_mm = std::max(diameter_mm, models[m]->diameter_mm);
    for (auto& d : r.detections) {
      d.model_index = static_cast<int>(m);
      merged.detections.push_back(std::move(d));
    }
    const StageTimings& t = r.timings;
    StageTimings& sum = merged.timings;
    sum.preprocess_ms += t.preprocess_ms;
    sum.clustering_ms += t.clustering_ms;
    sum.keypoints_ms += t.keypoints_ms;
    sum.features_ms += t.features_ms;
    sum.matching_ms += t.matching_ms;
    sum.refine_ms += t.refine_ms;
    sum.total_ms += t.total_ms;
    if (m == 0) {
      merged.preprocessed = r.preprocessed;
      merged.floor_points_removed = r.floor_points_removed;
      merged.objects = r.objects;
      merged.object_keypoints = r.object_keypoints;
      merged.object_features = r.object_features;
    }
  }
  sortBestFirst(merged.detections);
  merged.detections = suppressDuplicates(std::move(merged.detections), 0.3 * diameter_mm,
                                         [](const Detection& d) { return d.centre_mm; });
  if (params.matching.max_detections > 0 &&
      merged.detections.size() > static_cast<std::size_t>(params.matching.max_detections))
    merged.detections.resize(static_cast<std::size_t>(params.matching.max_detections));
  if (params.refine.enabled) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Detection> refined;
    for (std::size_t m = 0; m < models.size(); ++m) {
      std::vector<Detection> of_view;
      for (auto& d : merged.detections)
        if (d.model_index == static_cast<int>(m))
          of_view.push_back(std::move(d));
      recognizer.refine(models[m], of_view, scene_mm, sensor, params);
      std::move(of_view.begin(), of_view.end(), std::back_inserter(refined));
      reportProgress(progress, 1.0); // a last chance to stop
    }
    sortBestFirst(refined);
    merged.detections = std::move(refined);
    merged.timings.refine_ms = msSince(t0);
    merged.timings.total_ms += merged.timings.refine_ms;
  }
  return merged;
}

std::vector<Detection> suppressDuplicates(std::vector<Detection> detections, double min_distance_mm,
                                          const DetectionPosition& position) {
  const auto at = [&](const Detection& d) {
    return position ? position(d) : Eigen::Vector3d(d.T_scene_model.translation());
  };
  std::vector<Detection> kept;
  for (auto& d : detections) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const Detection& k) {
      return (at(k) - at(d)).norm() < min_distance_mm;
    });
    if (!duplicate)
      kept.push_back(std::move(d));
  }
  return kept;
}

void sortBestFirst(std::vector<Detection>& detections) {
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
}

} // namespace scanpick::core
