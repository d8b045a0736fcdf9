/// @file SceneAnalysis.cpp
/// The scene stages of recognition, memoized by their keys (StageMemo.h).

#include "core/common/Log.h"
#include "core/common/ParallelProgress.h"
#include "core/features/FeatureExtraction.h"
#include "core/pipeline/ProgressShares.h"
#include "core/pipeline/StageMemo.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/preprocess/SceneSplit.h"
#include "core/verification/PoseVerification.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <tbb/task_group.h>

namespace scanpick::core::detail {
namespace {

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

} // namespace

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

namespace {
/// The points of `index` (built on `with_walls`) that `pre` holds too, with their normals: the
/// walls left out. `pre`'s valid points are those of `with_walls` less the walls, in their order.
OrientedPoints withoutWalls(const SceneIndex& index, const PointCloud& pre,
                            const PointCloud& with_walls) {
  OrientedPoints out;
  std::size_t k = 0, next = 0; // k: index point; next: the next of pre's points to meet
  for (const Eigen::Vector3f& p : with_walls.points_mm) {
    if (!isValid(p))
      continue;
    while (next < pre.size() && !isValid(pre.points_mm[next]))
      ++next;
    if (next < pre.size() && pre.points_mm[next] == p) {
      out.points.push_back(index.points()[k]);
      out.normals.push_back(index.normals()[k]);
      ++next;
    }
    ++k;
  }
  return out;
}
} // namespace

std::shared_ptr<const ScenePairs> StageMemo::pairScene(const PreKey& key, double sampling_mm,
                                                       int stride, const PairQuantizer& quantizer,
                                                       double diameter_mm, PairKeySet keys,
                                                       bool pair_now, const ProgressFn& progress) {
  if (surface_scene_key != key || surface_scene_sampling != sampling_mm) {
    // The walls do not vote: a part's flat face would match them all along.
    const bool walls_apart = pre != pre_with_walls;
    const OrientedPoints without =
        walls_apart ? withoutWalls(*scene_index, *pre, *pre_with_walls) : OrientedPoints{};
    surface_scene = std::make_shared<const OrientedPoints>(
        sampleOriented(walls_apart ? without.points : scene_index->points(),
                       walls_apart ? without.normals : scene_index->normals(), sampling_mm));
    surface_scene_key = key;
    surface_scene_sampling = sampling_mm;
    surface_pairings.clear();
  }
  auto pairing =
      std::find_if(surface_pairings.begin(), surface_pairings.end(), [&](const SurfacePairing& p) {
        return p.stride == stride && p.quantizer == quantizer;
      });
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

namespace {

/// Floor removal and downsampling (progress: kProgressShares.preprocess).
void preprocessStage(StageMemo& memo, const PreKey& key, const PointCloud& scan_mm,
                     const RecognitionParams& params, const ProgressFn& progress,
                     StageTimings& timings) {
  if (memo.pre_key == key)
    return;
  const auto t0 = Clock::now();
  FloorRemovalResult floor = removeFloor(scan_mm, params.floor, params.seed,
                                         subProgress(progress, kProgressShares.preprocess));
  memo.floor_removed = floor.removed_points;
  memo.floor_plane = floor.resting_plane;
  // Without a voxel size the scan stays as it is: moved, not copied (a PhoXi scan is 9 MB).
  const double voxel_mm = params.downsample.voxel_mm;
  memo.pre = std::make_shared<const PointCloud>(
      voxel_mm > 0 ? voxelDownsample(floor.remaining, voxel_mm) : std::move(floor.remaining));
  // Downsampled, the scene's points are no longer the scan's, and withoutWalls could not tell the
  // walls among them: the walls then stay out of the index too.
  memo.pre_with_walls =
      floor.remaining_with_walls.empty() || voxel_mm > 0
          ? memo.pre
          : std::make_shared<const PointCloud>(std::move(floor.remaining_with_walls));
  memo.pre_key = key;
  memo.split_key.reset();
  timings.preprocess_ms = msSince(t0);
}

/// Starts in `tasks` what depends on the preprocessed scan alone: verification's scene index (the
/// scan's normals), the pairings of the sampled scene that the views prepared in `memo` share,
/// and the projector shadows. They run while the scene is split and its features found, which use
/// both cores only in part; each is the same whichever thread builds it. `memo` must outlive the
/// tasks, and nothing else may touch the fields they write until they are waited for.
void startSceneTasks(tbb::task_group& tasks, StageMemo& memo, const PreKey& pre_key,
                     const PointCloud& scan_mm, const SensorModel& sensor,
                     const RecognitionParams& params, const RecognitionParams& requested) {
  const std::pair index_key{pre_key, sensorHash(sensor)};
  const std::pair shadow_key{pre_key.scene, sensorHash(sensor)};
  const double sampling_mm = params.matching.surface_sampling_mm;
  const bool index = memo.index_key != index_key || !memo.scene_index;
  if (index)
    memo.scene_index.reset();
  memo.index_key = index_key;
  // Pairings that prepared views share are made now, not when the second of them votes.
  std::vector<SharedPairing> shared;
  if (params.matching.verify_tolerance_mm > 0 && sampling_mm > 0)
    shared = sharedPairings(memo.model_preps, requested, sampling_mm);
  if (index || !shared.empty())
    tasks.run([&memo, &sensor, &params, pre_key, sampling_mm, index, shared = std::move(shared),
               scene = memo.pre_with_walls] {
      if (index) {
        const auto t0 = Clock::now();
        SceneIndexOptions options;
        options.normal_radius_mm = params.keypoints.normal_radius_mm;
        options.sensor = sensor;
        memo.scene_index = std::make_shared<const SceneIndex>(*scene, options);
        logger()->debug("scene indexed for verification: {} points, {:.0f} ms; they lie within "
                        "{:.3f} px of where the sensor projects them (nearest points are looked "
                        "for in pixel windows up to {} px)",
                        memo.scene_index->points().size(), msSince(t0),
                        memo.scene_index->pixelSlack(), kMaxPixelWindowSlack);
      }
      for (const SharedPairing& p : shared)
        memo.pairScene(pre_key, sampling_mm, p.stride, p.quantizer, p.diameter_mm, p.keys, true,
                       {});
    });
  if (memo.shadow_key != shadow_key || !memo.shadow) {
    memo.shadow.reset();
    tasks.run([&memo, &scan_mm, &sensor] {
      memo.shadow = std::make_shared<const ProjectorShadow>(scan_mm, sensor);
    });
    memo.shadow_key = shadow_key;
  }
}

/// The split into objects (progress: kProgressShares.split).
void splitStage(StageMemo& memo, const SplitKey& key, const SensorModel& sensor,
                const RecognitionParams& params, const ProgressFn& progress,
                StageTimings& timings) {
  if (memo.split_key == key)
    return;
  const auto t0 = Clock::now();
  SceneSplit split = splitIntoObjects(*memo.pre, sensor, params.clustering, params.seed,
                                      subProgress(progress, kProgressShares.split));
  memo.objects = std::make_shared<const std::vector<PointCloud>>(std::move(split.objects));
  memo.split_key = key;
  memo.keypoint_key.reset();
  timings.clustering_ms = msSince(t0);
}

/// Each object's keypoints (progress: kProgressShares.keypoints).
void keypointStage(StageMemo& memo, const KeypointKey& key, const RecognitionParams& params,
                   const ProgressFn& progress, StageTimings& timings) {
  if (memo.keypoint_key == key)
    return;
  const auto t0 = Clock::now();
  const auto& objects = *memo.objects;
  std::vector<Keypoints> keypoints(objects.size());
  parallelForWithProgress(
      objects.size(), subProgress(progress, kProgressShares.keypoints),
      [&](std::size_t i) { keypoints[i] = extractKeypoints(objects[i], params.keypoints); });
  memo.keypoints = std::make_shared<const std::vector<Keypoints>>(std::move(keypoints));
  memo.keypoint_key = key;
  memo.feature_key.reset();
  timings.keypoints_ms = msSince(t0);
}

/// Each object's features (progress: kProgressShares.features).
void featureStage(StageMemo& memo, const FeatureKey& key, const RecognitionParams& params,
                  const ProgressFn& progress, StageTimings& timings) {
  if (memo.feature_key == key)
    return;
  const auto t0 = Clock::now();
  const std::size_t objects = memo.objects->size();
  std::vector<FeatureList> features(objects);
  parallelForWithProgress(
      objects, subProgress(progress, kProgressShares.features), [&](std::size_t i) {
        // Each object draws from its own stream, so results do not depend on scheduling.
        features[i] = extractFeatures((*memo.keypoints)[i].points_mm, params.features,
                                      params.seed + 0x9E3779B97F4A7C15ull * (i + 1))
                          .features;
      });
  memo.features = std::make_shared<const std::vector<FeatureList>>(std::move(features));
  memo.feature_key = key;
  timings.features_ms = msSince(t0);
}

/// The edge check's index of every object's keypoints.
void edgeIndexStage(StageMemo& memo, const KeypointKey& key, const SensorModel& sensor,
                    StageTimings& timings) {
  if (memo.edge_key == key && memo.edge_index)
    return;
  const auto t0 = Clock::now();
  const PointCloud all = edgeKeypointCloud(*memo.keypoints, sensor);
  SceneIndexOptions nearest_only; // the edge check asks for the nearest keypoint only
  nearest_only.estimate_normals = false;
  nearest_only.sensor = sensor;
  memo.edge_index =
      !all.hasValidPoint() ? nullptr : std::make_shared<const SceneIndex>(all, nearest_only);
  logger()->debug("edge check: {} keypoints indexed, {} (slack {:.3f} px)",
                  memo.edge_index ? memo.edge_index->size() : 0,
                  memo.edge_index && memo.edge_index->width() > 0 ? "by pixel" : "as a list",
                  memo.edge_index ? memo.edge_index->pixelSlack() : -1.0f);
  memo.edge_key = key;
  timings.matching_ms += msSince(t0);
}

} // namespace

SceneAnalysis analyzeScene(StageMemo& memo, const PointCloud& scan_mm, const SensorModel& sensor,
                           const RecognitionParams& params, const RecognitionParams& requested,
                           const ProgressFn& progress, StageTimings& timings) {
  const PreKey pre_key{sceneHash(scan_mm), params.floor, params.downsample, params.seed};
  preprocessStage(memo, pre_key, scan_mm, params, progress, timings);
  reportProgress(progress, kProgressShares.preprocess.end);
  const bool preparing = needsModelPrep(params) && memo.pre && memo.pre->hasValidPoint();
  tbb::task_group scene_tasks;
  if (preparing)
    startSceneTasks(scene_tasks, memo, pre_key, scan_mm, sensor, params, requested);
  const SplitKey split_key{pre_key, params.clustering, sensorHash(sensor)};
  splitStage(memo, split_key, sensor, params, progress, timings);
  reportProgress(progress, kProgressShares.split.end);
  const KeypointKey keypoint_key{split_key, params.keypoints};
  keypointStage(memo, keypoint_key, params, progress, timings);
  featureStage(memo, {keypoint_key, params.features}, params, progress, timings);
  // The edge check's keypoint index while the scene tasks may still run.
  const bool edge_check =
      params.matching.verify_tolerance_mm > 0 && params.matching.edge_tolerance_mm > 0;
  if (edge_check)
    edgeIndexStage(memo, keypoint_key, sensor, timings);
  const auto t0 = Clock::now(); // what the scene tasks still need is matching's time
  scene_tasks.wait();
  timings.matching_ms += msSince(t0);
  SceneAnalysis out;
  out.scan = &scan_mm;
  out.sensor = sensor;
  out.preprocessed = memo.pre;
  out.floor_points_removed = memo.floor_removed;
  out.floor_plane = memo.floor_plane;
  out.objects = memo.objects;
  out.keypoints = memo.keypoints;
  out.features = memo.features;
  if (preparing) {
    out.index = memo.scene_index;
    out.shadow = memo.shadow;
  }
  if (edge_check)
    out.edge_keypoints = memo.edge_index;
  return out;
}

} // namespace scanpick::core::detail
