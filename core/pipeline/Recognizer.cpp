#include "core/pipeline/Recognizer.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/features/FeatureExtraction.h"
#include "core/matching/FeatureMatcher.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/preprocess/SceneSplit.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <optional>

namespace scanpick::core {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// FNV-1a over 8-byte words: the scene's identity for the cache (content, not address, so a
/// re-captured identical scan hits and an edited buffer misses).
std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t h) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, bytes + i, 8);
    h = (h ^ word) * 1099511628211ull;
  }
  for (; i < size; ++i)
    h = (h ^ bytes[i]) * 1099511628211ull;
  return h;
}

std::uint64_t sceneHash(const PointCloud& cloud) {
  std::uint64_t h = 14695981039346656037ull;
  const std::uint32_t dims[2] = {cloud.width, cloud.height};
  h = hashBytes(dims, sizeof dims, h);
  h = hashBytes(cloud.points_mm.data(), cloud.points_mm.size() * sizeof(Eigen::Vector3f), h);
  return hashBytes(cloud.normals.data(), cloud.normals.size() * sizeof(Eigen::Vector3f), h);
}

std::uint64_t sensorHash(const SensorModel& s) {
  const double values[] = {double(s.width), double(s.height), s.fx, s.fy, s.cx, s.cy,
                           s.min_range_mm, s.max_range_mm, s.nominal_distance_mm};
  std::uint64_t h = hashBytes(values, sizeof values, 14695981039346656037ull);
  return hashBytes(s.T_camera_projector.matrix().data(), 16 * sizeof(double), h);
}

struct PreKey {
  std::uint64_t scene = 0;
  FloorParams floor;
  DownsampleParams downsample;
  std::uint64_t seed = 0;
  bool operator==(const PreKey&) const = default;
};
struct SplitKey {
  PreKey pre;
  ClusteringParams clustering;
  std::uint64_t sensor = 0;
  bool operator==(const SplitKey&) const = default;
};
struct KeypointKey {
  SplitKey split;
  KeypointParams keypoints;
  bool operator==(const KeypointKey&) const = default;
};
struct FeatureKey {
  KeypointKey keypoints;
  FeatureParams features;
  bool operator==(const FeatureKey&) const = default;
};

/// Runs `work(i)` for each object in parallel and reports progress in [begin, end] from the
/// calling thread's mutex-protected callback; cancellation is checked per object.
template <typename Work>
void forEachObject(std::size_t n, const ProgressFn& progress, double begin, double end, Work work) {
  std::mutex mutex;
  std::size_t done = 0;
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    work(i);
    const std::lock_guard lock(mutex);
    ++done;
    reportProgress(progress, begin + (end - begin) * double(done) / double(n));
  });
}

} // namespace

struct Recognizer::Cache {
  std::optional<PreKey> pre_key;
  std::shared_ptr<const PointCloud> pre;
  std::size_t floor_removed = 0;
  std::optional<SplitKey> split_key;
  std::shared_ptr<const std::vector<PointCloud>> objects;
  std::optional<KeypointKey> keypoint_key;
  std::shared_ptr<const std::vector<Keypoints>> keypoints;
  std::optional<FeatureKey> feature_key;
  std::shared_ptr<const std::vector<FeatureList>> features;
};

void Recognizer::setModel(std::shared_ptr<const TaughtModel> model) {
  const std::lock_guard lock(m_mutex);
  m_model = std::move(model);
}

std::shared_ptr<const TaughtModel> Recognizer::model() const {
  const std::lock_guard lock(m_mutex);
  return m_model;
}

void Recognizer::clearCache() {
  const std::lock_guard lock(m_mutex);
  m_cache.reset();
}

RecognitionResult Recognizer::recognize(const PointCloud& scene_mm, const SensorModel& sensor,
                                        const RecognitionParams& params,
                                        const ProgressFn& progress) {
  const auto t_start = Clock::now();
  std::shared_ptr<const TaughtModel> model;
  Cache cache;
  {
    const std::lock_guard lock(m_mutex);
    model = m_model;
    if (m_cache)
      cache = *m_cache;
  }
  if (!model)
    throw Error("no model to recognize: teach a part or open a .spmodel file first");
  scene_mm.validate();
  if (scene_mm.validCount() == 0)
    throw Error("the scene has no valid point (empty or all NaN): check the scan file or the "
                "camera capture");
  RecognitionResult result;

  const PreKey pre_key{sceneHash(scene_mm), params.floor, params.downsample, params.seed};
  if (cache.pre_key != pre_key) {
    const auto t0 = Clock::now();
    FloorRemovalResult floor =
        removeFloor(scene_mm, params.floor, params.seed, subProgress(progress, 0.0, 0.1));
    cache.floor_removed = floor.removed_points;
    cache.pre = std::make_shared<const PointCloud>(
        voxelDownsample(floor.remaining, params.downsample.voxel_mm));
    cache.pre_key = pre_key;
    cache.split_key.reset();
    result.timings.preprocess_ms = msSince(t0);
  }
  reportProgress(progress, 0.1);

  const SplitKey split_key{pre_key, params.clustering, sensorHash(sensor)};
  if (cache.split_key != split_key) {
    const auto t0 = Clock::now();
    SceneSplit split = splitIntoObjects(*cache.pre, sensor, params.clustering, params.seed,
                                        subProgress(progress, 0.1, 0.3));
    cache.objects = std::make_shared<const std::vector<PointCloud>>(std::move(split.objects));
    cache.split_key = split_key;
    cache.keypoint_key.reset();
    result.timings.clustering_ms = msSince(t0);
  }
  reportProgress(progress, 0.3);
  const auto& objects = *cache.objects;

  const KeypointKey keypoint_key{split_key, params.keypoints};
  if (cache.keypoint_key != keypoint_key) {
    const auto t0 = Clock::now();
    std::vector<Keypoints> keypoints(objects.size());
    forEachObject(objects.size(), progress, 0.3, 0.55, [&](std::size_t i) {
      keypoints[i] = extractKeypoints(objects[i], params.keypoints);
    });
    cache.keypoints = std::make_shared<const std::vector<Keypoints>>(std::move(keypoints));
    cache.keypoint_key = keypoint_key;
    cache.feature_key.reset();
    result.timings.keypoints_ms = msSince(t0);
  }
  const FeatureKey feature_key{keypoint_key, params.features};
  if (cache.feature_key != feature_key) {
    const auto t0 = Clock::now();
    std::vector<FeatureList> features(objects.size());
    forEachObject(objects.size(), progress, 0.55, 0.8, [&](std::size_t i) {
      // Each object draws from its own stream, so results do not depend on scheduling.
      features[i] = extractFeatures((*cache.keypoints)[i].points_mm, params.features,
                                    params.seed + 0x9E3779B97F4A7C15ull * (i + 1))
                        .features;
    });
    cache.features = std::make_shared<const std::vector<FeatureList>>(std::move(features));
    cache.feature_key = feature_key;
    result.timings.features_ms = msSince(t0);
  }
  {
    const std::lock_guard lock(m_mutex);
    m_cache = std::make_shared<Cache>(cache);
  }

  const auto t_match = Clock::now();
  std::vector<std::vector<MatchCandidate>> candidates(objects.size());
  forEachObject(objects.size(), progress, 0.8, 1.0, [&](std::size_t i) {
    candidates[i] = matchFeatures(model->features, (*cache.features)[i], params.matching);
  });
  for (std::size_t i = 0; i < candidates.size(); ++i)
    for (const auto& c : candidates[i]) {
      Detection d;
      d.T_scene_model = c.T_scene_model;
      d.score = c.score;
      d.matched_features = c.matched_features;
      d.cluster = static_cast<int>(i);
      for (const auto& g : model->grip_points)
        d.grip_points_scene.push_back({g.name, c.T_scene_model * g.position_mm});
      result.detections.push_back(std::move(d));
    }
  std::stable_sort(result.detections.begin(), result.detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  result.detections = suppressDuplicates(std::move(result.detections), 0.25 * model->diameter_mm);
  if (params.matching.max_detections > 0 &&
      result.detections.size() > static_cast<std::size_t>(params.matching.max_detections))
    result.detections.resize(static_cast<std::size_t>(params.matching.max_detections));
  result.timings.matching_ms = msSince(t_match);
  if (params.refine.enabled)
    logger()->warn("ICP refinement is not available in this build; poses are from the feature "
                   "matching (refined on all matched features)");

  result.preprocessed = cache.pre;
  result.floor_points_removed = cache.floor_removed;
  result.objects = cache.objects;
  result.object_keypoints = cache.keypoints;
  result.object_features = cache.features;
  result.timings.total_ms = msSince(t_start);
  reportProgress(progress, 1.0);
  return result;
}

std::vector<Detection> suppressDuplicates(std::vector<Detection> detections,
                                          double min_distance_mm) {
  std::vector<Detection> kept;
  for (auto& d : detections) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const Detection& k) {
      return (k.T_scene_model.translation() - d.T_scene_model.translation()).norm() <
             min_distance_mm;
    });
    if (!duplicate)
      kept.push_back(std::move(d));
  }
  return kept;
}

} // namespace scanpick::core
