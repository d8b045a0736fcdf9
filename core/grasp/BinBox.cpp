#include "core/grasp/BinBox.h"

#include "core/common/Error.h"
#include "core/common/PrincipalAxes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace scanpick::core::grasp {
namespace {

struct Plane {
  Eigen::Vector3d normal; ///< unit
  double d = 0.0;         ///< normal·p + d = 0
  std::vector<Eigen::Vector3d> inliers;
};

/// Least-squares plane through `points` (their PCA's smallest axis).
bool fitPlane(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& normal, double& d) {
  if (points.size() < 3)
    return false;
  const PrincipalAxes pca = principalAxes(points);
  normal = pca.axes.col(0).normalized();
  d = -normal.dot(pca.mean);
  return normal.allFinite();
}

/// Sequential RANSAC: the largest plane of `points`, removed from them, as long as one holds
/// `min_inliers`.
std::vector<Plane> findPlanes(std::vector<Eigen::Vector3d> points, const BinEstimateParams& p,
                              std::size_t min_inliers) {
  std::mt19937_64 rng(p.seed);
  std::vector<Plane> planes;
  for (int k = 0; k < p.max_planes && points.size() >= std::max<std::size_t>(min_inliers, 3); ++k) {
    std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
    std::size_t best_count = 0;
    Eigen::Vector3d best_n = Eigen::Vector3d::UnitZ();
    double best_d = 0.0;
    for (int it = 0; it < p.iterations; ++it) {
      const Eigen::Vector3d& a = points[pick(rng)];
      const Eigen::Vector3d& b = points[pick(rng)];
      const Eigen::Vector3d& c = points[pick(rng)];
      const Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() < 1e-6)
        continue;
      const Eigen::Vector3d un = n.normalized();
      const double d = -un.dot(a);
      std::size_t count = 0;
      for (const auto& q : points)
        count += std::abs(un.dot(q) + d) <= p.distance_mm ? 1 : 0;
      if (count > best_count) {
        best_count = count;
        best_n = un;
        best_d = d;
      }
    }
    if (best_count < min_inliers)
      break;
    Plane plane;
    std::vector<Eigen::Vector3d> rest;
    for (const auto& q : points)
      (std::abs(best_n.dot(q) + best_d) <= p.distance_mm ? plane.inliers : rest).push_back(q);
    if (!fitPlane(plane.inliers, plane.normal, plane.d)) {
      plane.normal = best_n;
      plane.d = best_d;
    }
    planes.push_back(std::move(plane));
    points = std::move(rest);
  }
  return planes;
}

} // namespace

std::string binCollision(const BinBox& bin, const Eigen::Vector3d& p_scene_mm, double margin_mm) {
  const Eigen::Vector3d p = bin.T_scene_bin.inverse() * p_scene_mm;
  if (bin.floor_found && p.z() < margin_mm)
    return "bin floor";
  if (p.z() >= bin.rim_height_mm)
    return "";
  static const char* const kNames[4] = {"bin wall +x", "bin wall -x", "bin wall +y", "bin wall -y"};
  const double v[4] = {p.x() - bin.half_size_mm.x(), -p.x() - bin.half_size_mm.x(),
                       p.y() - bin.half_size_mm.y(), -p.y() - bin.half_size_mm.y()};
  for (int i = 0; i < 4; ++i)
    if (bin.walls_found[std::size_t(i)] && v[i] > -margin_mm)
      return kNames[i];
  return "";
}

namespace {

/// Throws Error for an up that is not a unit vector or a parameter out of range.
void checkBinParams(const BinEstimateParams& params) {
  const Eigen::Vector3d up = params.up;
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-3)
    throw Error("bin estimate: up must be a unit vector");
  if (!(params.distance_mm > 0.0) || !(params.angle_tol_deg > 0.0 && params.angle_tol_deg < 45.0) ||
      !(params.min_plane_share > 0.0 && params.min_plane_share < 1.0) || params.max_planes < 1 ||
      params.iterations < 1 || params.max_samples < 3)
    throw Error("bin estimate: a parameter is out of range (distance_mm > 0, angle_tol_deg in "
                "(0, 45), min_plane_share in (0, 1), max_planes, iterations, max_samples >= 1)");
}

/// Every stride-th of the scene's `valid` valid points (mm), at most `max_samples` of them.
std::vector<Eigen::Vector3d> evenSample(const PointCloud& scene_mm, std::size_t valid,
                                        std::size_t max_samples) {
  const std::size_t stride = (valid + max_samples - 1) / max_samples;
  std::vector<Eigen::Vector3d> sample;
  std::size_t seen = 0;
  for (const auto& p : scene_mm.points_mm)
    if (isValid(p) && seen++ % stride == 0)
      sample.push_back(p.cast<double>());
  return sample;
}

/// The planes perpendicular to up (within the angle whose sine is `sin_tol`), each turned to face
/// `centre`, in the order found.
std::vector<const Plane*> inwardWalls(std::vector<Plane>& planes, const Eigen::Vector3d& up,
                                      const Eigen::Vector3d& centre, double sin_tol) {
  std::vector<const Plane*> walls;
  for (auto& plane : planes) {
    if (std::abs(plane.normal.dot(up)) >= sin_tol)
      continue;
    if (plane.normal.dot(centre) + plane.d < 0.0) {
      plane.normal = -plane.normal;
      plane.d = -plane.d;
    }
    walls.push_back(&plane);
  }
  return walls;
}

/// The walls assigned to the bin's four sides.
struct WallSides {
  /// Wall offsets from the centre along x and y: [+x, -x, +y, -y]; NaN where none was found.
  double offset[4];
  std::vector<const Plane*> used; ///< the walls that set an offset
};

/// Assigns each wall facing along x or y (within the angle whose cosine is `cos_tol`) to its side;
/// the first (largest) plane on a side is its wall.
WallSides wallSides(const std::vector<const Plane*>& walls,
                    const std::array<Eigen::Vector3d, 2>& axes, const Eigen::Vector3d& centre,
                    double cos_tol) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  WallSides sides{{nan, nan, nan, nan}, {}};
  for (const Plane* w : walls) {
    for (int a = 0; a < 2; ++a) {
      const double along = w->normal.dot(axes[std::size_t(a)]);
      if (std::abs(along) < cos_tol)
        continue;
      // The inward normal points against the wall's side: -x for the +x wall.
      const int slot = 2 * a + (along < 0.0 ? 0 : 1);
      const double t = -(w->normal.dot(centre) + w->d) / along;
      if (std::isnan(sides.offset[slot])) {
        sides.offset[slot] = t;
        sides.used.push_back(w);
      }
    }
  }
  return sides;
}

/// Sets the bin's found walls and half sizes from the sides' offsets, and moves `origin` from the
/// centre to midway between each pair of opposite walls.
void placeWalls(const WallSides& sides, const std::array<Eigen::Vector3d, 2>& axes, BinBox& bin,
                Eigen::Vector3d& origin) {
  for (int a = 0; a < 2; ++a) {
    const double hi = sides.offset[2 * a], lo = sides.offset[2 * a + 1];
    bin.walls_found[std::size_t(2 * a)] = !std::isnan(hi);
    bin.walls_found[std::size_t(2 * a + 1)] = !std::isnan(lo);
    if (!std::isnan(hi) && !std::isnan(lo)) {
      origin += 0.5 * (hi + lo) * axes[std::size_t(a)];
      bin.half_size_mm[a] = 0.5 * (hi - lo);
    } else {
      bin.half_size_mm[a] = std::abs(std::isnan(hi) ? lo : hi);
    }
  }
}

/// The floor's height along up from `origin`: the lowest plane facing up (within the angle whose
/// cosine is `cos_tol`) with most of its points between the walls of `probe`; `lowest_wall`
/// when there is none.
double floorHeight(const std::vector<Plane>& planes, const BinBox& probe,
                   const Eigen::Vector3d& origin, const Eigen::Vector3d& up, double cos_tol,
                   double distance_mm, double lowest_wall) {
  double floor_h = lowest_wall;
  bool plane_floor = false;
  for (const auto& plane : planes) {
    if (std::abs(plane.normal.dot(up)) <= cos_tol)
      continue;
    std::size_t inside = 0;
    for (const auto& p : plane.inliers)
      inside += binCollision(probe, p, -distance_mm).empty() ? 1 : 0;
    if (2 * inside < plane.inliers.size())
      continue; // a table around the bin, or a rim
    const double h = -(plane.normal.dot(origin) + plane.d) / plane.normal.dot(up);
    if (!plane_floor || h < floor_h) {
      floor_h = h;
      plane_floor = true;
    }
  }
  return floor_h;
}

} // namespace

std::optional<BinBox> estimateBin(const PointCloud& scene_mm, const BinEstimateParams& params) {
  const Eigen::Vector3d up = params.up;
  checkBinParams(params);
  const std::size_t valid = scene_mm.validCount();
  if (valid < 3)
    return std::nullopt;
  const std::vector<Eigen::Vector3d> sample = evenSample(scene_mm, valid, params.max_samples);
  const auto min_inliers =
      std::max<std::size_t>(3, std::size_t(params.min_plane_share * double(sample.size())));
  std::vector<Plane> planes = findPlanes(sample, params, min_inliers);

  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : sample)
    centre += p;
  centre /= double(sample.size());
  const double cos_tol = std::cos(params.angle_tol_deg * std::numbers::pi / 180.0);
  const double sin_tol = std::sin(params.angle_tol_deg * std::numbers::pi / 180.0);

  // Walls: perpendicular to up, turned to face the centre; the first one found sets +x.
  const std::vector<const Plane*> walls = inwardWalls(planes, up, centre, sin_tol);
  if (walls.empty())
    return std::nullopt;
  const Eigen::Vector3d x =
      -(walls.front()->normal - walls.front()->normal.dot(up) * up).normalized();
  const Eigen::Vector3d y = up.cross(x);
  const std::array<Eigen::Vector3d, 2> axes = {x, y};
  const WallSides sides = wallSides(walls, axes, centre, cos_tol);
  BinBox bin;
  Eigen::Vector3d origin = centre;
  placeWalls(sides, axes, bin, origin);
  // Heights along up from the origin's level.
  double lowest_wall = std::numeric_limits<double>::infinity();
  double highest_wall = -std::numeric_limits<double>::infinity();
  for (const Plane* w : sides.used)
    for (const auto& p : w->inliers) {
      lowest_wall = std::min(lowest_wall, (p - origin).dot(up));
      highest_wall = std::max(highest_wall, (p - origin).dot(up));
    }
  BinBox probe = bin; // walls only, to tell which horizontal planes lie inside them
  probe.T_scene_bin.linear().col(0) = x;
  probe.T_scene_bin.linear().col(1) = y;
  probe.T_scene_bin.linear().col(2) = up;
  probe.T_scene_bin.translation() = origin - 1e6 * up; // every point is above its "floor"
  probe.rim_height_mm = std::numeric_limits<double>::infinity();
  const double floor_h =
      floorHeight(planes, probe, origin, up, cos_tol, params.distance_mm, lowest_wall);
  bin.floor_found = true;
  bin.rim_height_mm = highest_wall - floor_h;
  bin.T_scene_bin = probe.T_scene_bin;
  bin.T_scene_bin.translation() = origin + floor_h * up;
  return bin;
}

} // namespace scanpick::core::grasp
