/// @file RecognizeViews.cpp
/// Several views of one part in one scene: each view recognized with the recognizer's shared
/// scene stages, their detections merged, and the merged ones refined.

#include "core/ambiguity/ModelPrep.h"
#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/common/Progress.h"
#include "core/pipeline/ProgressShares.h"
#include "core/pipeline/Recognizer.h"
#include "core/refine/SceneIndex.h"

#include <algorithm>
#include <chrono>
#include <iterator>

namespace scanpick::core {
namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// `detections` handed to `work` view by view (Detection::model_index, of `views`), then
/// together again, best first.
template <typename Work>
std::vector<Detection> ofEachView(std::vector<Detection> detections, std::size_t views,
                                  Work&& work) {
  std::vector<Detection> out;
  for (std::size_t m = 0; m < views; ++m) {
    std::vector<Detection> of_view;
    for (auto& d : detections)
      if (d.model_index == static_cast<int>(m))
        of_view.push_back(std::move(d));
    work(m, of_view);
    std::move(of_view.begin(), of_view.end(), std::back_inserter(out));
  }
  sortBestFirst(out);
  return out;
}
} // namespace

double prepareViews(Recognizer& recognizer,
                    const std::vector<std::shared_ptr<const TaughtModel>>& models,
                    const RecognitionParams& params) {
  const auto t0 = Clock::now();
  for (const auto& model : models)
    recognizer.prepare(model, params);
  return msSince(t0);
}

namespace {

/// Each view's detections in `scene_mm` (Recognizer::detect, ambiguous rotations left as matching
/// found them),
/// Detection::model_index naming the view, best first; the timings summed over the views and the
/// last view's scene analysis (the scene stages are shared; the last view's has what any view
/// needed).
RecognitionResult detectEachView(Recognizer& recognizer,
                                 const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                 const PointCloud& scene_mm, const SensorModel& sensor,
                                 const RecognitionParams& params, const ProgressFn& progress) {
  RecognitionResult merged;
  const double share = 1.0 / double(models.size());
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double begin = double(m) * share;
    RecognitionResult r = recognizer.detect(models[m], scene_mm, sensor, params,
                                            subProgress(progress, begin, begin + share));
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
    merged.scene = r.scene;
  }
  sortBestFirst(merged.detections);
  return merged;
}

/// The largest diameter of the views (mm).
double maxDiameter(const std::vector<std::shared_ptr<const TaughtModel>>& models) {
  double diameter_mm = 0.0;
  for (const auto& model : models)
    diameter_mm = std::max(diameter_mm, model->diameter_mm);
  return diameter_mm;
}

/// The views' detections of one instance merged (mergeViewDetections), their ambiguous rotations
/// resolved per view (Recognizer::resolveAmbiguities), and merged again when a rotation moved one
/// onto an instance another view's detection holds. Best first.
std::vector<Detection> mergeAndResolve(
    Recognizer& recognizer, const std::vector<std::shared_ptr<const TaughtModel>>& models,
    std::vector<Detection> detections, const std::shared_ptr<const SceneAnalysis>& scene,
    const RecognitionParams& params) {
  const double diameter_mm = maxDiameter(models);
  // Two views' poses of one instance that differ: the one the whole part bears out better.
  PartScorer on_part; // made when first needed
  const SameInstanceArbiter prefer = [&](const Detection& kept, const Detection& candidate) {
    if (!on_part)
      on_part = recognizer.partScorer(models, scene, params);
    const double kept_score = on_part(kept), candidate_score = on_part(candidate);
    const bool take = candidate_score > kept_score + detail::kPartScoreMargin; // false for NaN
    logger()->debug("view {}'s pose at ({:.0f}, {:.0f}, {:.0f}) mm scores {:.3f} on the whole "
                    "part, view {}'s pose of that instance {:.3f}: {}",
                    candidate.model_index, candidate.centre_mm.x(), candidate.centre_mm.y(),
                    candidate.centre_mm.z(), candidate_score, kept.model_index, kept_score,
                    take ? "it takes the other's place" : "it is dropped");
    return take;
  };
  detections =
      mergeViewDetections(std::move(detections), models, kViewMergeShare * diameter_mm, prefer);
  // Whether a rotation moved any detection.
  const auto poses = [](const std::vector<Detection>& of_view) {
    std::vector<Eigen::Matrix4d> out;
    for (const Detection& d : of_view)
      out.push_back(d.T_scene_model.matrix());
    return out;
  };
  bool rotated = false;
  detections = ofEachView(
      std::move(detections), models.size(), [&](std::size_t m, std::vector<Detection>& of_view) {
        const auto before = poses(of_view);
        of_view = recognizer.resolveAmbiguities(models[m], std::move(of_view), *scene, params);
        rotated = rotated || poses(of_view) != before;
      });
  if (rotated)
    detections =
        mergeViewDetections(std::move(detections), models, kViewMergeShare * diameter_mm, prefer);
  sortBestFirst(detections);
  return detections;
}

} // namespace

RecognitionResult recognizeViews(Recognizer& recognizer,
                                 const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                 const PointCloud& scene_mm, const SensorModel& sensor,
                                 const RecognitionParams& params, const ProgressFn& progress) {
  if (models.empty())
    throw Error("no model to recognize: give at least one .spmodel");
  // Refinement waits for the merge (Recognizer::refine).
  RecognitionParams unrefined = params;
  unrefined.refine.enabled = false;
  RecognitionResult merged =
      detectEachView(recognizer, models, scene_mm, sensor, unrefined, progress);
  const auto t_merge = Clock::now();
  const std::size_t found = merged.detections.size();
  merged.detections =
      mergeAndResolve(recognizer, models, std::move(merged.detections), merged.scene, unrefined);
  const double merge_ms = msSince(t_merge);
  logger()->debug("the views' {} detections merged into {}, their ambiguities resolved, in "
                  "{:.1f} ms",
                  found, merged.detections.size(), merge_ms);
  merged.timings.matching_ms += merge_ms;
  merged.timings.total_ms += merge_ms;
  if (params.matching.max_detections > 0 &&
      merged.detections.size() > static_cast<std::size_t>(params.matching.max_detections))
    merged.detections.resize(static_cast<std::size_t>(params.matching.max_detections));
  if (params.refine.enabled) {
    const auto t0 = Clock::now();
    merged.detections = ofEachView(
        std::move(merged.detections), models.size(),
        [&](std::size_t m, std::vector<Detection>& of_view) {
          of_view = recognizer.refine(models[m], std::move(of_view), *merged.scene, params);
          reportProgress(progress, kProgressShares.after_matching.end); // a last chance to stop
        });
    // Refinement may bring a pose onto an instance another view's detection holds: the better
    // one stays.
    merged.detections = mergeViewDetections(std::move(merged.detections), models,
                                            kViewMergeShare * maxDiameter(models));
    merged.timings.refine_ms = msSince(t0);
    merged.timings.total_ms += merged.timings.refine_ms;
  }
  return merged;
}

namespace {

/// The points of a view and of the views joined to it (its frame, mm), every stride-th so that
/// about `count` remain; empty when no views are joined (the part's other sides are unknown).
std::vector<Eigen::Vector3f> partPoints(const TaughtModel& model, std::size_t count) {
  if (model.joined_views.empty())
    return {};
  std::vector<const PointCloud*> clouds{&model.cloud_mm};
  for (const auto& view : model.joined_views)
    clouds.push_back(&view.cloud_mm);
  std::size_t total = 0;
  for (const PointCloud* cloud : clouds)
    total += cloud->points_mm.size();
  const std::size_t stride = std::max<std::size_t>(1, total / count);
  std::vector<Eigen::Vector3f> points;
  std::size_t k = 0;
  for (const PointCloud* cloud : clouds)
    for (const auto& p : cloud->points_mm)
      if (k++ % stride == 0 && isValid(p))
        points.push_back(p);
  return points;
}

/// `points` moved by `T`, as an unorganized cloud.
PointCloud moved(const std::vector<Eigen::Vector3f>& points, const Eigen::Isometry3d& T) {
  const Eigen::Isometry3f Tf = T.cast<float>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const auto& p : points)
    out.push_back(Tf * p);
  return PointCloud::fromPoints(std::move(out));
}

/// Whether two poses lie more than kSameInstanceMm or kSameInstanceDeg apart.
bool posesDiffer(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b) {
  const double angle = Eigen::AngleAxisd(T_a.linear().transpose() * T_b.linear()).angle();
  return (T_a.translation() - T_b.translation()).norm() > kSameInstanceMm ||
         angle > kSameInstanceDeg * EIGEN_PI / 180.0;
}

/// Whether two views' detections put the part (TaughtModel::T_part_model) at poses more than
/// kSameInstanceMm or kSameInstanceDeg apart; false when a view does not know its place in the
/// part.
bool posesDiffer(const Detection& a, const Detection& b,
                 const std::vector<std::shared_ptr<const TaughtModel>>& models) {
  const auto& part_a = models[static_cast<std::size_t>(a.model_index)]->T_part_model;
  const auto& part_b = models[static_cast<std::size_t>(b.model_index)]->T_part_model;
  return part_a && part_b &&
         posesDiffer(a.T_scene_model * part_a->inverse(), b.T_scene_model * part_b->inverse());
}

} // namespace

std::vector<Detection>
mergeViewDetections(std::vector<Detection> detections,
                    const std::vector<std::shared_ptr<const TaughtModel>>& models,
                    double min_distance_mm, const SameInstanceArbiter& prefer) {
  // Each candidate's part points are looked for among about four times as many of the kept one.
  std::vector<std::vector<Eigen::Vector3f>> sample(models.size()), surface(models.size());
  std::vector<double> part_mm(models.size(), 0.0); // the whole part's size, when known
  for (std::size_t m = 0; m < models.size(); ++m) {
    sample[m] = partPoints(*models[m], kSameInstanceSample);
    surface[m] = partPoints(*models[m], 4 * kSameInstanceSample);
    Eigen::AlignedBox3f box;
    for (const auto& p : surface[m])
      box.extend(p);
    part_mm[m] = surface[m].empty() ? 0.0 : double(box.diagonal().norm());
  }
  const auto part = [&](const std::vector<std::vector<Eigen::Vector3f>>& points,
                        const Detection& d) -> const std::vector<Eigen::Vector3f>& {
    if (d.model_index < 0 || static_cast<std::size_t>(d.model_index) >= models.size())
      throw Error("a detection names model " + std::to_string(d.model_index) + " of " +
                  std::to_string(models.size()));
    return points[static_cast<std::size_t>(d.model_index)];
  };
  std::vector<Detection> kept;
  std::vector<std::unique_ptr<const SceneIndex>> kept_surface; // made when first asked
  SceneIndexOptions nearest_only;
  nearest_only.estimate_normals = false;
  const auto max_sq = static_cast<float>(kSameSurfaceMm * kSameSurfaceMm);
  for (auto& d : detections) {
    const auto& candidate = part(sample, d);
    bool duplicate = false;
    for (std::size_t k = 0; k < kept.size() && !duplicate; ++k) {
      const auto& kept_points = part(surface, kept[k]);
      const bool whole_part = !candidate.empty() && !kept_points.empty();
      // With the whole part known, the shared surface decides wherever the two views' centres may
      // lie on one instance: anywhere within the whole part's size (two sides of a plate, the end
      // and the side of a bar, or one view at a symmetric pose). Beyond min_distance_mm it must
      // be most of the part: two neighbours lying face to face share a face.
      const double distance_mm = (kept[k].centre_mm - d.centre_mm).norm();
      const double within_mm = whole_part
                                   ? std::max({min_distance_mm, part_mm[std::size_t(d.model_index)],
                                               part_mm[std::size_t(kept[k].model_index)]})
                                   : min_distance_mm;
      if (distance_mm >= within_mm)
        continue;
      const double same_share =
          distance_mm < min_distance_mm ? kSameInstanceShare : kSameInstanceFarShare;
      if (!whole_part) {
        duplicate = true; // the part's other sides are unknown: near is the same
        break;
      }
      if (!kept_surface[k])
        kept_surface[k] = std::make_unique<const SceneIndex>(
            moved(kept_points, kept[k].T_scene_model), nearest_only);
      const Eigen::Isometry3f T = d.T_scene_model.cast<float>();
      std::size_t shared = 0;
      for (const auto& p : candidate)
        shared += kept_surface[k]->nearest(T * p, max_sq) >= 0 ? 1 : 0;
      const double share = double(shared) / double(candidate.size());
      duplicate = share >= same_share;
      logger()->debug("view {}'s detection at ({:.0f}, {:.0f}, {:.0f}) mm shares {:.2f} of the "
                      "part's surface with view {}'s there: {}",
                      d.model_index, d.centre_mm.x(), d.centre_mm.y(), d.centre_mm.z(), share,
                      kept[k].model_index, duplicate ? "the same instance" : "another instance");
      if (duplicate && prefer && kept[k].score - d.score <= kSameInstanceTie &&
          posesDiffer(kept[k], d, models) && prefer(kept[k], d)) {
        kept[k] = std::move(d);
        kept_surface[k].reset();
      }
    }
    if (!duplicate) {
      kept.push_back(std::move(d));
      kept_surface.emplace_back();
    }
  }
  return kept;
}

std::vector<Detection> suppressDuplicates(std::vector<Detection> detections, double min_distance_mm,
                                          const SameInstanceArbiter& prefer) {
  std::vector<Detection> kept;
  for (auto& d : detections) {
    const auto same = std::find_if(kept.begin(), kept.end(), [&](const Detection& k) {
      return (k.T_scene_model.translation() - d.T_scene_model.translation()).norm() <
             min_distance_mm;
    });
    if (same == kept.end())
      kept.push_back(std::move(d));
    else if (prefer && posesDiffer(same->T_scene_model, d.T_scene_model) && prefer(*same, d))
      *same = std::move(d);
  }
  return kept;
}

void sortBestFirst(std::vector<Detection>& detections) {
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
}

} // namespace scanpick::core
