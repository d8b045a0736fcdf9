#pragma once
/// @file Parameters.h
/// One plain value struct per recognition stage, grouped in RecognitionParams. Names follow the
/// thesis (chapter 3, tables 5.1-5.8); units are millimetres, radians and point counts.
/// Every field is described once, in the metadata table of ParameterTable.h, from which the GUI
/// builds its editors and presets are read and written.

#include <cstdint>

namespace scanpick::core {

/// Scene preprocessing, §3.3: floor/plane removal by RANSAC.
struct FloorParams {
  bool enabled = true;              ///< remove the largest planes (bin floor, table) first
  double distance_mm = 2.0;         ///< RANSAC plane inlier distance
  int max_planes = 1;               ///< how many dominant planes to remove
  double min_plane_fraction = 0.15; ///< a plane must hold this fraction of the points to go
  /// Beyond the thesis, for bins standing on the ground: after the planes above, also remove the
  /// plane parallel to the first that holds at least this fraction of the points and has
  /// (almost) nothing behind it: the bin's floor, which the ground around the bin outnumbers. The
  /// rim of the bin's walls and the parts' flat faces have the floor behind them. 0 = off.
  double bin_floor_fraction = 0.0;
  bool operator==(const FloorParams&) const = default;
};

/// Optional voxel downsampling before keypoints (0 = off). Not in the thesis: keeps the cost of
/// high-resolution PhoXi scans bounded.
struct DownsampleParams {
  double voxel_mm = 0.0;
  bool operator==(const DownsampleParams&) const = default;
};

/// Object count (Algorithm 7) and centre-based clustering (k-means, §3.3).
struct ClusteringParams {
  bool enabled = true;          ///< off: the whole scene is one cluster
  double count_radius_mm = 1.5; ///< r: single-linkage distance on the 2D projection
  int count_min_points = 1000;  ///< min_cluster_size: clusters counted as objects
  enum class Init { FarthestFirst, KMeansPlusPlus } init = Init::FarthestFirst;
  int max_iterations = 100;   ///< Lloyd iterations at most
  int min_cluster_points = 3; ///< smaller k-means clusters are removed and k-means re-run
  /// How objects are split: k-means with k = the count (the thesis), or the projected clusters
  /// of Algorithm 7 used directly (beyond the thesis: keeps touching parts apart).
  enum class Method { KMeans, ProjectedClusters } method = Method::KMeans;
  bool operator==(const ClusteringParams&) const = default;
};

/// First-level keypoints, §3.1 (Algorithms 1 and 2).
struct KeypointParams {
  enum class Method { Neighbourhood, NormalsGradient, Both } method = Method::Neighbourhood;
  double neighbourhood_radius_mm = 3.0;   ///< Δr: neighbourhood search radius
  double position_range_mm = 0.6;         ///< Δp: centroid offset marking an edge; < 0 keeps all
  double gradient_sensitivity_rad = 0.35; ///< s: flat-region tolerance of Algorithm 1
  int gradient_neighbours = 12;           ///< n: neighbours examined per step of Algorithm 1
  double normal_radius_mm = 3.0;          ///< radius for normal estimation
  bool operator==(const KeypointParams&) const = default;
};

/// Second-level features, §3.1-3.2: repeated RANSAC lines and circles among keypoints.
struct FeatureParams {
  enum class Estimator { Ransac, Mlesac, Prosac } estimator = Estimator::Ransac;
  int ransac_size = 50;              ///< minimum inliers of a line or circle ("Ransac size")
  double line_threshold_mm = 5.0;    ///< line inlier tolerance ("Ransac threshold")
  double circle_threshold_mm = 5.0;  ///< circle inlier tolerance ("Ransac threshold")
  int max_iterations = 1000;         ///< RANSAC trials per search
  int max_features = 200;            ///< stop after this many lines + circles
  double min_circle_radius_mm = 1.0; ///< circles outside [min, max] are not accepted
  double max_circle_radius_mm = 200.0;
  bool lines = true;   ///< search lines
  bool circles = true; ///< search circles
  /// Inliers of a line or circle are split where consecutive ones (along the line or arc) are
  /// farther apart than this, and only the largest run is kept; 0 = automatic (the larger of
  /// 3 x threshold and 4 x the median keypoint spacing).
  double run_gap_mm = 0.0;
  /// Beyond the thesis: a RANSAC sample's other points are drawn within this distance of its
  /// first point (keypoints lie on edges, so a near pair is likely on one edge), which finds
  /// features in far fewer trials; 0 = uniform sampling over all keypoints (the thesis).
  double sample_radius_mm = 0.0;
  bool operator==(const FeatureParams&) const = default;
};

/// Feature matching, §3.4 (Algorithm 8).
struct MatchingParams {
  double length_tolerance_mm = 60.0;       ///< Δl for lines ("Matching length")
  double radius_tolerance_mm = 60.0;       ///< Δl for circles ("Matching radius size")
  double position_tolerance_mm = 20.0;     ///< Δp ("Matching position")
  double orientation_tolerance_rad = 0.25; ///< Δo ("Matching orientation")
  double roll_step_deg = 5.0;              ///< angular step of the roll (toroid) search
  double score_threshold = 0.1;            ///< detections scoring below are rejected ("Score")
  int max_detections = 0;                  ///< 0 = no limit
  int max_instances_per_cluster = 4;       ///< repeated searches per cluster (merged parts)
  /// Beyond the thesis: point-level verification. A pose is checked by the share of the model's
  /// points the camera should see that have a scene point facing the same way within this
  /// distance (mm), less those the scan looks through; 0 = off (the thesis).
  double verify_tolerance_mm = 0.0;
  /// With verification on, detections confirming a smaller share of visible points are dropped.
  double min_coverage = 0.0;
  /// With verification on, coverage is weighed by the share of model keypoints (on confirmed
  /// surface) with a scene keypoint within this distance (mm); 0 = off.
  double edge_tolerance_mm = 0.0;
  /// Distinct pose hypotheses per search that verification re-ranks (1 = the thesis: the best
  /// feature score alone decides, so a 180° flip of two parallel circles can win).
  int hypotheses = 1;
  /// Beyond the thesis, for bins of touching parts: with verification on and this > 0, one
  /// search keeps up to this many distinct poses over all seed pairs (the best one prunes
  /// nothing), verifies each, and reports all reaching min_coverage, instead of the repeated
  /// best-first rounds of max_instances_per_cluster. 0 = the rounds.
  int pool_size = 0;
  /// Beyond the thesis: surface point pair voting (PointPairVoting.h) adds pose hypotheses that
  /// need no feature pairs; each is refined on the features it confirms or by ICP, whichever
  /// verifies best, and verified like the others (verification must be on). The model and scene are
  /// sampled with voxels of this edge (mm; about 4 % of the part's diameter); 0 = off.
  double surface_sampling_mm = 0.0;
  /// Every n-th sampled scene point is a voting reference.
  int surface_reference_stride = 5;
  /// At most this many voted poses (pose clusters, most votes first) are verified.
  int surface_poses = 100;
  /// Beyond the thesis, for nearly symmetric parts: a turn of a view (found by voting the view
  /// against itself) that puts at least this share of its points back on its own surface (after
  /// ICP) is a near symmetry (NearSymmetry.h). Each detection is compared with its turned pose on
  /// the points that differ, and the pose the scan contradicts clearly less is kept; when the scan
  /// cannot tell, the turned pose is reported as an alternative. Needs verification; 0 = off.
  double symmetry_overlap = 0.0;
  bool operator==(const MatchingParams&) const = default;
};

/// Pose refinement after matching (not in the thesis, which names ICP as future work).
struct RefineParams {
  bool enabled = false; ///< run ICP on each detection
  int max_iterations = 30;
  double max_correspondence_mm = 5.0;
  /// The coarse-to-fine schedule shrinks the pair distance from max_correspondence_mm towards
  /// 3x the current residual, but not below this (mm); about 5-10x the sensor noise.
  double min_correspondence_mm = 1.0;
  /// A visible model point with a scene point this close counts as an inlier (mm).
  double inlier_distance_mm = 1.0;
  /// Stop when an iteration moves no model point by more than this (mm).
  double convergence_mm = 0.005;
  /// Model points used (deterministic voxel subsample of the taught cloud).
  int model_points = 2000;
  /// Point-to-plane (true) or point-to-point (false) error.
  bool point_to_plane = true;
  /// A settled pose counts as converged only with at least this inlier share, [0, 1]. High on
  /// purpose: a part seen edge-on along an extrusion can settle a few mm off along it with
  /// ~0.85 of its points still confirmed (the true pose: ~0.98 when unoccluded).
  double min_inlier_fraction = 0.9;
  /// After ICP, a view that is a surface of revolution is slid along its axis to where the scan
  /// shows its wall's ends (AxialEnds): ICP hardly pins that direction on a cup or pipe lying on
  /// its side.
  bool axial_ends = true;
  /// After ICP, other views are moved, along each direction ICP hardly pins (a plate seen face-on
  /// in its own plane), to where the scan's points end as the view's do (outlineShift); ICP then
  /// leaves those directions as they came instead of drifting along them. Off by
  /// default: it helps plates (coat-rack) and hurts a view cut from a cluttered scan
  /// (docs/design-notes-refinement.md).
  bool outline_ends = false;
  bool operator==(const RefineParams&) const = default;
};

/// All recognition parameters. Same input + same parameters (seed included) = same output.
struct RecognitionParams {
  FloorParams floor;
  DownsampleParams downsample;
  ClusteringParams clustering;
  KeypointParams keypoints;
  FeatureParams features;
  MatchingParams matching;
  RefineParams refine;
  std::uint64_t seed = 42; ///< seed of every random choice (RANSAC samples, k-means++)
  bool operator==(const RecognitionParams&) const = default;
};

} // namespace scanpick::core
