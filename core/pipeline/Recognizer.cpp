#include "core/pipeline/Recognizer.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/features/FeatureExtraction.h"
#include "core/matching/FeatureMatcher.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/preprocess/SceneSplit.h"
#include "core/refine/PoseRefinement.h"

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

/// The model's points for verification (model frame, mm) and their unit normals facing the teach
/// camera (NaN where none could be estimated).
struct VerifyModel {
  std::vector<Eigen::Vector3f> points, normals;
  std::vector<Eigen::Vector3f> keypoints;  ///< the model's keypoints (edges), strided
};

/// The scene's keypoints (of every object) indexed, for the edge check of verification.
struct EdgeCheck {
  const SceneIndex* scene_keypoints = nullptr;
  double tolerance_mm = 0.0;
};

/// Verification never expects fewer than this share of the model's points to be seen, however
/// many are hidden: a pose confirmed on one leg of a bracket whose other leg falls behind other
/// parts must not score as a whole part.
constexpr double kMinExpectedShare = 0.75;

/// cos 60°: model and scene normals closer than this agree.
constexpr float kMinNormalAgreement = 0.5f;

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
  /// Verification and refinement: the preprocessed scene indexed (key: pre_key) and the model's
  /// point subsample (key: model and point count).
  std::optional<PreKey> index_key;
  std::shared_ptr<const SceneIndex> scene_index;
  std::shared_ptr<const TaughtModel> refine_model_for;
  int refine_model_points = 0;
  std::shared_ptr<const RefineModel> refine_model;
  /// Verification: the model's valid points, strided to at most refine.model_points.
  std::shared_ptr<const VerifyModel> verify_points;
  /// Every object's keypoints in one index (key: keypoint_key), for the edge check.
  std::optional<KeypointKey> edge_key;
  std::shared_ptr<const SceneIndex> edge_index;
};

namespace {
/// Builds (or keeps from the cache) the scene index and the model's point subsample used by
/// verification and refinement.
void prepareVerificationImpl(std::optional<PreKey>& index_key,
                             std::shared_ptr<const SceneIndex>& scene_index,
                             std::shared_ptr<const TaughtModel>& refine_model_for, int& refine_model_points,
                             std::shared_ptr<const RefineModel>& refine_model,
                             std::shared_ptr<const VerifyModel>& verify_points,
                             const PointCloud& pre, const std::shared_ptr<const TaughtModel>& model,
                             const PreKey& pre_key,
                             const RecognitionParams& params) {
  if (index_key != pre_key || !scene_index) {
    SceneIndexOptions options;
    options.normal_radius_mm = params.keypoints.normal_radius_mm;
    scene_index = std::make_shared<const SceneIndex>(pre, options);
    index_key = pre_key;
  }
  const int points = std::max(10, params.refine.model_points);
  if (refine_model_for != model || refine_model_points != points || !verify_points ||
      (params.refine.enabled && !refine_model)) {
    refine_model.reset();
    if (params.refine.enabled)
      refine_model = std::make_shared<const RefineModel>(
          model->cloud_mm, points, Eigen::Vector3d(model->T_teach_model.inverse().translation()));
    // Every valid point, evenly strided, with its normal where one can be estimated: wire-like
    // models (the thesis's ideal part) have none and are verified by position alone.
    SceneIndexOptions model_options;
    model_options.normal_radius_mm = params.keypoints.normal_radius_mm;
    model_options.viewpoint_mm = model->T_teach_model.inverse().translation();
    const SceneIndex model_index(model->cloud_mm, model_options);
    const auto& valid = model_index.points();
    const std::size_t stride = std::max<std::size_t>(1, (valid.size() + points - 1) / points);
    auto strided = std::make_shared<VerifyModel>();
    for (std::size_t i = 0; i < valid.size(); i += stride) {
      strided->points.push_back(valid[i]);
      strided->normals.push_back(model_index.normals()[i]);
    }
    const std::size_t key_stride =
        std::max<std::size_t>(1, (model->keypoints_mm.size() + 399) / 400);
    for (std::size_t i = 0; i < model->keypoints_mm.size(); i += key_stride)
      strided->keypoints.push_back(model->keypoints_mm[i]);
    verify_points = std::move(strided);
    refine_model_for = model;
    refine_model_points = points;
  }
}
/// Share of the model's keypoints lying on confirmed scene surface that also have a scene keypoint
/// within the edge tolerance (1 when off or when fewer than 10 lie on surface): a flat face
/// matched onto another flat face at a wrong turn confirms its surface but not its outline.
double edgeAgreement(const VerifyModel& model, const SceneIndex& index, const Eigen::Isometry3f& T,
                     float surface_tol_sq, const EdgeCheck& edges) {
  if (!edges.scene_keypoints || edges.tolerance_mm <= 0)
    return 1.0;
  const auto edge_tol_sq = static_cast<float>(edges.tolerance_mm * edges.tolerance_mm);
  std::size_t on_surface = 0, on_edge = 0;
  for (const auto& k : model.keypoints) {
    const Eigen::Vector3f p = T * k;
    if (index.nearest(p, 4.0f * surface_tol_sq) < 0)
      continue;
    ++on_surface;
    if (edges.scene_keypoints->nearest(p, edge_tol_sq) >= 0)
      ++on_edge;
  }
  return on_surface < 10 ? 1.0 : double(on_edge) / double(on_surface);
}

/// Point-level verification of a pose (beyond the thesis): a model point (of the subsample) is
/// confirmed when a scene point facing the same way lies within `tolerance_mm`. On an organized
/// scene whose size is the sensor's, an unconfirmed point is a violation when the camera sees the
/// scene clearly behind it at its pixel (more than 3 x tolerance farther), i.e. looks through
/// where the pose puts material (a hole, or the floor beside a part), and hidden when the camera
/// sees something clearly in front of it (another part); points turned away from the camera are
/// hidden too. Returns (confirmed − violations) ÷ the points expected to be seen, clamped to
/// [0, 1], times the edge agreement. The expected count is never taken below kMinExpectedShare of the model,
/// so a pose that turns the taught side away, such as a flip, cannot score on the few points left.
double verifyPose(const VerifyModel& model, const SceneIndex& index,
                  const PointCloud& scene, const SensorModel& sensor,
                  const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                  const EdgeCheck& edges) {
  const auto& model_points = model.points;
  if (model_points.empty())
    return 0.0;
  const bool organized = scene.height > 1 && static_cast<int>(scene.width) == sensor.width &&
                         static_cast<int>(scene.height) == sensor.height && sensor.fx > 0;
  const Eigen::Isometry3f T = T_scene_model.cast<float>();
  const auto tol_sq = static_cast<float>(tolerance_mm * tolerance_mm);
  const auto margin = static_cast<float>(3.0 * tolerance_mm);
  std::size_t confirmed = 0, violations = 0, hidden = 0;
  for (std::size_t k = 0; k < model_points.size(); ++k) {
    const Eigen::Vector3f p = T * model_points[k];
    const Eigen::Vector3f& n_model = model.normals[k];
    // The camera sits at the scene origin.
    const bool turned_away = n_model.allFinite() && (T.linear() * n_model).dot(-p) <= 0.0f;
    const std::int64_t near = index.nearest(p, tol_sq);
    if (near >= 0 && !turned_away) {
      // A surface confirms a point only when it faces the same way: the far face of a thin plate
      // lies within tolerance of the near one's points but turned away.
      const Eigen::Vector3f& n_scene = index.normals()[static_cast<std::size_t>(near)];
      if (!n_scene.allFinite() || !n_model.allFinite() ||
          (T.linear() * n_model).dot(n_scene) > kMinNormalAgreement) {
        ++confirmed;
        continue;
      }
    }
    if (turned_away) {
      ++hidden;
      continue;
    }
    if (!organized || p.z() <= 0.0f)
      continue;
    const Eigen::Vector2d uv = sensor.project(p.cast<double>());
    const long u = std::lround(uv.x()), v = std::lround(uv.y());
    if (u < 0 || v < 0 || u >= sensor.width || v >= sensor.height)
      continue;
    const Eigen::Vector3f& s = scene.points_mm[static_cast<std::size_t>(v) * scene.width +
                                               static_cast<std::size_t>(u)];
    if (!isValid(s))
      continue;
    if (s.z() > p.z() + margin)
      ++violations;
    else if (s.z() < p.z() - margin)
      ++hidden;
  }
  const double expected =
      std::max(double(model_points.size() - hidden), kMinExpectedShare * double(model_points.size()));
  const double q = (double(confirmed) - double(violations)) / expected;
  return std::clamp(q, 0.0, 1.0) * edgeAgreement(model, index, T, tol_sq, edges);
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
  const bool verifying = params.matching.verify_tolerance_mm > 0;
  if ((verifying || params.refine.enabled) && cache.pre && cache.pre->validCount() > 0) {
    const auto t0 = Clock::now();
    prepareVerificationImpl(cache.index_key, cache.scene_index, cache.refine_model_for,
                            cache.refine_model_points, cache.refine_model, cache.verify_points,
                            *cache.pre, model,
                            pre_key, params);
    result.timings.matching_ms += msSince(t0);
  }
  const bool edge_check = verifying && params.matching.edge_tolerance_mm > 0;
  if (edge_check && (cache.edge_key != keypoint_key || !cache.edge_index)) {
    PointCloud all;
    for (const auto& k : *cache.keypoints)
      all.points_mm.insert(all.points_mm.end(), k.points_mm.begin(), k.points_mm.end());
    all.width = static_cast<std::uint32_t>(all.points_mm.size());
    all.height = 1;
    cache.edge_index = all.points_mm.empty() ? nullptr : std::make_shared<const SceneIndex>(all);
    cache.edge_key = keypoint_key;
  }
  const EdgeCheck edges{edge_check ? cache.edge_index.get() : nullptr,
                        params.matching.edge_tolerance_mm};
  {
    const std::lock_guard lock(m_mutex);
    m_cache = std::make_shared<Cache>(cache);
  }

  const auto t_match = Clock::now();
  PoseVerifier verify;
  if (verifying && cache.scene_index && cache.verify_points)
    verify = [&](const Eigen::Isometry3d& T) {
      return verifyPose(*cache.verify_points, *cache.scene_index, scene_mm, sensor, T,
                        params.matching.verify_tolerance_mm, edges);
    };
  std::vector<std::vector<MatchCandidate>> candidates(objects.size());
  forEachObject(objects.size(), progress, 0.8, 0.95, [&](std::size_t i) {
    candidates[i] = matchFeatures(model->features, (*cache.features)[i], params.matching, {}, verify);
  });
  for (std::size_t i = 0; i < candidates.size(); ++i)
    for (const auto& c : candidates[i]) {
      Detection d;
      d.T_scene_model = c.T_scene_model;
      d.feature_score = c.score;
      d.coverage = c.coverage;
      d.score = verify ? c.coverage : c.score;
      d.matched_features = c.matched_features;
      d.cluster = static_cast<int>(i);
      result.detections.push_back(std::move(d));
    }
  std::stable_sort(result.detections.begin(), result.detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  result.detections = suppressDuplicates(std::move(result.detections), 0.25 * model->diameter_mm);
  if (params.matching.max_detections > 0 &&
      result.detections.size() > static_cast<std::size_t>(params.matching.max_detections))
    result.detections.resize(static_cast<std::size_t>(params.matching.max_detections));
  result.timings.matching_ms += msSince(t_match);
  if (params.refine.enabled && cache.scene_index && cache.refine_model) {
    const auto t0 = Clock::now();
    tbb::parallel_for(std::size_t{0}, result.detections.size(), [&](std::size_t k) {
      Detection& d = result.detections[k];
      const RefinementResult r =
          refinePose(*cache.refine_model, *cache.scene_index, d.T_scene_model, params.refine);
      if (!verifying) {
        d.T_scene_model = r.T_scene_model;
        d.refined = true;
        return;
      }
      // The refined pose is kept only when it verifies at least as well: ICP can slide a part
      // seen edge-on along its extrusion.
      const double coverage = verifyPose(*cache.verify_points, *cache.scene_index, scene_mm,
                                         sensor, r.T_scene_model,
                                         params.matching.verify_tolerance_mm, edges);
      if (coverage >= d.coverage) {
        d.T_scene_model = r.T_scene_model;
        d.refined = true;
        d.coverage = coverage;
        d.score = coverage;
      }
    });
    std::stable_sort(result.detections.begin(), result.detections.end(),
                     [](const Detection& a, const Detection& b) { return a.score > b.score; });
    result.timings.refine_ms = msSince(t0);
  }
  for (auto& d : result.detections)
    for (const auto& g : model->grip_points)
      d.grip_points_scene.push_back({g.name, d.T_scene_model * g.position_mm});
  reportProgress(progress, 1.0);

  result.preprocessed = cache.pre;
  result.floor_points_removed = cache.floor_removed;
  result.objects = cache.objects;
  result.object_keypoints = cache.keypoints;
  result.object_features = cache.features;
  result.timings.total_ms = msSince(t_start);
  reportProgress(progress, 1.0);
  return result;
}

RecognitionResult recognizeViews(Recognizer& recognizer,
                                 const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                 const PointCloud& scene_mm, const SensorModel& sensor,
                                 const RecognitionParams& params, const ProgressFn& progress) {
  if (models.empty())
    throw Error("no model to recognize: give at least one .spmodel");
  RecognitionResult merged;
  double diameter_mm = 0.0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    recognizer.setModel(models[m]);
    const double begin = double(m) / double(models.size());
    RecognitionResult r = recognizer.recognize(
        scene_mm, sensor, params, subProgress(progress, begin, begin + 1.0 / double(models.size())));
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
  std::stable_sort(merged.detections.begin(), merged.detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  merged.detections = suppressDuplicates(std::move(merged.detections), 0.3 * diameter_mm);
  if (params.matching.max_detections > 0 &&
      merged.detections.size() > static_cast<std::size_t>(params.matching.max_detections))
    merged.detections.resize(static_cast<std::size_t>(params.matching.max_detections));
  return merged;
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
