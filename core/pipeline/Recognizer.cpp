#include "core/pipeline/Recognizer.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/common/ParallelProgress.h"
#include "core/features/FeatureExtraction.h"
#include "core/matching/FeatureMatcher.h"
#include "core/matching/PointPairVoting.h"
#include "core/pipeline/DetectionSteps.h"
#include "core/pipeline/ModelPrep.h"
#include "core/pipeline/PoseVerification.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/preprocess/SceneSplit.h"
#include "core/refine/PoseRefinement.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

namespace scanpick::core {
namespace {

using detail::kIcpCoverageSlack;
using detail::ModelPrep;
using detail::placeDetections;
using detail::PosePolisher;
using detail::PoseRescue;
using detail::refineDetections;
using detail::resolveDetectionTurns;
using detail::surfaceDetections;

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// FNV-1a over 8-byte words in four interleaved lanes (a PhoXi scan is 9 MB, hashed for each view
/// of a part: one lane waits on each multiply): the scene's identity for the cache (content, not
/// address, so a re-captured identical scan hits and an edited buffer misses).
std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t h) {
  constexpr std::uint64_t kPrime = 1099511628211ull;
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::uint64_t lanes[4] = {h, h ^ 1, h ^ 2, h ^ 3};
  std::size_t i = 0;
  for (; i + 32 <= size; i += 32)
    for (int k = 0; k < 4; ++k) {
      std::uint64_t word = 0;
      std::memcpy(&word, bytes + i + 8 * k, 8);
      lanes[k] = (lanes[k] ^ word) * kPrime;
    }
  for (const std::uint64_t lane : lanes)
    h = (h ^ lane) * kPrime;
  for (; i < size; ++i)
    h = (h ^ bytes[i]) * kPrime;
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
  const double values[] = {
      double(s.width), double(s.height),     s.fx, s.fy, s.cx, s.cy, s.min_range_mm,
      s.max_range_mm,  s.nominal_distance_mm};
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

/// The scene is paired within this much more than the diameter of the view that needs it, so that
/// the other views of a part (their diameters differ by a few per cent) share the pairing.
constexpr double kPairingMargin = 1.1;

/// Point-level verification of poses of `prep`'s view in `scene`. A search that drops every pose
/// scoring under `drop_below` may skip those poses' edge check (verifyPose). Every argument taken
/// by reference must outlive the verifier.
PoseVerifier verifierFor(const ModelPrep& prep, const VerifyScene& scene, double tolerance_mm,
                         const EdgeCheck& edges, double drop_below = 0.0) {
  return [&prep, &scene, tolerance_mm, &edges, drop_below](const Eigen::Isometry3d& T) {
    return verifyPose(*prep.verify, scene, T, tolerance_mm, edges, drop_below);
  };
}

/// ICP of `prep`'s view in `scene` where the view was prepared for it, else the pose unchanged.
/// Every argument must outlive the polisher.
PosePolisher polisherFor(const ModelPrep& prep, const SceneIndex& scene,
                         const RefineParams& params) {
  return [&prep, &scene, &params](const Eigen::Isometry3d& T) {
    return prep.refine ? refinePose(*prep.refine, scene, T, params).T_scene_model : T;
  };
}

} // namespace

struct Recognizer::Cache {
  std::optional<PreKey> pre_key;
  std::shared_ptr<const PointCloud> pre;
  std::size_t floor_removed = 0;
  std::optional<Eigen::Vector4f> floor_plane; ///< the largest plane removed (key: pre_key)
  std::optional<SplitKey> split_key;
  std::shared_ptr<const std::vector<PointCloud>> objects;
  std::optional<KeypointKey> keypoint_key;
  std::shared_ptr<const std::vector<Keypoints>> keypoints;
  std::optional<FeatureKey> feature_key;
  std::shared_ptr<const std::vector<FeatureList>> features;
  /// Verification and refinement: the preprocessed scene indexed with the sensor (key: pre_key and
  /// the sensor's hash), and the preparation of the last few models searched (views alternate
  /// from scene to scene).
  std::optional<std::pair<PreKey, std::uint64_t>> index_key;
  std::shared_ptr<const SceneIndex> scene_index;
  /// The scan's projector shadows (key: the scan's and the sensor's hashes).
  std::optional<std::pair<std::uint64_t, std::uint64_t>> shadow_key;
  std::shared_ptr<const ProjectorShadow> shadow;
  std::vector<std::shared_ptr<const ModelPrep>> model_preps;
  /// Every object's keypoints in one index (key: keypoint_key), for the edge check.
  std::optional<KeypointKey> edge_key;
  std::shared_ptr<const SceneIndex> edge_index;
  /// Surface voting: the sampled scene (key: pre_key and the sampling).
  std::optional<PreKey> surface_scene_key;
  double surface_scene_sampling = 0.0;
  std::shared_ptr<const OrientedPoints> surface_scene;
  /// How the views have voted with surface_scene: by stride and quantizer, and the scene paired
  /// (ScenePairs) for those alike, shared by those whose diameter its radius and whose keys its
  /// keys cover. For prepared views that vote alike the scene is paired beside the feature search.
  /// A view voting with its own stride (the cup's bottom view) pairs as it votes (paired beside
  /// the feature search instead, it competed with it for the cores and was no faster), and so
  /// does the first of views not prepared beforehand.
  struct SurfacePairing {
    int stride = 0;
    PairQuantizer quantizer;
    std::shared_ptr<const ScenePairs> pairs; ///< null while one view has voted so
    PairKeySet keys;                         ///< the keys paired
  };
  std::vector<SurfacePairing> surface_pairings;

  /// The scene sampled at `sampling_mm` from scene_index (made if missing) and paired for the
  /// views whose table keys are `keys`, the largest `diameter_mm` across, voting with `stride` and
  /// `quantizer`: paired again when missing, within a smaller radius or for other keys (then for
  /// theirs too), except for the first view to vote so, which pairs as it votes (null) unless
  /// `pair_now`.
  std::shared_ptr<const ScenePairs> pairScene(const PreKey& key, double sampling_mm, int stride,
                                              const PairQuantizer& quantizer, double diameter_mm,
                                              PairKeySet keys, bool pair_now,
                                              const ProgressFn& progress) {
    if (surface_scene_key != key || surface_scene_sampling != sampling_mm) {
      surface_scene = std::make_shared<const OrientedPoints>(
          sampleOriented(scene_index->points(), scene_index->normals(), sampling_mm));
      surface_scene_key = key;
      surface_scene_sampling = sampling_mm;
      surface_pairings.clear();
    }
    auto pairing = std::find_if(
        surface_pairings.begin(), surface_pairings.end(),
        [&](const SurfacePairing& p) { return p.stride == stride && p.quantizer == quantizer; });
    if (pairing == surface_pairings.end()) {
      pairing = surface_pairings.insert(surface_pairings.end(), {stride, quantizer, nullptr, {}});
      if (!pair_now)
        return nullptr;
    }
    if (!pairing->pairs || pairing->pairs->radius() < diameter_mm || !keys.within(pairing->keys)) {
      keys.add(pairing->keys);
      pairing->keys = keys;
      pairing->pairs = std::make_shared<const ScenePairs>(
          *surface_scene, quantizer, stride,
          std::max(kPairingMargin * diameter_mm, pairing->pairs ? pairing->pairs->radius() : 0.0),
          std::move(keys), progress);
    }
    return pairing->pairs;
  }
};

namespace {
/// A scene pairing that two or more prepared views vote with (the same stride and quantizer, at
/// the same sampling), the diameter of the largest of them and the keys of their tables.
struct SharedPairing {
  int stride = 0;
  PairQuantizer quantizer;
  double diameter_mm = 0.0;
  int views = 0;
  PairKeySet keys;
};

/// The pairings of the scene sampled at `sampling_mm` that two or more of the prepared views
/// share, their strides each view's own (`requested` with the view's parameters).
std::vector<SharedPairing>
sharedPairings(const std::vector<std::shared_ptr<const ModelPrep>>& preps,
               const RecognitionParams& requested, double sampling_mm) {
  std::vector<SharedPairing> all;
  for (const auto& prep : preps) {
    if (!prep->pairs || prep->surface_sampling_mm != sampling_mm)
      continue;
    const int stride = std::max(
        1, withViewParams(requested, prep->model->view_params).matching.surface_reference_stride);
    const PairQuantizer& quantizer = prep->pairs->quantizer();
    auto shared = std::find_if(all.begin(), all.end(), [&](const SharedPairing& p) {
      return p.stride == stride && p.quantizer == quantizer;
    });
    if (shared == all.end())
      shared = all.insert(all.end(), {stride, quantizer, 0.0, 0, {}});
    shared->diameter_mm = std::max(shared->diameter_mm, prep->pairs->diameter());
    shared->keys.add(*prep->pairs);
    ++shared->views;
  }
  std::erase_if(all, [](const SharedPairing& p) { return p.views < 2; });
  return all;
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

Recognizer::Cache Recognizer::cacheSnapshot() const {
  const std::lock_guard lock(m_mutex);
  return m_cache ? *m_cache : Cache{};
}

namespace {
void requireModel(const std::shared_ptr<const TaughtModel>& model, const char* action) {
  if (!model)
    throw Error(std::string("no model to ") + action +
                ": teach a part or open a .spmodel file first");
}
} // namespace

void Recognizer::prepare(const RecognitionParams& requested) {
  prepare(model(), requested);
}

void Recognizer::prepare(const std::shared_ptr<const TaughtModel>& model,
                         const RecognitionParams& requested) {
  requireModel(model, "prepare");
  const RecognitionParams params = withViewParams(requested, model->view_params);
  if (!detail::needsModelPrep(params))
    return;
  Cache cache = cacheSnapshot();
  detail::prepareModel(cache.model_preps, model, params);
  // Only the preparations go back: a recognition running meanwhile may have cached scene stages.
  const std::lock_guard lock(m_mutex);
  m_cache = std::make_shared<Cache>(m_cache ? *m_cache : Cache{});
  m_cache->model_preps = cache.model_preps;
}

std::size_t Recognizer::preparedModels() const {
  const std::lock_guard lock(m_mutex);
  return m_cache ? m_cache->model_preps.size() : 0;
}

void Recognizer::clearCache() {
  const std::lock_guard lock(m_mutex);
  m_cache.reset();
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
  return recognize(model, scene_mm, sensor, requested, progress, Turns::Resolve);
}

RecognitionResult Recognizer::recognize(const std::shared_ptr<const TaughtModel>& model,
                                        const PointCloud& scene_mm, const SensorModel& sensor,
                                        const RecognitionParams& requested,
                                        const ProgressFn& progress, Turns turns) {
  const auto t_start = Clock::now();
  requireModel(model, "recognize");
  Cache cache = cacheSnapshot();
  const RecognitionParams params = withViewParams(requested, model->view_params);
  scene_mm.validate();
  if (!scene_mm.hasValidPoint())
    throw Error("the scene has no valid point (empty or all NaN): check the scan file or the "
                "camera capture");
  RecognitionResult result;

  const PreKey pre_key{sceneHash(scene_mm), params.floor, params.downsample, params.seed};
  if (cache.pre_key != pre_key) {
    const auto t0 = Clock::now();
    FloorRemovalResult floor =
        removeFloor(scene_mm, params.floor, params.seed, subProgress(progress, 0.0, 0.1));
    cache.floor_removed = floor.removed_points;
    cache.floor_plane = floor.planes.empty() ? std::nullopt : std::optional(floor.planes.front());
    // Without a voxel size the scan stays as it is: moved, not copied (a PhoXi scan is 9 MB).
    cache.pre = std::make_shared<const PointCloud>(
        params.downsample.voxel_mm > 0
            ? voxelDownsample(floor.remaining, params.downsample.voxel_mm)
            : std::move(floor.remaining));
    cache.pre_key = pre_key;
    cache.split_key.reset();
    result.timings.preprocess_ms = msSince(t0);
  }
  reportProgress(progress, 0.1);

  // Verification's scene index (the scan's normals), the sampled scene and its pairings for
  // surface voting, and projector shadows depend on the preprocessed scan alone: they are built
  // in tasks while the scene is split and its features found, which use both cores only in
  // part. Each is the same whichever thread builds it.
  const bool preparing = detail::needsModelPrep(params) && cache.pre && cache.pre->hasValidPoint();
  const std::pair index_key{pre_key, sensorHash(sensor)};
  const std::pair shadow_key{pre_key.scene, sensorHash(sensor)};
  const double sampling_mm = params.matching.surface_sampling_mm;
  const bool verifying = params.matching.verify_tolerance_mm > 0;
  tbb::task_group scene_tasks;
  if (preparing) {
    const bool index = cache.index_key != index_key || !cache.scene_index;
    if (index)
      cache.scene_index.reset();
    cache.index_key = index_key;
    // Pairings that prepared views share are made now, not when the second of them votes.
    std::vector<SharedPairing> shared;
    if (verifying && sampling_mm > 0)
      shared = sharedPairings(cache.model_preps, requested, sampling_mm);
    if (index || !shared.empty())
      scene_tasks.run([&, index, shared = std::move(shared), scene = cache.pre] {
        if (index) {
          const auto t0 = Clock::now();
          SceneIndexOptions options;
          options.normal_radius_mm = params.keypoints.normal_radius_mm;
          options.sensor = sensor;
          cache.scene_index = std::make_shared<const SceneIndex>(*scene, options);
          logger()->debug("scene indexed for verification: {} points, {:.0f} ms; they lie within "
                          "{:.3f} px of where the sensor projects them (nearest points are looked "
                          "for in pixel windows up to {} px)",
                          cache.scene_index->points().size(), msSince(t0),
                          cache.scene_index->pixelSlack(), kMaxPixelWindowSlack);
        }
        for (const SharedPairing& p : shared)
          cache.pairScene(pre_key, sampling_mm, p.stride, p.quantizer, p.diameter_mm, p.keys, true,
                          {});
      });
  }
  if (preparing && (cache.shadow_key != shadow_key || !cache.shadow)) {
    cache.shadow.reset();
    scene_tasks.run(
        [&] { cache.shadow = std::make_shared<const ProjectorShadow>(scene_mm, sensor); });
    cache.shadow_key = shadow_key;
  }

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
    parallelForWithProgress(objects.size(), subProgress(progress, 0.3, 0.55), [&](std::size_t i) {
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
    parallelForWithProgress(objects.size(), subProgress(progress, 0.55, 0.8), [&](std::size_t i) {
      // Each object draws from its own stream, so results do not depend on scheduling.
      features[i] = extractFeatures((*cache.keypoints)[i].points_mm, params.features,
                                    params.seed + 0x9E3779B97F4A7C15ull * (i + 1))
                        .features;
    });
    cache.features = std::make_shared<const std::vector<FeatureList>>(std::move(features));
    cache.feature_key = feature_key;
    result.timings.features_ms = msSince(t0);
  }
  // The edge check's keypoint index while the scene tasks may still run.
  const bool edge_check = verifying && params.matching.edge_tolerance_mm > 0;
  if (edge_check && (cache.edge_key != keypoint_key || !cache.edge_index)) {
    const auto t0 = Clock::now();
    const PointCloud all = edgeKeypointCloud(*cache.keypoints, sensor);
    SceneIndexOptions nearest_only; // the edge check asks for the nearest keypoint only
    nearest_only.estimate_normals = false;
    nearest_only.sensor = sensor;
    cache.edge_index =
        !all.hasValidPoint() ? nullptr : std::make_shared<const SceneIndex>(all, nearest_only);
    logger()->debug("edge check: {} keypoints indexed, {} (slack {:.3f} px)",
                    cache.edge_index ? cache.edge_index->size() : 0,
                    cache.edge_index && cache.edge_index->width() > 0 ? "by pixel" : "as a list",
                    cache.edge_index ? cache.edge_index->pixelSlack() : -1.0f);
    cache.edge_key = keypoint_key;
    result.timings.matching_ms += msSince(t0);
  }
  std::shared_ptr<const ModelPrep> prep;
  if (preparing) {
    const auto t0 = Clock::now(); // what the scene tasks still need is matching's time
    scene_tasks.wait();
    prep = detail::prepareModel(cache.model_preps, model, params);
    result.timings.matching_ms += msSince(t0);
  }
  const EdgeCheck edges{edge_check ? cache.edge_index.get() : nullptr,
                        params.matching.edge_tolerance_mm};
  const bool surface = verifying && sampling_mm > 0 && prep;
  std::shared_ptr<const ScenePairs> scene_pairs;
  if (surface) {
    const auto t0 = Clock::now();
    const PointPairModel& view = *prep->pairs;
    PairKeySet keys;
    keys.add(view);
    scene_pairs = cache.pairScene(
        pre_key, sampling_mm, std::max(1, params.matching.surface_reference_stride),
        view.quantizer(), view.diameter(), std::move(keys), false, subProgress(progress, 0.8, 0.8));
    result.timings.matching_ms += msSince(t0);
  }
  {
    const std::lock_guard lock(m_mutex);
    m_cache = std::make_shared<Cache>(cache);
  }

  const auto t_match = Clock::now();
  const VerifyScene verify_scene{cache.scene_index.get(), &scene_mm, &sensor, cache.floor_plane,
                                 cache.shadow.get()};
  const auto verifierFrom = [&](double drop_below) -> PoseVerifier {
    return verifying && prep ? verifierFor(*prep, verify_scene, params.matching.verify_tolerance_mm,
                                           edges, drop_below)
                             : PoseVerifier{};
  };
  const PoseVerifier verify = verifierFrom(0.0);
  // The pooled search keeps the poses reaching the minimum coverage, and nothing else of them.
  const PoseVerifier verify_pooled =
      params.matching.pool_size > 0 ? verifierFrom(params.matching.min_coverage) : verify;
  std::vector<std::vector<MatchCandidate>> candidates(objects.size());
  parallelForWithProgress(objects.size(), subProgress(progress, 0.8, 0.95), [&](std::size_t i) {
    candidates[i] =
        matchFeatures(model->features, (*cache.features)[i], params.matching, {}, verify_pooled);
  });
  logger()->debug("feature matching: {} model features, {:.0f} ms", model->features.size(),
                  msSince(t_match));
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
  // ICP where the model was prepared for it (refinement, surface voting, near symmetries).
  const PosePolisher polish =
      prep ? polisherFor(*prep, *cache.scene_index, params.refine) : PosePolisher{};
  // A view that is a surface of revolution but for a detail may be found turned about its axis,
  // its detail (a cup's handle) where the scan has none: the turn its detail says can verify. (Its
  // own detail only: a turn the joined detail says keeps the coverage the pose was found with.)
  PoseRescue rescue;
  if (verify && prep->near_axis)
    rescue = [&](Detection& d) {
      const auto turn = detail::turnByDetail(*prep, verify_scene, params.matching, verify, polish,
                                             d.T_scene_model, d.coverage, false);
      if (turn && turn->coverage > d.coverage)
        detail::takeTurn(d, *turn);
    };
  if (surface) {
    // A voted pose under half the minimum coverage is neither polished nor rescued, and ICP's pose
    // replaces it only within kIcpCoverageSlack: under that, its score only has to stay under.
    const PoseVerifier verify_voted =
        verifierFrom(0.5 * params.matching.min_coverage - kIcpCoverageSlack);
    for (auto& d :
         surfaceDetections(*prep->pairs, *cache.surface_scene, scene_pairs.get(), model->features,
                           *cache.features, params.matching, kVoteClusterShare * model->diameter_mm,
                           verify_voted, polish, rescue, subProgress(progress, 0.95, 0.98)))
      result.detections.push_back(std::move(d));
  }
  sortBestFirst(result.detections);
  result.detections =
      suppressDuplicates(std::move(result.detections), kDuplicateShare * model->diameter_mm);
  if (turns == Turns::Resolve && prep)
    resolveDetectionTurns(result.detections, *prep, verify_scene, params.matching, verify, polish,
                          kDuplicateShare * model->diameter_mm);
  if (params.matching.max_detections > 0 &&
      result.detections.size() > static_cast<std::size_t>(params.matching.max_detections))
    result.detections.resize(static_cast<std::size_t>(params.matching.max_detections));
  result.timings.matching_ms += msSince(t_match);
  if (params.refine.enabled && prep) {
    const auto t0 = Clock::now();
    refineDetections(result.detections, *prep, *cache.scene_index, params.refine, verify);
    result.timings.refine_ms = msSince(t0);
  }
  placeDetections(result.detections, *model, prep.get(), verify ? &verify_scene : nullptr,
                  params.matching.verify_tolerance_mm);
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

Recognizer::Cache Recognizer::recognizedScene(const PointCloud& scene_mm, const SensorModel& sensor,
                                              const RecognitionParams& params,
                                              const char* action) const {
  Cache cache = cacheSnapshot();
  const PreKey pre_key{sceneHash(scene_mm), params.floor, params.downsample, params.seed};
  if (cache.pre_key != pre_key || !cache.pre)
    throw Error(std::string(action) + " needs the scene recognized first, with the same floor, "
                                      "downsampling and seed");
  const std::pair index_key{pre_key, sensorHash(sensor)};
  if (cache.index_key != index_key || !cache.scene_index) {
    SceneIndexOptions options;
    options.normal_radius_mm = params.keypoints.normal_radius_mm;
    options.sensor = sensor;
    cache.scene_index = std::make_shared<const SceneIndex>(*cache.pre, options);
    cache.index_key = index_key;
  }
  return cache;
}

struct Recognizer::PreparedScene {
  Cache cache;
  std::shared_ptr<const ModelPrep> prep;
  VerifyScene scene; ///< into `cache`, and the caller's scan and sensor
  EdgeCheck edges;
};

Recognizer::PreparedScene Recognizer::preparedScene(const std::shared_ptr<const TaughtModel>& model,
                                                    const PointCloud& scene_mm,
                                                    const SensorModel& sensor,
                                                    const RecognitionParams& params,
                                                    const char* action) {
  PreparedScene out;
  out.cache = recognizedScene(scene_mm, sensor, params, action);
  out.prep = detail::prepareModel(out.cache.model_preps, model, params);
  {
    const std::lock_guard lock(m_mutex);
    m_cache = std::make_shared<Cache>(out.cache);
  }
  out.scene = {out.cache.scene_index.get(), &scene_mm, &sensor, out.cache.floor_plane,
               out.cache.shadow.get()};
  out.edges = {params.matching.edge_tolerance_mm > 0 ? out.cache.edge_index.get() : nullptr,
               params.matching.edge_tolerance_mm};
  return out;
}

void Recognizer::refine(const std::shared_ptr<const TaughtModel>& model,
                        std::vector<Detection>& detections, const PointCloud& scene_mm,
                        const SensorModel& sensor, const RecognitionParams& requested) {
  requireModel(model, "refine");
  const RecognitionParams params = withViewParams(requested, model->view_params);
  if (!params.refine.enabled || detections.empty())
    return;
  const PreparedScene at = preparedScene(model, scene_mm, sensor, params, "refinement");
  const double tolerance = params.matching.verify_tolerance_mm;
  const PoseVerifier verify =
      tolerance > 0 ? verifierFor(*at.prep, at.scene, tolerance, at.edges) : PoseVerifier{};
  refineDetections(detections, *at.prep, *at.cache.scene_index, params.refine, verify);
  placeDetections(detections, *model, at.prep.get(), verify ? &at.scene : nullptr, tolerance);
}

void Recognizer::resolveTurns(const std::shared_ptr<const TaughtModel>& model,
                              std::vector<Detection>& detections, const PointCloud& scene_mm,
                              const SensorModel& sensor, const RecognitionParams& requested) {
  requireModel(model, "resolve turns");
  const RecognitionParams params = withViewParams(requested, model->view_params);
  const double tolerance = params.matching.verify_tolerance_mm;
  if (!detail::needsModelPrep(params) || !(tolerance > 0) || detections.empty())
    return;
  const PreparedScene at = preparedScene(model, scene_mm, sensor, params, "resolving turns");
  const ModelPrep& prep = *at.prep;
  if (!prep.near_axis && prep.symmetries.empty())
    return;
  const PoseVerifier verify = verifierFor(prep, at.scene, tolerance, at.edges);
  const PosePolisher polish = polisherFor(prep, *at.cache.scene_index, params.refine);
  sortBestFirst(detections);
  resolveDetectionTurns(detections, prep, at.scene, params.matching, verify, polish,
                        kDuplicateShare * model->diameter_mm);
  placeDetections(detections, *model, &prep, &at.scene, tolerance);
}

PartScorer Recognizer::partScorer(const std::vector<std::shared_ptr<const TaughtModel>>& models,
                                  const PointCloud& scene_mm, const SensorModel& sensor,
                                  const RecognitionParams& requested) {
  auto cache = std::make_shared<Cache>(
      recognizedScene(scene_mm, sensor, requested, "scoring on the whole part"));
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
    const auto prep = detail::prepareModel(cache->model_preps, models[m], params);
    ViewPart& view = views[m];
    view.tolerance_mm = params.matching.verify_tolerance_mm;
    if (!prep->joined_points || !(view.tolerance_mm > 0))
      continue;
    view.points = prep->joined_points;
    const std::size_t count = view.points->points.size();
    const std::size_t stride = std::max<std::size_t>(1, count / kPartScorePoints);
    for (std::size_t k = 0; k < count; k += stride)
      view.every.push_back(static_cast<std::uint32_t>(k));
  }
  {
    const std::lock_guard lock(m_mutex);
    m_cache = std::make_shared<Cache>(*cache);
  }
  const VerifyScene scene{cache->scene_index.get(), &scene_mm, &sensor, cache->floor_plane,
                          cache->shadow.get()};
  // `cache` keeps what `scene` points to alive.
  return [cache, views = std::move(views), scene](const Detection& d) {
    if (d.model_index < 0 || static_cast<std::size_t>(d.model_index) >= views.size())
      throw Error("a detection names view " + std::to_string(d.model_index) + " of " +
                  std::to_string(views.size()));
    const ViewPart& view = views[static_cast<std::size_t>(d.model_index)];
    if (!view.points)
      return std::numeric_limits<double>::quiet_NaN();
    const PointTally t = tallyPoints(*view.points, scene, d.T_scene_model, view.tolerance_mm,
                                     {.subset = &view.every, .stop = {}, .sort_unmeasured = true});
    const double expected = double(t.points) - double(t.hidden) - double(t.shadowed);
    return expected > 0 ? (double(t.confirmed) - double(t.violations)) / expected : 0.0;
  };
}

} // namespace scanpick::core
