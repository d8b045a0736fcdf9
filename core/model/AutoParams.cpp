#include "core/model/AutoParams.h"

#include "core/cloud/PointKdTree.h"
#include "core/common/Error.h"
#include "core/common/PrincipalAxes.h"
#include "core/params/ParameterTable.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <spdlog/fmt/fmt.h>

namespace scanpick::core {
namespace {

constexpr std::size_t kMinPoints = 10;
constexpr std::size_t kMaxExamined = 4000;
constexpr std::size_t kPlaneNeighbours = 12;

std::vector<Eigen::Vector3f> validPoints(const PointCloud& cloud) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud.points_mm)
    if (isValid(p))
      points.push_back(p);
  if (points.size() < kMinPoints)
    throw Error("the crop holds " + std::to_string(points.size()) +
                " valid points: too few to measure the scan (widen the crop box)");
  return points;
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// Indices of at most kMaxExamined points, evenly strided.
std::vector<std::size_t> examined(std::size_t count) {
  const std::size_t stride = std::max<std::size_t>(1, count / kMaxExamined);
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < count; i += stride)
    indices.push_back(i);
  return indices;
}

/// A lower bound of the diameter: the largest distance among the points extreme along 62
/// directions spread over the sphere (within ~1 % of the exact value).
double extremesDistance_mm(const std::vector<Eigen::Vector3f>& points) {
  std::vector<std::size_t> extremes;
  constexpr int kDirections = 31;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int d = 0; d < kDirections; ++d) {
    const double z = 1.0 - (d + 0.5) / kDirections, r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3f axis(float(r * std::cos(golden * d)), float(r * std::sin(golden * d)),
                               float(z));
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      const float t = axis.dot(points[i]);
      lo = t < axis.dot(points[lo]) ? i : lo;
      hi = t > axis.dot(points[hi]) ? i : hi;
    }
    extremes.push_back(lo);
    extremes.push_back(hi);
  }
  double best = 0.0;
  for (std::size_t a = 0; a < extremes.size(); ++a)
    for (std::size_t b = a + 1; b < extremes.size(); ++b)
      best = std::max(best, (points[extremes[a]] - points[extremes[b]]).cast<double>().norm());
  return best;
}

/// The points binned in a grid of cubic cells, each cell with the bounding box of its points.
struct CellGrid {
  struct Cell {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
    std::vector<std::size_t> members;
  };
  std::vector<Cell> cells;
};

CellGrid binPoints(const std::vector<Eigen::Vector3f>& points, double cell_mm) {
  std::map<std::array<std::int64_t, 3>, std::size_t> index_of;
  CellGrid grid;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = points[i].cast<double>();
    const std::array<std::int64_t, 3> key{std::int64_t(std::floor(p.x() / cell_mm)),
                                          std::int64_t(std::floor(p.y() / cell_mm)),
                                          std::int64_t(std::floor(p.z() / cell_mm))};
    const auto [it, added] = index_of.try_emplace(key, grid.cells.size());
    if (added)
      grid.cells.emplace_back();
    auto& cell = grid.cells[it->second];
    cell.low = cell.low.cwiseMin(p);
    cell.high = cell.high.cwiseMax(p);
    cell.members.push_back(i);
  }
  return grid;
}

/// The largest distance between two of `points`, exact: starting from the extremes' lower
/// bound, only pairs of grid cells whose bounding boxes can lie farther apart are examined.
double largestDistance_mm(const std::vector<Eigen::Vector3f>& points) {
  double best = extremesDistance_mm(points);
  if (!(best > 0))
    return 0.0;
  const CellGrid grid = binPoints(points, best / 24);
  for (std::size_t a = 0; a < grid.cells.size(); ++a)
    for (std::size_t b = a; b < grid.cells.size(); ++b) {
      const auto &ca = grid.cells[a], &cb = grid.cells[b];
      const Eigen::Vector3d span =
          (ca.high - cb.low).cwiseAbs().cwiseMax((cb.high - ca.low).cwiseAbs());
      if (span.norm() <= best)
        continue;
      for (const std::size_t i : ca.members)
        for (const std::size_t j : cb.members)
          best = std::max(best, (points[i] - points[j]).cast<double>().norm());
    }
  return best;
}

/// Records each value set, clamped to its parameter's range as the table does.
class Deriver {
public:
  explicit Deriver(AutoParams& out) : m_out(out) {}
  double set(const std::string& key, double value, std::string reason) {
    const ParamInfo* info = findParameter(key);
    if (!info)
      throw Error("internal: no parameter '" + key + "'");
    info->set(m_out.params, value);
    const double stored = info->get(m_out.params);
    std::erase_if(m_out.values, [&](const DerivedValue& v) { return v.key == key; });
    m_out.values.push_back({key, stored, std::move(reason)});
    return stored;
  }

private:
  AutoParams& m_out;
};

std::string mm(double value) {
  return fmt::format("{:.3g} mm", value);
}

} // namespace

ScanMeasures measureScan(const PointCloud& cloud_mm) {
  const std::vector<Eigen::Vector3f> points = validPoints(cloud_mm);
  const PointVectorSource source{&points};
  PointKdTree tree(3, source);
  tree.buildIndex();
  std::vector<double> spacing, noise;
  std::vector<std::uint32_t> index(kPlaneNeighbours + 1);
  std::vector<float> distance2(kPlaneNeighbours + 1);
  for (const std::size_t i : examined(points.size())) {
    const std::size_t found =
        tree.knnSearch(points[i].data(), kPlaneNeighbours + 1, index.data(), distance2.data());
    if (found < 2)
      continue;
    spacing.push_back(std::sqrt(double(distance2[1])));
    if (found < kPlaneNeighbours + 1)
      continue;
    const PrincipalAxes plane =
        principalAxes(found, [&](std::size_t k) { return points[index[k]]; });
    noise.push_back(std::sqrt(plane.variances[0]));
  }
  ScanMeasures measures;
  measures.spacing_mm = spacing.empty() ? 0.0 : median(spacing);
  measures.noise_mm = noise.empty() ? 0.0 : median(noise);
  return measures;
}

PartMeasures measurePart(const PointCloud& part_mm, double spacing_mm) {
  const std::vector<Eigen::Vector3f> all = validPoints(part_mm);
  const PointVectorSource source{&all};
  PointKdTree tree(3, source);
  tree.buildIndex();
  // Flying pixels: far from their third-nearest neighbour.
  const auto limit2 = static_cast<float>(std::pow(5.0 * std::max(spacing_mm, 1e-3), 2));
  std::vector<Eigen::Vector3f> points;
  points.reserve(all.size());
  std::array<std::uint32_t, 4> index{};
  std::array<float, 4> distance2{};
  for (const auto& p : all)
    if (tree.knnSearch(p.data(), 4, index.data(), distance2.data()) == 4 && distance2[3] <= limit2)
      points.push_back(p);
  if (points.size() < kMinPoints)
    points = all;

  PartMeasures measures;
  measures.points = all.size();
  const PrincipalAxes pca = principalAxes(points);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const auto& p : points) {
    const Eigen::Vector3d q = pca.axes.transpose() * (p.cast<double>() - pca.mean);
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  const Eigen::Vector3d extent = high - low; // smallest eigenvalue first
  measures.extent_mm = Eigen::Vector3d(extent[2], extent[1], extent[0]);

  measures.diameter_mm = largestDistance_mm(points);
  return measures;
}

AutoParams deriveScanParams(const ScanMeasures& scan, RecognitionParams base) {
  AutoParams out;
  out.params = std::move(base);
  out.scan = scan;
  Deriver d(out);
  const double s = scan.spacing_mm, sigma = scan.noise_mm;
  double floor_mm = std::max({1.0, 3.0 * s, 8.0 * sigma});
  std::string floor_reason = "3 x the point spacing (" + mm(s) + ") or 8 x the depth noise (" +
                             mm(sigma) + "), at least 1 mm: the whole floor within, noise and all";
  const double layer = scan.part_layer_mm;
  if (layer > 0 && 0.5 * layer < floor_mm) {
    floor_mm = std::max(0.5 * layer, 4.0 * sigma);
    floor_reason = "half the height of the part's lowest face above the floor (" + mm(layer) +
                   "), at least 4 x the depth noise (" + mm(sigma) +
                   "): a thin part lying flat stays";
  }
  d.set("floor.distance_mm", floor_mm, floor_reason);
  d.set("floor.bin_floor_fraction", 0.02,
        "a bin's floor (a plane parallel to the ground with nothing behind it) goes too");
  d.set("floor.bin_walls", 1.0,
        "a bin's walls and rim go too: a part's flat face matches a wall all along it");
  d.set("clustering.method", 1.0, "projected clusters keep touching parts apart");
  d.set("clustering.count_radius_mm", std::max(1.5, 3.0 * s),
        "3 x the point spacing, at least 1.5 mm: neighbouring points of one part link");
  return out;
}

AutoParams deriveParams(const ScanMeasures& scan, const PartMeasures& part,
                        RecognitionParams base) {
  AutoParams out = deriveScanParams(scan, std::move(base));
  out.part = part;
  Deriver d(out);
  const double s = scan.spacing_mm, sigma = scan.noise_mm, size = part.diameter_mm;
  const std::string spacing = " the point spacing (" + mm(s) + ")";
  const std::string noise = " the depth noise (" + mm(sigma) + ")";
  const std::string diameter = " the part's diameter (" + mm(size) + ")";

  d.set("clustering.count_min_points", std::clamp(0.1 * double(part.points), 30.0, 1000.0),
        "a tenth of the taught view's " + std::to_string(part.points) +
            " points (30 to 1000): a part half hidden still counts");
  const double radius = d.set("keypoints.neighbourhood_radius_mm", 4.0 * s,
                              "4 x" + spacing + ": about 50 neighbours per point");
  d.set("keypoints.normal_radius_mm", radius, "as the neighbourhood radius");
  d.set("keypoints.position_range_mm", std::max(radius / 6.0, 3.0 * sigma),
        "a sixth of the neighbourhood radius, at least 3 x" + noise +
            ": a centroid this far off marks an edge");
  const double across = size / std::max(s, 1e-3);
  d.set("features.ransac_size", std::clamp(0.15 * across, 6.0, 15.0),
        "0.15 x the points across the part (" + fmt::format("{:.0f}", across) +
            "), 6 to 15: a line or circle of a small part holds fewer keypoints");
  const double threshold =
      std::max(1.4 * s, 3.0 * sigma); // keypoints of one edge scatter about a spacing
  d.set("features.line_threshold_mm", threshold, "1.4 x" + spacing + ", at least 3 x" + noise);
  d.set("features.circle_threshold_mm", threshold, "as the line threshold");
  d.set("features.max_circle_radius_mm", std::max(0.6 * size, 2.0),
        "0.6 x" + diameter + ": no circle of the part is larger");
  d.set("features.sample_radius_mm", std::max(0.07 * size, 3.0 * radius),
        "0.07 x" + diameter + ", at least 3 neighbourhood radii");
  d.set("features.max_iterations", 50, "samples drawn near each other find edges in few trials");
  d.set("matching.length_tolerance_mm", std::max(0.07 * size, 10.0 * s),
        "0.07 x" + diameter + ", at least 10 x" + spacing + ": occlusion shortens lines");
  d.set("matching.radius_tolerance_mm", 3.0 * threshold, "3 x the circle threshold");
  d.set("matching.position_tolerance_mm", std::max(0.035 * size, 4.0 * threshold),
        "0.035 x" + diameter + ", at least 4 x the line threshold");
  d.set("matching.orientation_tolerance_rad",
        std::clamp(std::atan(4.0 * threshold / std::max(0.3 * size, 1e-3)), 0.15, 0.3),
        "the angle 4 x the line threshold makes over 0.3 x" + diameter + " (0.15 to 0.3 rad)");
  const double verify = d.set("matching.verify_tolerance_mm", std::max(1.4 * s, 5.0 * sigma),
                              "1.4 x" + spacing + ", at least 5 x" + noise +
                                  ": a surface point confirms the pose within");
  d.set("matching.edge_tolerance_mm", 2.0 * verify, "2 x the verification tolerance");
  d.set("matching.min_coverage", 0.75,
        "three quarters of the surface the camera should see: less is weak evidence");
  d.set("matching.hypotheses", 16, "poses re-ranked by verification per search");
  d.set("matching.max_instances_per_cluster", 40, "touching parts in one cluster");
  d.set("matching.pool_size", 200, "poses kept over all seed pairs of a cluster");
  d.set("matching.surface_sampling_mm", std::max(0.035 * size, 2.5 * s),
        "0.035 x" + diameter + ", at least 2.5 x" + spacing +
            ": surface voting finds parts without features");
  d.set("matching.surface_reference_stride", 16, "every 16th sampled scene point votes");
  d.set("matching.surface_poses", 30, "voted poses verified");
  d.set("matching.symmetry_overlap", 0.75,
        "a rotation that puts three quarters of the view back on itself is checked against the "
        "scan, or reported as an alternative pose");
  d.set("refine.enabled", 1.0, "ICP brings poses to the scan's own accuracy");
  d.set("refine.max_correspondence_mm", std::max(5.0 * verify, 0.02 * size),
        "5 x the verification tolerance, at least 0.02 x" + diameter + ": the coarse pose's error");
  d.set("refine.min_correspondence_mm", verify, "the verification tolerance");
  d.set("refine.inlier_distance_mm", verify, "the verification tolerance");
  return out;
}

} // namespace scanpick::core
