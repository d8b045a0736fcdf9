#include "core/params/ParameterTable.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace scanpick::core {
namespace {

/// Builds get/set for a member `field` of the stage struct `group` of RecognitionParams.
template <typename Group, typename Field>
ParamInfo entry(Group RecognitionParams::*group, Field Group::*field, ParamInfo info) {
  info.get = [group, field](const RecognitionParams& p) {
    return static_cast<double>((p.*group).*field);
  };
  const double lo = info.min_value, hi = info.max_value;
  info.set = [group, field, lo, hi](RecognitionParams& p, double v) {
    v = std::clamp(v, lo, hi);
    if constexpr (std::is_enum_v<Field>)
      (p.*group).*field = static_cast<Field>(static_cast<int>(std::lround(v)));
    else if constexpr (std::is_same_v<Field, bool>)
      (p.*group).*field = v >= 0.5;
    else if constexpr (std::is_integral_v<Field>)
      (p.*group).*field = static_cast<Field>(std::llround(v));
    else
      (p.*group).*field = static_cast<Field>(v);
  };
  return info;
}

ParamInfo make(std::string key, std::string label, std::string unit, Stage stage, ParamType type,
               double lo, double hi, double step, std::string description,
               std::vector<std::string> choices = {}) {
  ParamInfo info;
  info.key = std::move(key);
  info.label = std::move(label);
  info.unit = std::move(unit);
  info.description = std::move(description);
  info.stage = stage;
  info.type = type;
  info.min_value = lo;
  info.max_value = hi;
  info.step = step;
  info.choices = std::move(choices);
  return info;
}

using RP = RecognitionParams;
constexpr auto D = ParamType::Double;
constexpr auto I = ParamType::Int;
constexpr auto B = ParamType::Bool;
constexpr auto E = ParamType::Enum;

std::vector<ParamInfo> buildTable() {
  std::vector<ParamInfo> t;
  // --- Scene preprocessing (§3.3) ---
  t.push_back(entry(
      &RP::floor, &FloorParams::enabled,
      make("floor.enabled", "Remove floor", "", Stage::Preprocess, B, 0, 1, 1,
           "Remove the dominant planes (bin floor, table) with RANSAC before anything else.")));
  t.push_back(
      entry(&RP::floor, &FloorParams::distance_mm,
            make("floor.distance_mm", "Floor distance", "mm", Stage::Preprocess, D, 0.05, 50, 0.1,
                 "Points closer than this to the fitted plane are floor and are removed.")));
  t.push_back(
      entry(&RP::floor, &FloorParams::max_planes,
            make("floor.max_planes", "Planes to remove", "", Stage::Preprocess, I, 0, 6, 1,
                 "How many dominant planes to remove (1: floor; 5: floor and four bin walls).")));
  t.push_back(entry(
      &RP::floor, &FloorParams::min_plane_fraction,
      make("floor.min_plane_fraction", "Min plane share", "", Stage::Preprocess, D, 0.0, 1.0, 0.01,
           "A plane is removed only if it holds at least this fraction of the scene's points.")));
  t.push_back(entry(
      &RP::floor, &FloorParams::bin_floor_fraction,
      make("floor.bin_floor_fraction", "Bin floor share", "", Stage::Preprocess, D, 0.0, 1.0, 0.005,
           "Beyond the thesis, for a bin standing on the ground: also remove the plane parallel "
           "to the first removed one that holds at least this fraction of the scene's points and "
           "has (almost) nothing behind it, the bin's floor; 0 = off.")));
  t.push_back(entry(
      &RP::floor, &FloorParams::bin_walls,
      make("floor.bin_walls", "Remove bin walls", "", Stage::Preprocess, B, 0, 1, 1,
           "Beyond the thesis, after a bin's floor: also remove the bin's walls and rim from what "
           "forms objects and votes (verification and ICP still see them).")));
  t.push_back(
      entry(&RP::downsample, &DownsampleParams::voxel_mm,
            make("downsample.voxel_mm", "Voxel size", "mm", Stage::Preprocess, D, 0, 20, 0.1,
                 "Voxel-grid downsampling of the scene before keypoints; 0 keeps every point.")));
  // --- Object count and clustering (§3.3, Algorithm 7, k-means) ---
  t.push_back(
      entry(&RP::clustering, &ClusteringParams::enabled,
            make("clustering.enabled", "Split into objects", "", Stage::Clustering, B, 0, 1, 1,
                 "Count the objects and split the scene with k-means; off treats the scene as one "
                 "object.")));
  t.push_back(entry(
      &RP::clustering, &ClusteringParams::count_radius_mm,
      make("clustering.count_radius_mm", "Count radius r", "mm", Stage::Clustering, D, 0.1, 50, 0.1,
           "Single-linkage distance r on the scene projected along the line to the farther "
           "source (Algorithm 7); the thesis suggests 1-1.5 mm for PhoXi.")));
  t.push_back(entry(&RP::clustering, &ClusteringParams::count_min_points,
                    make("clustering.count_min_points", "Min object size", "points",
                         Stage::Clustering, I, 1, 1000000, 10,
                         "Projected clusters with at least this many points are counted as objects "
                         "(min_cluster_size of Algorithm 7).")));
  t.push_back(entry(
      &RP::clustering, &ClusteringParams::init,
      make("clustering.init", "k-means seeding", "", Stage::Clustering, E, 0, 1, 1,
           "Initial centres of Lloyd's k-means: farthest-first traversal (the thesis's choice, "
           "deterministic) or k-means++ (seeded).",
           {"farthest_first", "kmeans++"})));
  t.push_back(entry(
      &RP::clustering, &ClusteringParams::max_iterations,
      make("clustering.max_iterations", "k-means iterations", "", Stage::Clustering, I, 1, 1000, 1,
           "Upper bound on Lloyd iterations; it stops earlier when the objective stops "
           "decreasing.")));
  t.push_back(
      entry(&RP::clustering, &ClusteringParams::min_cluster_points,
            make("clustering.min_cluster_points", "Min cluster size", "points", Stage::Clustering,
                 I, 1, 100000, 1,
                 "k-means clusters smaller than this are outliers: their points are removed and "
                 "k-means is re-run (the thesis uses 3).")));
  t.push_back(
      entry(&RP::clustering, &ClusteringParams::method,
            make("clustering.method", "Split method", "", Stage::Clustering, E, 0, 1, 1,
                 "k-means with k = the object count (the thesis), or the projected clusters of the "
                 "count used directly as objects (keeps touching parts apart; small fragments join "
                 "the nearest object).",
                 {"kmeans", "projected_clusters"})));
  // --- First-level keypoints (§3.1) ---
  t.push_back(entry(
      &RP::keypoints, &KeypointParams::method,
      make("keypoints.method", "Keypoint method", "", Stage::Keypoints, E, 0, 2, 1,
           "Neighbourhood analysis (edges, Algorithm 2), normals gradient analysis (curvature "
           "peaks, Algorithm 1), or both together.",
           {"neighbourhood", "normals_gradient", "both"})));
  t.push_back(entry(&RP::keypoints, &KeypointParams::neighbourhood_radius_mm,
                    make("keypoints.neighbourhood_radius_mm", "Neighbourhood radius Δr", "mm",
                         Stage::Keypoints, D, 0.1, 100, 0.1,
                         "Radius of the neighbourhood whose centroid is examined.")));
  t.push_back(
      entry(&RP::keypoints, &KeypointParams::position_range_mm,
            make("keypoints.position_range_mm", "Neig. position range Δp", "mm", Stage::Keypoints,
                 D, -1, 50, 0.05,
                 "A point is an edge keypoint when its neighbourhood centroid is at least this far "
                 "away; a negative value keeps every point (the thesis's ideal test uses -1).")));
  t.push_back(entry(
      &RP::keypoints, &KeypointParams::gradient_sensitivity_rad,
      make("keypoints.gradient_sensitivity_rad", "Gradient sensitivity s", "rad", Stage::Keypoints,
           D, 0.0, 3.14, 0.01,
           "Normals gradient analysis: a point whose neighbours' normals all turn less than s "
           "is in a flat region and yields no keypoint.")));
  t.push_back(entry(
      &RP::keypoints, &KeypointParams::gradient_neighbours,
      make("keypoints.gradient_neighbours", "Gradient neighbours n", "points", Stage::Keypoints, I,
           3, 200, 1, "Normals gradient analysis: neighbours examined at each step of the walk.")));
  t.push_back(
      entry(&RP::keypoints, &KeypointParams::normal_radius_mm,
            make("keypoints.normal_radius_mm", "Normal radius", "mm", Stage::Keypoints, D, 0.1, 100,
                 0.1, "Radius of the neighbourhood used to estimate surface normals.")));
  // --- Second-level features (§3.1-3.2) ---
  t.push_back(
      entry(&RP::features, &FeatureParams::estimator,
            make("features.estimator", "Estimator", "", Stage::Features, E, 0, 2, 1,
                 "Sample-consensus estimator for lines and circles; the thesis keeps RANSAC, which "
                 "finds more features than MLESAC and PROSAC.",
                 {"ransac", "mlesac", "prosac"})));
  t.push_back(entry(&RP::features, &FeatureParams::ransac_size,
                    make("features.ransac_size", "Ransac size", "points", Stage::Features, I, 2,
                         100000, 1, "Minimum inliers of an accepted line or circle.")));
  t.push_back(
      entry(&RP::features, &FeatureParams::line_threshold_mm,
            make("features.line_threshold_mm", "Ransac threshold (lines)", "mm", Stage::Features, D,
                 0.0001, 50, 0.05, "Distance within which a keypoint is an inlier of a line.")));
  t.push_back(entry(&RP::features, &FeatureParams::circle_threshold_mm,
                    make("features.circle_threshold_mm", "Ransac threshold (circles)", "mm",
                         Stage::Features, D, 0.0001, 50, 0.05,
                         "Distance within which a keypoint is an inlier of a circle.")));
  t.push_back(entry(&RP::features, &FeatureParams::max_iterations,
                    make("features.max_iterations", "Ransac trials", "", Stage::Features, I, 10,
                         100000, 10, "Random samples drawn per line or circle search.")));
  t.push_back(entry(&RP::features, &FeatureParams::max_features,
                    make("features.max_features", "Max features", "", Stage::Features, I, 1, 10000,
                         1, "Stop extracting after this many lines and circles per cloud.")));
  t.push_back(
      entry(&RP::features, &FeatureParams::min_circle_radius_mm,
            make("features.min_circle_radius_mm", "Min circle radius", "mm", Stage::Features, D, 0,
                 1000, 0.5, "Circles with a smaller radius are rejected.")));
  t.push_back(
      entry(&RP::features, &FeatureParams::max_circle_radius_mm,
            make("features.max_circle_radius_mm", "Max circle radius", "mm", Stage::Features, D, 0,
                 5000, 1, "Circles with a larger radius are rejected.")));
  t.push_back(entry(
      &RP::features, &FeatureParams::lines,
      make("features.lines", "Find lines", "", Stage::Features, B, 0, 1, 1, "Search 3D lines.")));
  t.push_back(entry(&RP::features, &FeatureParams::circles,
                    make("features.circles", "Find circles", "", Stage::Features, B, 0, 1, 1,
                         "Search 3D circles.")));
  t.push_back(entry(
      &RP::features, &FeatureParams::run_gap_mm,
      make("features.run_gap_mm", "Max inlier gap", "mm", Stage::Features, D, 0, 500, 0.5,
           "A line's or circle's inliers are cut where neighbours along it are farther apart than "
           "this and only the largest connected run is kept, so collinear edges of different "
           "objects do not merge; 0 = automatic.")));
  t.push_back(entry(
      &RP::features, &FeatureParams::sample_radius_mm,
      make("features.sample_radius_mm", "Sample radius", "mm", Stage::Features, D, 0, 1000, 1,
           "Beyond the thesis: the other points of a RANSAC sample are drawn within this "
           "distance of its first point, so features are found in far fewer trials; 0 = uniform "
           "sampling (the thesis).")));
  // --- Feature matching (§3.4) ---
  t.push_back(
      entry(&RP::matching, &MatchingParams::length_tolerance_mm,
            make("matching.length_tolerance_mm", "Matching length Δl", "mm", Stage::Matching, D, 0,
                 500, 0.5, "Two lines may match when their lengths differ by at most this.")));
  t.push_back(
      entry(&RP::matching, &MatchingParams::radius_tolerance_mm,
            make("matching.radius_tolerance_mm", "Matching radius size", "mm", Stage::Matching, D,
                 0, 500, 0.5, "Two circles may match when their radii differ by at most this.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::position_tolerance_mm,
      make("matching.position_tolerance_mm", "Matching position Δp", "mm", Stage::Matching, D, 0.01,
           200, 0.1,
           "Radius around the predicted position (on the roll toroid, and after the transform "
           "when scoring) within which a scene feature is accepted.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::orientation_tolerance_rad,
      make("matching.orientation_tolerance_rad", "Matching orientation Δo", "rad", Stage::Matching,
           D, 0.001, 3.14, 0.01,
           "Largest angle between predicted and found feature directions (line axis or circle "
           "normal).")));
  t.push_back(
      entry(&RP::matching, &MatchingParams::roll_step_deg,
            make("matching.roll_step_deg", "Roll step", "deg", Stage::Matching, D, 0.1, 90, 0.5,
                 "Angular step of the search around T1's axis (the toroid of Figure 3.5).")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::score_threshold,
      make("matching.score_threshold", "Score", "", Stage::Matching, D, 0, 1, 0.01,
           "Detections whose share of confirmed model features is below this are rejected.")));
  t.push_back(entry(&RP::matching, &MatchingParams::max_detections,
                    make("matching.max_detections", "Max detections", "", Stage::Matching, I, 0,
                         1000, 1, "Report at most this many detections, best first; 0 = all.")));
  t.push_back(
      entry(&RP::matching, &MatchingParams::max_instances_per_cluster,
            make("matching.max_instances_per_cluster", "Instances per object", "", Stage::Matching,
                 I, 1, 50, 1,
                 "Searches per scene cluster: after a detection its features are removed and the "
                 "cluster is searched again, since clustering may merge touching parts.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::verify_tolerance_mm,
      make("matching.verify_tolerance_mm", "Verify distance", "mm", Stage::Matching, D, 0, 50, 0.1,
           "Beyond the thesis: a pose is verified by the share of model points with a scene "
           "point within this distance, less those the camera sees through (organized scans); "
           "0 = off (the thesis's feature score only).")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::min_coverage,
      make("matching.min_coverage", "Min coverage", "", Stage::Matching, D, 0, 1, 0.01,
           "With verification on: detections confirming a smaller share of their visible model "
           "points are rejected.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::edge_tolerance_mm,
      make("matching.edge_tolerance_mm", "Edge distance", "mm", Stage::Matching, D, 0, 50, 0.1,
           "Beyond the thesis: with verification on, the coverage is also weighed by the share "
           "of the model's keypoints (edges) lying on confirmed surface that have a scene keypoint "
           "within this distance, so a plate turned on another plate scores low; 0 = off.")));
  t.push_back(
      entry(&RP::matching, &MatchingParams::hypotheses,
            make("matching.hypotheses", "Hypotheses", "", Stage::Matching, I, 1, 64, 1,
                 "Distinct poses per search re-ranked by verification; 1 = the thesis (the best "
                 "feature score alone decides).")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::pool_size,
      make("matching.pool_size", "Pose pool", "", Stage::Matching, I, 0, 5000, 10,
           "Beyond the thesis, for bins of touching parts: with verification on, one search keeps "
           "up to this many distinct poses from all seed pairs, verifies each and reports every "
           "one reaching the min coverage (instead of repeated best-first searches); 0 = off.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::surface_sampling_mm,
      make("matching.surface_sampling_mm", "Surface sampling", "mm", Stage::Matching, D, 0, 100,
           0.5,
           "Beyond the thesis: with verification on, surface point pair voting adds pose "
           "hypotheses that need no line or circle pairs (parts whose edges are hidden by their "
           "neighbours); model and scene are sampled with voxels of this edge, about 4 % of the "
           "part's diameter; 0 = off.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::surface_reference_stride,
      make("matching.surface_reference_stride", "Surface reference stride", "", Stage::Matching, I,
           1, 100, 1,
           "Surface voting: every n-th sampled scene point votes as a reference; lower finds more "
           "(partly hidden) parts, higher is faster.")));
  t.push_back(
      entry(&RP::matching, &MatchingParams::surface_poses,
            make("matching.surface_poses", "Surface poses", "", Stage::Matching, I, 1, 5000, 10,
                 "Surface voting: at most this many voted poses (most votes first) are refined and "
                 "verified.")));
  t.push_back(entry(
      &RP::matching, &MatchingParams::symmetry_overlap,
      make("matching.symmetry_overlap", "Near-symmetry overlap", "", Stage::Matching, D, 0, 1, 0.05,
           "Beyond the thesis, for nearly symmetric parts (a plate whose hook differs only at its "
           "lip): a turn of the view, found by voting the view against itself, that puts this "
           "share of its points back on its own surface is a near symmetry; each detection is "
           "compared with its turned pose on the points that differ, and the pose the scan "
           "contradicts clearly less is kept, or both are reported when it cannot tell. Needs "
           "verification; 0 = off.")));
  // --- Refinement (beyond the thesis) ---
  t.push_back(
      entry(&RP::refine, &RefineParams::enabled,
            make("refine.enabled", "ICP refinement", "", Stage::Refine, B, 0, 1, 1,
                 "Refine each detection's pose with ICP against the scene points; views that know "
                 "their place in the part fit the other views' points too, and several views' "
                 "detections are refined after they are merged.")));
  t.push_back(entry(&RP::refine, &RefineParams::max_iterations,
                    make("refine.max_iterations", "ICP iterations", "", Stage::Refine, I, 1, 500, 1,
                         "Upper bound on ICP iterations.")));
  t.push_back(
      entry(&RP::refine, &RefineParams::max_correspondence_mm,
            make("refine.max_correspondence_mm", "ICP distance", "mm", Stage::Refine, D, 0.01, 100,
                 0.1, "Model-scene point pairs farther apart than this are ignored by ICP.")));
  t.push_back(
      entry(&RP::refine, &RefineParams::min_correspondence_mm,
            make("refine.min_correspondence_mm", "ICP final distance", "mm", Stage::Refine, D, 0.01,
                 100, 0.1,
                 "The pair distance shrinks from the ICP distance towards 3x the residual, but not "
                 "below this; about 5-10x the sensor noise (PhoXi 1 mm, Kinect 10 mm).")));
  t.push_back(entry(
      &RP::refine, &RefineParams::inlier_distance_mm,
      make("refine.inlier_distance_mm", "Inlier distance", "mm", Stage::Refine, D, 0.01, 100, 0.1,
           "A visible model point with a scene point this close confirms the refined pose.")));
  t.push_back(
      entry(&RP::refine, &RefineParams::convergence_mm,
            make("refine.convergence_mm", "ICP convergence", "mm", Stage::Refine, D, 0.000001, 10,
                 0.001, "ICP stops when an iteration moves no model point by more than this.")));
  t.push_back(entry(
      &RP::refine, &RefineParams::model_points,
      make("refine.model_points", "ICP model points", "points", Stage::Refine, I, 10, 1000000, 100,
           "Model points used by ICP (an even voxel subsample); more is slower, rarely better.")));
  t.push_back(entry(
      &RP::refine, &RefineParams::point_to_plane,
      make("refine.point_to_plane", "Point-to-plane", "", Stage::Refine, B, 0, 1, 1,
           "Minimise point-to-plane distances (fast, sub-sample accurate); off: point-to-point.")));
  t.push_back(entry(
      &RP::refine, &RefineParams::min_inlier_fraction,
      make("refine.min_inlier_fraction", "ICP min inliers", "", Stage::Refine, D, 0, 1, 0.01,
           "A refined pose counts as converged only if this share of the visible model points "
           "has a scene point within the inlier distance.")));
  t.push_back(entry(
      &RP::refine, &RefineParams::axial_ends,
      make("refine.axial_ends", "Slide to the ends", "", Stage::Refine, B, 0, 1, 1,
           "After ICP, a view that is a surface of revolution (a cup or pipe on its side) is slid "
           "along its axis to where the scan shows its wall's two ends, which ICP hardly pins; "
           "the middle between the ends is where the part's middle is, whatever the pixel size.")));
  t.push_back(entry(
      &RP::refine, &RefineParams::outline_ends,
      make("refine.outline_ends", "Slide to the outline", "", Stage::Refine, B, 0, 1, 1,
           "After ICP, a view that is no surface of revolution is moved along each direction ICP "
           "hardly pins (a plate seen face-on, in its own plane), or pins loosely where both "
           "sides agree within 0.1 mm (a plate seen edge-on, along its length), to where the "
           "scan's points end as the view's do, both sides of the outline together; other views "
           "of the part tell where this view's ends were hidden when it was taught. ICP then "
           "leaves the directions it hardly pins as they came, for the outline to place. Helps "
           "plates; a view cut from a cluttered scan can lose by it.")));
  // --- Seed ---
  ParamInfo seed = make("seed", "Random seed", "", Stage::Preprocess, I, 0, 2147483647, 1,
                        "Seed of every random choice; the same input and seed give the same "
                        "output.");
  seed.get = [](const RP& p) { return static_cast<double>(p.seed); };
  seed.set = [](RP& p, double v) {
    p.seed = static_cast<std::uint64_t>(std::clamp(v, 0.0, 2147483647.0));
  };
  t.push_back(std::move(seed));
  for (ParamInfo& info : t)
    info.tuned = std::find(std::begin(kTunedParameters), std::end(kTunedParameters), info.key) !=
                 std::end(kTunedParameters);
  return t;
}

} // namespace

std::span<const ParamInfo> parameterTable() {
  static const std::vector<ParamInfo> table = buildTable();
  return table;
}

const ParamInfo* findParameter(std::string_view key) {
  for (const auto& info : parameterTable())
    if (info.key == key)
      return &info;
  return nullptr;
}

void checkParamValue(const ParamInfo& info, double value) {
  const bool whole = info.type != ParamType::Double;
  if (std::isfinite(value) && value >= info.min_value && value <= info.max_value &&
      (!whole || value == std::round(value)))
    return;
  std::ostringstream range;
  range << info.min_value << " – " << info.max_value;
  throw Error("'" + info.key + "' = " + std::to_string(value) + " is outside its range " +
              range.str() + (whole ? " (a whole number)" : ""));
}

std::string stageName(Stage stage) {
  switch (stage) {
  case Stage::Preprocess:
    return "Scene preprocessing";
  case Stage::Clustering:
    return "Object count and clustering";
  case Stage::Keypoints:
    return "First-level keypoints";
  case Stage::Features:
    return "Second-level features";
  case Stage::Matching:
    return "Feature matching";
  case Stage::Refine:
    return "Refinement";
  }
  return "?";
}

std::optional<Stage> firstChangedStage(const RecognitionParams& a, const RecognitionParams& b) {
  std::optional<Stage> first;
  for (const auto& info : parameterTable())
    if (info.get(a) != info.get(b) && (!first || info.stage < *first))
      first = info.stage;
  return first;
}

} // namespace scanpick::core
