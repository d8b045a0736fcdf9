#pragma once
/// @file PointPairVoting.h
/// Surface pose hypotheses beyond the thesis: point pair features with voting in a local
/// coordinate space (Drost et al., "Model globally, match locally", CVPR 2010). The thesis's
/// lines and circles need two matching feature pairs per pose, and in a bin a part's edges are
/// often cut by its neighbours; the surface itself still shows. Every pair of sampled model
/// points is described by (distance, angle of each normal to the joining line, angle between
/// the normals) and stored in a table; each scene reference point pairs with its neighbours,
/// looks the pairs up and votes for (model point, rotation about its normal). The vote peaks
/// are poses, clustered and ranked by their votes; the recognizer verifies each one.
///
/// PCL's PPFRegistration implements the same features but registers one cloud to one pose; a
/// bin needs every pose peak, so the voting is done here on PCL-free oriented points.

#include "core/common/Progress.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace scanpick::core {

/// Points with unit normals (mm). Both vectors have the same length.
struct OrientedPoints {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
};

/// One voxel of edge `voxel_mm` → the centroid of its points and their mean normal (re-normalized);
/// points with a non-finite position or normal are skipped. Ordered by voxel (deterministic).
/// Throws Error when the sizes differ or voxel_mm <= 0.
OrientedPoints sampleOriented(const std::vector<Eigen::Vector3f>& points_mm,
                              const std::vector<Eigen::Vector3f>& normals, double voxel_mm);

/// A pose hypothesis from the voting.
struct VotedPose {
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  /// Votes of the poses merged into this one (higher = more surface agrees).
  int votes = 0;
};

/// How the scene is searched.
struct VotingOptions {
  /// Every n-th sampled scene point is a reference point (1 = all; Drost: 5).
  int reference_stride = 5;
  /// Poses closer than this (mm, at the model origin) and `cluster_angle_rad` are merged.
  double cluster_distance_mm = 10.0;
  double cluster_angle_rad = 0.35;
  /// At most this many pose clusters are returned, most votes first.
  int max_poses = 100;
  /// For voting a model against itself (the scene is the model, in its own frame): model points
  /// closer than this (mm) to the reference point do not vote, so the peaks are the model's
  /// symmetries instead of the identity. 0 = every model point votes.
  double exclude_self_mm = 0.0;
};

/// The model's point pair table. Immutable after construction; vote() is thread-safe.
class PointPairModel {
public:
  /// Builds the table from the sampled model (model frame, mm). `distance_step_mm` quantizes the
  /// pair distance (usually the sampling voxel), `angle_bins` the angles (bins per 2π; the normal
  /// angles in [0, π] use half as many). Throws Error for fewer than 3 or more than 65535 points
  /// or bad steps.
  PointPairModel(OrientedPoints model, double distance_step_mm, int angle_bins = 30);

  /// Votes with the sampled scene (scene frame, mm) and returns the pose clusters, most votes
  /// first. Parallel over reference points (TBB) and deterministic. Throws Cancelled when
  /// `progress` asks to stop.
  [[nodiscard]] std::vector<VotedPose> vote(const OrientedPoints& scene,
                                            const VotingOptions& options,
                                            const ProgressFn& progress = {}) const;

  [[nodiscard]] std::size_t pointCount() const { return m_model.points.size(); }
  [[nodiscard]] std::size_t pairCount() const { return m_table.size(); }
  /// Largest distance between two sampled model points (mm): the scene search radius.
  [[nodiscard]] double diameter() const { return m_diameter_mm; }

private:
  /// One model pair, 4 bytes so that the table streams through the cache while voting.
  struct Entry {
    std::uint16_t model_point;
    /// Rotation about the reference normal bringing the pair into the local plane, in turns of
    /// 2π / 65536 (fixedAngle): differences wrap by themselves.
    std::uint16_t alpha;
  };
  [[nodiscard]] std::uint32_t key(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1,
                                  const Eigen::Vector3f& p2, const Eigen::Vector3f& n2,
                                  bool* valid) const;

  OrientedPoints m_model;
  double m_distance_step_mm;
  int m_angle_bins;
  double m_diameter_mm = 0.0;
  /// cos(k π / half) for k = 1 .. half - 1 (half = m_angle_bins / 2): an angle's bin is the number
  /// of these its cosine does not exceed, without an arccosine per pair.
  std::vector<float> m_bin_cosines;
  std::vector<Entry> m_table;           ///< grouped by key
  std::vector<std::uint32_t> m_offsets; ///< per key, where its entries start in m_table
  /// For each model point: the transform into its local frame (point at the origin, normal on +x).
  std::vector<Eigen::Isometry3f> m_to_local;
};

} // namespace scanpick::core
