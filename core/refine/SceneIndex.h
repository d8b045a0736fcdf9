#pragma once
/// @file SceneIndex.h
/// Scene points with unit normals in a kd-tree: built once per scene, then shared (read-only) by
/// the refinement and verification of every detection in that scene.

#include "core/cloud/PixelCoordinates.h"
#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Progress.h"

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace scanpick::core {

/// How SceneIndex estimates normals when the cloud brings none.
struct SceneIndexOptions {
  /// Where the camera is, in the cloud's frame (mm). Normals are turned to face it, and
  /// refinement uses it to tell which model points the camera can see. Default: the origin, as
  /// for a scan in its camera frame.
  Eigen::Vector3d viewpoint_mm = Eigen::Vector3d::Zero();
  /// Neighbours farther than this from a point do not shape its normal (mm); default 3 mm, the
  /// size of a PhoXi-class surface patch that is still flat on machined parts.
  double normal_radius_mm = 3.0;
  /// Organized clouds: the normal is the PCA of the valid pixels in a (2w+1)² window (w = this)
  /// that lie within normal_radius_mm; linear in the number of pixels, no tree search. The
  /// default 3 x 3 window blends faces only within a pixel of an edge (a 5 x 5 window doubled
  /// the worst pose error on 5 mm thin plates); raise it for noisier sensors (Kinect: 3-4).
  int pixel_half_window = 1;
  /// Unorganized clouds: PCA of this many nearest neighbours (within normal_radius_mm).
  int neighbours = 12;
  /// Use the cloud's own normals when it has them (re-oriented towards the viewpoint).
  bool use_cloud_normals = true;
  /// False: the cloud's own normals are taken as they are, not turned towards the viewpoint (a
  /// model joined from views, each facing its own teach camera).
  bool orient_cloud_normals = true;
  /// False: no normals at all (normals() all NaN), for an index used for nearest points only.
  bool estimate_normals = true;
  /// Normals for every n-th indexed point only (the others NaN), for a caller that keeps only
  /// those points (makeVerifyModel's stride): each the normal it would have with 1, at a fraction
  /// of the cost.
  int normal_stride = 1;
  /// The sensor that took an organized cloud of its size: when the cloud's points lie within
  /// kMaxPixelWindowSlack pixels of where it projects them (pixelSlack()), nearest() looks in the
  /// pixel window that must hold the answer instead of the kd-tree, with the same answers.
  std::optional<SensorModel> sensor;
};

/// Largest pixelSlack() (px) at which SceneIndex::nearest looks in pixel windows: beyond it the
/// cloud and the sensor model disagree, and the windows would grow.
inline constexpr float kMaxPixelWindowSlack = 1.0f;

/// The valid points of a cloud, their normals (NaN where too few neighbours), and a kd-tree
/// (built on the first search that needs it).
/// Immutable after construction: queries are safe from many threads at once.
class SceneIndex {
public:
  /// Builds the index from `scene_mm` (organized or not; NaN points are skipped). Normal
  /// estimation runs in parallel (TBB) and is deterministic. Throws Error when the cloud has no
  /// valid point or the options are out of range; Cancelled when `progress` asks to stop.
  explicit SceneIndex(const PointCloud& scene_mm, const SceneIndexOptions& options = {},
                      const ProgressFn& progress = {});
  ~SceneIndex();
  SceneIndex(SceneIndex&&) noexcept;
  SceneIndex& operator=(SceneIndex&&) noexcept;
  SceneIndex(const SceneIndex&) = delete;
  SceneIndex& operator=(const SceneIndex&) = delete;

  /// Number of indexed (valid) points.
  [[nodiscard]] std::size_t size() const { return m_normals.size(); }
  /// Indexed points (mm), in the order of the valid points of the input cloud.
  [[nodiscard]] const std::vector<Eigen::Vector3f>& points() const;
  /// Unit normals facing the viewpoint; NaN where a normal could not be estimated.
  [[nodiscard]] const std::vector<Eigen::Vector3f>& normals() const { return m_normals; }
  /// Surface variation of each point's neighbourhood, λ0 / (λ0 + λ1 + λ2) of its PCA: about 0 on
  /// a flat patch, up to 1/3; high where a patch straddles an edge (its normal is then a blend).
  /// 0 where the normal came with the cloud.
  [[nodiscard]] const std::vector<float>& surfaceVariation() const { return m_variation; }
  /// Median surface variation of the estimated normals (0 if none): the flat-surface level set by
  /// the sensor noise and the sampling, against which edges stand out.
  [[nodiscard]] float typicalVariation() const { return m_typical_variation; }
  [[nodiscard]] const SceneIndexOptions& options() const { return m_options; }

  /// Nearest indexed point to `query_mm` no farther than sqrt(max_distance_sq) (mm²). Returns
  /// its index, or -1 when there is none that close. Exact (no approximate search), so
  /// deterministic; ties go to the lower index. With the options' sensor and a pixelSlack() of at
  /// most kMaxPixelWindowSlack, a small sphere (a window of up to 17 x 17 pixels) is searched in
  /// the pixels that can hold it: the pinhole's slope over the sphere, the slack and the rounding.
  [[nodiscard]] std::int64_t nearest(const Eigen::Vector3f& query_mm, float max_distance_sq,
                                     float* distance_sq = nullptr) const;

  /// Organized clouds: nearest() among the points of the pixels within `half_u` columns and
  /// `half_v` rows of pixel (u, v) only, with the same distances and tie rule; -1 when none of them
  /// is that close, or the cloud was not organized. It equals nearest() whenever every indexed
  /// point that close lies in the window.
  [[nodiscard]] std::int64_t nearestInWindow(const Eigen::Vector3f& query_mm, float max_distance_sq,
                                             int u, int v, int half_u, int half_v,
                                             float* distance_sq = nullptr) const;
  /// Organized clouds: the index of each pixel's point (-1 where none), row by row; empty when the
  /// cloud was not organized.
  [[nodiscard]] const std::vector<std::int32_t>& pixelIndex() const { return m_pixel_index; }
  [[nodiscard]] int width() const { return m_width; }   ///< of the organized cloud, else 0
  [[nodiscard]] int height() const { return m_height; } ///< of the organized cloud, else 0
  /// How far (pixels) the indexed points lie from where the options' sensor projects them at
  /// most; negative without a sensor, for a cloud not organized at the sensor's size, or with a
  /// point behind the camera.
  [[nodiscard]] float pixelSlack() const { return m_pixel_slack; }

private:
  struct Tree;
  /// Largest half window (pixels, exclusive) nearest() searches; wider spheres go to the tree.
  static constexpr double kMaxWindowReach = 9.0;
  [[nodiscard]] float measurePixelSlack(const SensorModel& sensor) const;
  SceneIndexOptions m_options;
  std::vector<std::int32_t> m_pixel_index;
  /// Organized clouds: each pixel's indexed point, so that a pixel window is read row by row
  /// without looking up each pixel's index.
  PixelCoordinates m_pixel_points;
  int m_width = 0, m_height = 0;
  float m_pixel_slack = -1.0f;
  std::vector<Eigen::Vector3f> m_normals;
  std::vector<float> m_variation;
  float m_typical_variation = 0.0f;
  std::unique_ptr<Tree> m_tree;
};

} // namespace scanpick::core
