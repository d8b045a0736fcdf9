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
#include <optional>
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

/// How a pair of oriented points becomes a table key (Drost's feature: the distance, the angle of
/// each normal to the joining line and the angle between the normals, each quantized). A model's
/// table and the scene pairs voted against it must quantize alike.
class PairQuantizer {
public:
  /// `distance_step_mm` quantizes the distance (usually the sampling voxel), `angle_bins` the
  /// angles (bins per 2π; the angles in [0, π] use half as many). Throws Error for a step <= 0 or
  /// bins outside [4, 360].
  PairQuantizer(double distance_step_mm, int angle_bins);

  /// The pair's key, or false in `valid` for a pair that tells nothing (closer than half a step,
  /// or two points of one plane, both normals across the joining line).
  [[nodiscard]] std::uint32_t key(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1,
                                  const Eigen::Vector3f& p2, const Eigen::Vector3f& n2,
                                  bool* valid) const;
  /// Points given as coordinate arrays (mm) with their unit normals, for keysWithin(); each array
  /// has at least 8 readable values past the last point used.
  struct PointArrays {
    const float *x, *y, *z, *nx, *ny, *nz;
  };
  /// A point of keysWithin()'s range that pairs: its position in the arrays, the pair's key and
  /// the squared distance (mm²) summed as the kd-tree's metric sums it (x, then y, then z).
  struct KeyedPoint {
    std::uint32_t at;
    std::uint32_t key;
    float distance_sq;
  };
  /// The pairs of (p1, n1) with the points [begin, end) of `points` that lie strictly within
  /// `radius_sq` (mm²) and have a valid key, with the keys key() gives them, written to `out`
  /// (room for end - begin); returns how many. Eight pairs at a time (GCC's vector types, also
  /// built for AVX2, without fused multiply-add), each sum in the order Eigen sums it, so that the
  /// keys are key()'s to the bit.
  std::size_t keysWithin(const PointArrays& points, std::size_t begin, std::size_t end,
                         const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, float radius_sq,
                         KeyedPoint* out) const;
  [[nodiscard]] int angleBins() const { return m_angle_bins; }
  bool operator==(const PairQuantizer& other) const {
    return m_distance_step_mm == other.m_distance_step_mm && m_angle_bins == other.m_angle_bins;
  }

private:
  /// An angle's bin from its cosine, without an arccosine: the number of the bounds
  /// cos(k π / half), k = 1 .. half - 1 (half = m_angle_bins / 2), that the cosine does not exceed.
  [[nodiscard]] int bin(float cosine) const;

  double m_distance_step_mm;
  int m_angle_bins;
  std::vector<float> m_bin_cosines; ///< the bounds, decreasing
  /// The bin at the centre of each of 512 equal cells of [-1, 1]: bin() starts there and steps
  /// over the bounds to the exact bin (none or one step for the default 30 bins).
  std::vector<std::uint8_t> m_bin_guess;
};

class PointPairModel;

/// The keys of one or more point pair tables: the scene pairs that any of them votes with. Most
/// scene pairs have a key no view of a part holds, and a pairing that keeps only the others needs
/// their angles only.
class PairKeySet {
public:
  /// The keys of `model`'s table, added.
  void add(const PointPairModel& model);
  /// The keys of `other`, added.
  void add(const PairKeySet& other);
  [[nodiscard]] bool contains(std::uint32_t key) const {
    return (key >> 6) < m_bits.size() && ((m_bits[key >> 6] >> (key & 63)) & 1u) != 0;
  }
  /// Whether every key of `model`'s table is in the set.
  [[nodiscard]] bool covers(const PointPairModel& model) const;
  /// Whether every key of this set is in `other`.
  [[nodiscard]] bool within(const PairKeySet& other) const;

private:
  std::vector<std::uint64_t> m_bits;
};

/// The scene side of the voting: each reference point's local frame and the pairs it makes with
/// its neighbours within a radius, keyed. It depends on the scene, the reference stride, the
/// quantizer, the radius and the keys kept only, so the views of a part that sample their
/// surfaces alike vote with one ScenePairs per scene instead of pairing the scene again each.
/// Immutable.
class ScenePairs {
public:
  /// Every `reference_stride`-th point of `scene` (scene frame, mm) pairs with its neighbours
  /// within `radius_mm`; with `keys`, only the pairs of a key in it are kept (the views that will
  /// vote with them: see covers()). Parallel (TBB) and deterministic; throws Cancelled when
  /// `progress` asks to stop.
  ScenePairs(const OrientedPoints& scene, const PairQuantizer& quantizer, int reference_stride,
             double radius_mm, std::optional<PairKeySet> keys = std::nullopt,
             const ProgressFn& progress = {});
  /// Whether `model` can vote with these pairs as with the scene itself: the same quantizer, a
  /// radius of at least its diameter and, when only some keys were kept, all of its keys.
  [[nodiscard]] bool covers(const PointPairModel& model) const;

  /// One keyed pair of a reference point.
  struct Pair {
    std::uint32_t key;
    /// The neighbour's rotation about the reference normal into the local plane, in turns of
    /// 2π / 65536 (as PointPairModel's entries).
    std::uint16_t alpha;
    float distance_sq; ///< mm², to keep only the neighbours within a smaller radius
  };
  [[nodiscard]] std::size_t referenceCount() const { return m_reference_points.size(); }
  [[nodiscard]] const Eigen::Vector3f& referencePoint(std::size_t r) const {
    return m_reference_points[r];
  }
  /// The frame in which reference `r` is the origin and its normal the +x axis.
  [[nodiscard]] const Eigen::Isometry3f& toLocal(std::size_t r) const { return m_to_local[r]; }
  /// Reference `r`'s pairs: [begin, end).
  [[nodiscard]] const Pair* pairsBegin(std::size_t r) const { return m_pairs[r].data(); }
  [[nodiscard]] const Pair* pairsEnd(std::size_t r) const {
    return m_pairs[r].data() + m_pairs[r].size();
  }
  [[nodiscard]] const PairQuantizer& quantizer() const { return m_quantizer; }
  [[nodiscard]] double radius() const { return m_radius_mm; }

private:
  PairQuantizer m_quantizer;
  double m_radius_mm;
  std::optional<PairKeySet> m_keys; ///< the keys kept; none: every key
  std::vector<Eigen::Vector3f> m_reference_points;
  std::vector<Eigen::Isometry3f> m_to_local;
  std::vector<std::vector<Pair>> m_pairs; ///< per reference
};

/// The model's point pair table. Immutable after construction; vote() is thread-safe.
class PointPairModel {
public:
  /// Builds the table from the sampled model (model frame, mm). `distance_step_mm` quantizes the
  /// pair distance (usually the sampling voxel), `angle_bins` the angles (PairQuantizer). Throws
  /// Error for fewer than 3 or more than 65535 points or bad steps.
  PointPairModel(OrientedPoints model, double distance_step_mm, int angle_bins = 30);

  /// Votes with the sampled scene (scene frame, mm) and returns the pose clusters, most votes
  /// first. Parallel over reference points (TBB) and deterministic. Throws Cancelled when
  /// `progress` asks to stop.
  [[nodiscard]] std::vector<VotedPose> vote(const OrientedPoints& scene,
                                            const VotingOptions& options,
                                            const ProgressFn& progress = {}) const;
  /// The same with the scene already paired (its stride replaces options.reference_stride): the
  /// same poses as vote(scene, options) when the pairs cover this model (ScenePairs::covers; only
  /// the pairs within the diameter vote). Throws Error otherwise.
  [[nodiscard]] std::vector<VotedPose> vote(const ScenePairs& scene, const VotingOptions& options,
                                            const ProgressFn& progress = {}) const;

  [[nodiscard]] std::size_t pointCount() const { return m_model.points.size(); }
  [[nodiscard]] std::size_t pairCount() const { return m_table.size(); }
  /// Largest distance between two sampled model points (mm): the scene search radius.
  [[nodiscard]] double diameter() const { return m_diameter_mm; }
  [[nodiscard]] const PairQuantizer& quantizer() const { return m_quantizer; }
  /// Whether the table holds pairs of `key`.
  [[nodiscard]] bool inTable(std::uint32_t key) const {
    return key + 1 < m_offsets.size() && m_offsets[key] != m_offsets[key + 1];
  }
  /// One more than the largest key in the table (0 when empty).
  [[nodiscard]] std::uint32_t keyEnd() const {
    return m_offsets.empty() ? 0 : static_cast<std::uint32_t>(m_offsets.size() - 1);
  }

private:
  /// One model pair, 4 bytes so that the table streams through the cache while voting: the model
  /// point in the low 16 bits, in the high 16 the rotation about its normal bringing the pair into
  /// the local plane, in turns of 2π / 65536 (differences wrap by themselves).
  using Entry = std::uint32_t;

  /// One reference point's best (model point, angle) as a pose (float, as voted), and its votes.
  struct ReferencePeak {
    Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
    int votes = 0;
  };
  /// The votes of one reference point's pairs (those within the diameter).
  [[nodiscard]] ReferencePeak peakOf(const ScenePairs::Pair* begin, const ScenePairs::Pair* end,
                                     const Eigen::Vector3f& reference,
                                     const Eigen::Isometry3f& to_local,
                                     const VotingOptions& options) const;
  /// The peaks clustered into poses (kept in reference order, so ties sort deterministically).
  [[nodiscard]] static std::vector<VotedPose> clustered(std::vector<ReferencePeak> peaks,
                                                        const VotingOptions& options);

  OrientedPoints m_model;
  PairQuantizer m_quantizer;
  double m_diameter_mm = 0.0;
  std::vector<Entry> m_table;           ///< grouped by key
  std::vector<std::uint32_t> m_offsets; ///< per key, where its entries start in m_table
  /// For each model point: the transform into its local frame (point at the origin, normal on +x).
  std::vector<Eigen::Isometry3f> m_to_local;
};

} // namespace scanpick::core
