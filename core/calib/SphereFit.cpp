#include "core/calib/SphereFit.h"

#include "core/common/Error.h"
#include "core/common/PrincipalAxes.h"

#include <algorithm>
#include <cmath>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_sphere.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <random>

namespace scanpick::core::calib {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A plane n·p + d = 0 with a unit normal n.
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0;
  [[nodiscard]] double distance(const Eigen::Vector3d& p) const { return std::abs(n.dot(p) + d); }
};

/// Least-squares plane through `points` (the smallest principal direction).
Plane fitPlane(const std::vector<Eigen::Vector3d>& points) {
  const PrincipalAxes pca = principalAxes(points);
  Plane plane;
  plane.n = pca.axes.col(0).normalized();
  plane.d = -plane.n.dot(pca.mean);
  return plane;
}

/// The plane with the most points within `threshold_mm`: RANSAC on at most 20,000 evenly spread
/// points (a scan can hold a million), then a least-squares fit to all its points.
Plane largestPlane(const std::vector<Eigen::Vector3d>& points, double threshold_mm,
                   std::mt19937_64& rng) {
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 20000);
  std::vector<Eigen::Vector3d> sample;
  for (std::size_t i = 0; i < points.size(); i += stride)
    sample.push_back(points[i]);
  std::uniform_int_distribution<std::size_t> pick(0, sample.size() - 1);
  Plane best;
  std::size_t best_count = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a = sample[pick(rng)], b = sample[pick(rng)], c = sample[pick(rng)];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9)
      continue;
    Plane plane;
    plane.n = n.normalized();
    plane.d = -plane.n.dot(a);
    std::size_t count = 0;
    for (const auto& p : sample)
      count += plane.distance(p) <= threshold_mm;
    if (count > best_count)
      best_count = count, best = plane;
  }
  // Two rounds of least squares on the points near the plane tighten it to the whole scan.
  for (int round = 0; round < 2; ++round) {
    std::vector<Eigen::Vector3d> near;
    for (const auto& p : points)
      if (best.distance(p) <= threshold_mm)
        near.push_back(p);
    if (near.size() < 3)
      break;
    best = fitPlane(near);
  }
  return best;
}

/// The points left after removing the large planes (SphereFitParams::plane_min_fraction).
std::vector<Eigen::Vector3d> withoutLargePlanes(std::vector<Eigen::Vector3d> points,
                                                const SphereFitParams& params) {
  std::mt19937_64 rng(params.seed);
  for (int i = 0; i < params.max_planes && points.size() >= 3; ++i) {
    const Plane plane = largestPlane(points, params.plane_threshold_mm, rng);
    std::vector<Eigen::Vector3d> rest;
    rest.reserve(points.size());
    for (const auto& p : points)
      if (plane.distance(p) > params.plane_threshold_mm)
        rest.push_back(p);
    const double removed = double(points.size() - rest.size());
    if (removed < params.plane_min_fraction * double(points.size()))
      break;
    // A flat surface's points spread across the slab by the sensor's noise; a slab through the
    // spheres (their tops or centres lie in one plane) is filled evenly, RMS threshold / √3.
    double sum_sq = 0;
    for (const auto& p : points)
      if (plane.distance(p) <= params.plane_threshold_mm)
        sum_sq += plane.distance(p) * plane.distance(p);
    if (std::sqrt(sum_sq / removed) > 0.4 * params.plane_threshold_mm)
      break;
    points = std::move(rest);
  }
  return points;
}

/// Clusters of points closer than `tolerance_mm`, each with at least `min_points`.
std::vector<std::vector<Eigen::Vector3d>> clusters(const std::vector<Eigen::Vector3d>& points,
                                                   double tolerance_mm, int min_points) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(points.size());
  for (const auto& p : points)
    cloud->push_back(pcl::PointXYZ(float(p.x()), float(p.y()), float(p.z())));
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(cloud);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
  extraction.setClusterTolerance(tolerance_mm);
  extraction.setMinClusterSize(min_points);
  extraction.setMaxClusterSize(std::numeric_limits<int>::max());
  extraction.setSearchMethod(tree);
  extraction.setInputCloud(cloud);
  std::vector<pcl::PointIndices> found;
  extraction.extract(found);
  std::vector<std::vector<Eigen::Vector3d>> out;
  for (const auto& indices : found) {
    std::vector<Eigen::Vector3d> members;
    members.reserve(indices.indices.size());
    for (const int i : indices.indices)
      members.push_back(points[std::size_t(i)]);
    out.push_back(std::move(members));
  }
  return out;
}

/// RANSAC sphere (PCL) in one cluster: centre and radius, or false.
bool ransacSphere(const std::vector<Eigen::Vector3d>& points, double radius_mm,
                  const SphereFitParams& params, Eigen::Vector4d& sphere) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : points)
    cloud->push_back(pcl::PointXYZ(float(p.x()), float(p.y()), float(p.z())));
  pcl::SampleConsensusModelSphere<pcl::PointXYZ>::Ptr model(
      new pcl::SampleConsensusModelSphere<pcl::PointXYZ>(cloud));
  model->setRadiusLimits((1 - params.radius_tolerance) * radius_mm,
                         (1 + params.radius_tolerance) * radius_mm);
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, params.sphere_threshold_mm);
  ransac.setMaxIterations(500);
  if (!ransac.computeModel())
    return false;
  Eigen::VectorXf coefficients;
  ransac.getModelCoefficients(coefficients);
  if (coefficients.size() != 4)
    return false;
  sphere = coefficients.cast<double>();
  return sphere.allFinite();
}

} // namespace

Eigen::Vector3d refineSphereCentre(const std::vector<Eigen::Vector3d>& points_mm,
                                   const Eigen::Vector3d& start_mm, double radius_mm,
                                   double threshold_mm, int& inliers, double& rms_mm) {
  Eigen::Vector3d c = start_mm;
  for (int iteration = 0; iteration < 20; ++iteration) {
    // Gauss-Newton on r_j = |p_j - c| - R, J_j = -(p_j - c)ᵀ / |p_j - c|.
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    int n = 0;
    for (const auto& p : points_mm) {
      const Eigen::Vector3d v = p - c;
      const double len = v.norm();
      const double r = len - radius_mm;
      if (len < 1e-9 || std::abs(r) > threshold_mm)
        continue;
      const Eigen::Vector3d J = -v / len;
      JtJ += J * J.transpose();
      Jtr += J * r;
      ++n;
    }
    if (n < 4)
      break;
    const Eigen::Vector3d step = JtJ.ldlt().solve(-Jtr);
    if (!step.allFinite())
      break;
    c += step;
    if (step.norm() < 1e-7)
      break;
  }
  inliers = 0;
  double sum_sq = 0;
  for (const auto& p : points_mm) {
    const double r = (p - c).norm() - radius_mm;
    if (std::abs(r) <= threshold_mm)
      ++inliers, sum_sq += r * r;
  }
  rms_mm = inliers > 0 ? std::sqrt(sum_sq / inliers) : 0.0;
  return c;
}

std::vector<SphereFit> fitSpheres(const PointCloud& scan, double radius_mm,
                                  const SphereFitParams& params) {
  if (!(radius_mm > 0))
    throw Error("the sphere radius must be positive (mm)");
  std::vector<Eigen::Vector3d> points;
  points.reserve(scan.size());
  for (const auto& p : scan.points_mm)
    if (isValid(p))
      points.push_back(p.cast<double>());
  points = withoutLargePlanes(std::move(points), params);
  const double tolerance =
      params.cluster_tolerance_mm > 0 ? params.cluster_tolerance_mm : 0.2 * radius_mm;
  // A cap at least min_cap_deg wide: the mean of its unit normals is at most (1 + cos α) / 2 long
  // (for points spread evenly over the cap's area).
  const double max_mean_normal = (1 + std::cos(params.min_cap_deg * kPi / 180)) / 2;

  std::vector<SphereFit> found;
  if (points.empty())
    return found;
  for (const auto& cluster : clusters(points, tolerance, params.min_sphere_points)) {
    Eigen::AlignedBox3d box;
    for (const auto& p : cluster)
      box.extend(p);
    if (box.sizes().maxCoeff() > 4 * radius_mm)
      continue; // not one sphere: a wall, an object, a sphere merged with its surroundings
    Eigen::Vector4d sphere;
    if (!ransacSphere(cluster, radius_mm, params, sphere))
      continue;
    SphereFit fit;
    fit.ransac_radius_mm = sphere[3];
    fit.centre_mm = refineSphereCentre(cluster, sphere.head<3>(), radius_mm,
                                       params.sphere_threshold_mm, fit.points, fit.rms_mm);
    if (fit.points < params.min_sphere_points || 2 * fit.points < int(cluster.size()))
      continue;
    Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
    for (const auto& p : cluster) {
      const Eigen::Vector3d v = p - fit.centre_mm;
      if (std::abs(v.norm() - radius_mm) <= params.sphere_threshold_mm)
        mean_normal += v.normalized();
    }
    if (mean_normal.norm() / fit.points > max_mean_normal)
      continue;
    found.push_back(fit);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const SphereFit& a, const SphereFit& b) { return a.points > b.points; });
  return found;
}

} // namespace scanpick::core::calib
