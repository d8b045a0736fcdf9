#pragma once
/// @file StageMemo.h
/// The recognizer's memo of its scene stages (internal to core/pipeline): each stage's output
/// kept with the key it was made from (the scene's content hash and that stage's parameters), so
/// that a stage runs again only when its key changes. analyzeScene fills it and hands on a
/// SceneAnalysis.

#include "core/ambiguity/ModelPrep.h"
#include "core/common/Progress.h"
#include "core/matching/PointPairVoting.h"
#include "core/params/Parameters.h"
#include "core/pipeline/Recognizer.h"
#include "core/pipeline/SceneAnalysis.h"
#include "core/refine/SceneIndex.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace scanpick::core::detail {

/// The scan's identity for the memo: its content, not its address (a re-captured identical scan
/// hits, an edited buffer misses).
std::uint64_t sceneHash(const PointCloud& cloud);
/// The sensor's identity for the memo: its intrinsics, range and projector pose.
std::uint64_t sensorHash(const SensorModel& s);

/// The stages' keys, each holding the key of the stage it builds on: floor removal and
/// downsampling, the split into objects, keypoints, features.
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

/// Each stage's last output and its key; copied under the recognizer's lock, worked on, and stored
/// back (a copy shares the outputs, which are immutable).
struct StageMemo {
  std::optional<PreKey> pre_key;
  std::shared_ptr<const PointCloud> pre;
  /// `pre` with the bin's walls and rim back in (FloorRemovalResult::remaining_with_walls), or
  /// `pre` itself: what the scene index holds, since poses must not pass through the walls, while
  /// the walls neither form objects nor vote.
  std::shared_ptr<const PointCloud> pre_with_walls;
  std::size_t floor_removed = 0;
  std::optional<Eigen::Vector4f> floor_plane; ///< the plane the parts rest on (key: pre_key)
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
                                              const ProgressFn& progress);
};

/// The scene stages of `scan_mm` for `params` (a view's parameters, TaughtModel::view_params
/// applied; `requested` as the caller gave them, for the views prepared in `memo` that share a
/// pairing): floor removal and downsampling, the split into objects, keypoints, features, and,
/// when `params` need a model preparation, the scene index, projector shadows and the edge
/// check's keypoint index. Runs only the stages whose keys changed, updating `memo`; adds each
/// stage's time to `timings` (0 for a stage served from the memo). Progress runs through the shares
/// kProgressShares.preprocess to kProgressShares.features (ProgressShares.h).
/// Throws Cancelled when `progress` asks to stop.
SceneAnalysis analyzeScene(StageMemo& memo, const PointCloud& scan_mm, const SensorModel& sensor,
                           const RecognitionParams& params, const RecognitionParams& requested,
                           const ProgressFn& progress, StageTimings& timings);

} // namespace scanpick::core::detail
