#pragma once
/// @file Parameters.h
/// One plain value struct per recognition stage, grouped in RecognitionParams. Names follow the
/// thesis (chapter 3, tables 5.1-5.8); units are millimetres (_mm), radians (_rad), degrees (_deg)
/// and point counts. Every field is described once, in the metadata table (ParameterTable.cpp,
/// key "stage.field"; `scanpick-cli params` and docs/parameters.md print it), from which the GUI
/// builds its editors and presets are read and written.

#include <cstdint>

namespace scanpick::core {

/// Scene preprocessing, §3.3: floor/plane removal by RANSAC.
struct FloorParams {
  bool enabled = true;
  double distance_mm = 2.0;
  int max_planes = 1;
  double min_plane_fraction = 0.15;
  double bin_floor_fraction = 0.0;
  bool bin_walls = false;
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
  bool enabled = true;
  double count_radius_mm = 1.5;
  int count_min_points = 1000;
  enum class Init { FarthestFirst, KMeansPlusPlus } init = Init::FarthestFirst;
  int max_iterations = 100;
  int min_cluster_points = 3;
  enum class Method { KMeans, ProjectedClusters } method = Method::KMeans;
  bool operator==(const ClusteringParams&) const = default;
};

/// First-level keypoints, §3.1 (Algorithms 1 and 2).
struct KeypointParams {
  enum class Method { Neighbourhood, NormalsGradient, Both } method = Method::Neighbourhood;
  double neighbourhood_radius_mm = 3.0;
  double position_range_mm = 0.6;
  double gradient_sensitivity_rad = 0.35;
  int gradient_neighbours = 12;
  double normal_radius_mm = 3.0;
  bool operator==(const KeypointParams&) const = default;
};

/// Second-level features, §3.1-3.2: repeated RANSAC lines and circles among keypoints.
struct FeatureParams {
  enum class Estimator { Ransac, Mlesac, Prosac } estimator = Estimator::Ransac;
  int ransac_size = 50;
  double line_threshold_mm = 5.0;
  double circle_threshold_mm = 5.0;
  int max_iterations = 1000;
  int max_features = 200;
  double min_circle_radius_mm = 1.0;
  double max_circle_radius_mm = 200.0;
  bool lines = true;
  bool circles = true;
  double run_gap_mm = 0.0;
  double sample_radius_mm = 0.0;
  bool operator==(const FeatureParams&) const = default;
};

/// Feature matching, §3.4 (Algorithm 8).
struct MatchingParams {
  double length_tolerance_mm = 60.0;
  double radius_tolerance_mm = 60.0;
  double position_tolerance_mm = 20.0;
  double orientation_tolerance_rad = 0.25;
  double roll_step_deg = 5.0;
  double score_threshold = 0.1;
  int max_detections = 0;
  int max_instances_per_cluster = 4;
  double verify_tolerance_mm = 0.0;
  double min_coverage = 0.0;
  double edge_tolerance_mm = 0.0;
  int hypotheses = 1;
  int pool_size = 0;
  double surface_sampling_mm = 0.0;
  int surface_reference_stride = 5;
  int surface_poses = 100;
  double symmetry_overlap = 0.0;
  bool operator==(const MatchingParams&) const = default;
};

/// Pose refinement after matching (not in the thesis, which names ICP as future work).
struct RefineParams {
  bool enabled = false;
  int max_iterations = 30;
  double max_correspondence_mm = 5.0;
  double min_correspondence_mm = 1.0;
  double inlier_distance_mm = 1.0;
  double convergence_mm = 0.005;
  int model_points = 2000;
  bool point_to_plane = true;
  double min_inlier_fraction = 0.9;
  bool axial_ends = true;
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
  std::uint64_t seed = 42;
  bool operator==(const RecognitionParams&) const = default;
};

} // namespace scanpick::core
