#pragma once
/// @file SceneAnalysis.h
/// What the scene stages make of one scan, before any model is matched in it: the first stage of
/// recognition (Recognizer::analyze). Every later stage (matching, hypothesis verification,
/// ambiguity resolution, refinement) takes it as a value.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/features/Feature.h"
#include "core/keypoints/Keypoints.h"
#include "core/verification/PoseVerification.h"

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

namespace scanpick::core {

class SceneIndex;

/// One scan analysed: floor removed and downsampled, split into objects, each object's keypoints
/// and features, and what verification and refinement look poses up in. Immutable once made;
/// the stages it holds are shared with the recognizer's cache.
struct SceneAnalysis {
  /// The scan analysed (scene frame = camera frame, mm): the caller's, which must outlive every
  /// use of this analysis (verification looks through the organized scan).
  const PointCloud* scan = nullptr;
  SensorModel sensor; ///< the camera that took it
  /// The scan after floor removal and downsampling.
  std::shared_ptr<const PointCloud> preprocessed;
  std::size_t floor_points_removed = 0;
  /// The plane the parts rest on (FloorRemovalResult::resting_plane), (a, b, c, d) with a unit
  /// normal towards the camera; none: no floor.
  std::optional<Eigen::Vector4f> floor_plane;
  /// One cloud per object (cluster), then per object its keypoints and features.
  std::shared_ptr<const std::vector<PointCloud>> objects;
  std::shared_ptr<const std::vector<Keypoints>> keypoints;
  std::shared_ptr<const std::vector<FeatureList>> features;
  /// The preprocessed scan indexed with its normals, for verification and ICP; null when the
  /// parameters need neither (made on demand by the stages that do).
  std::shared_ptr<const SceneIndex> index;
  /// The scan's projector shadows; null when not needed (no verification).
  std::shared_ptr<const ProjectorShadow> shadow;
  /// Every object's keypoints in one index, for the edge check; null without it.
  std::shared_ptr<const SceneIndex> edge_keypoints;

  /// Verification's view of this analysis (into it and the caller's scan).
  [[nodiscard]] VerifyScene verifyScene() const {
    return {index.get(), scan, &sensor, floor_plane, shadow.get()};
  }
};

} // namespace scanpick::core
