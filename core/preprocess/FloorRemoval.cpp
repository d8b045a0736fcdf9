#include "core/preprocess/FloorRemoval.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/common/PrincipalAxes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_parallel_plane.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <pcl/search/kdtree.h>
#include <string>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

/// PCL seeds its sampler with a constant; this exposes the generator so our seed drives it.
template <class Model> class Seeded : public Model {
public:
  using Model::Model;
  void seed(std::uint64_t s) { this->rng_alg_.seed(static_cast<unsigned>(s ^ (s >> 32))); }
};
using SeededPlaneModel = Seeded<pcl::SampleConsensusModelPlane<pcl::PointXYZ>>;
using SeededWallModel = Seeded<pcl::SampleConsensusModelParallelPlane<pcl::PointXYZ>>;

/// RANSAC on a sample is as good as on all points for a dominant plane and 10-20x cheaper.
constexpr std::size_t kMaxSamplePoints = 60000;
constexpr int kPlaneTrials = 500;

/// A bin floor is looked for in a band of this half-width (mm) around each height above the first
/// plane, wide enough for a bin floor a little tilted against the ground.
constexpr double kBinFloorBandMm = 5.0;

/// A bin floor has at most this share of the remaining points behind it (the bin walls' feet).
constexpr double kMaxShareBehindBinFloor = 0.02;

/// A supporting floor has at most this share of the points around the part farther than
/// kBehindDistances x the plane distance behind it (noise and flying pixels).
constexpr double kMaxShareBehindFloor = 0.02;
constexpr double kBehindDistances = 3.0;

/// Bin walls: at most this many, each within kWallAngleDeg of parallel to the bin floor's normal,
/// found by RANSAC (kWallTrials) on at most kMaxWallSamplePoints points whose three samples lie
/// within kWallSampleDistances x the plane distance of each other (a wall is a small share of a
/// bin's points: samples drawn far apart would rarely fall on one); kWallRetries planes with
/// points behind them (faces of parts) may be set aside.
constexpr std::size_t kMaxBinWalls = 4;
constexpr double kWallAngleDeg = 10.0;
constexpr int kWallTrials = 100;
constexpr std::size_t kMaxWallSamplePoints = 5000;
constexpr double kWallSampleDistances = 25.0;
constexpr int kWallRetries = 4;

/// A bin wall has at most this share of the points above the bin's floor behind it
/// (removeBinWalls): a face of a part inside the bin has the bin's far side behind it.
constexpr double kMaxShareBehindBinWall = 0.02;

/// "Around the part": within this many times the part's radius of its centre, along the plane.
/// What lies behind a table farther off (a room's floor or wall beyond the table's edge) says
/// nothing about whether the part rests on it.
constexpr float kAroundPartRadii = 1.5f;

/// Heights above the first plane searched for a bin floor (mm).
constexpr double kMaxBinFloorHeightMm = 500.0;

/// The bin floor among `alive` (indices into `points`): the plane parallel to `ground` (unit
/// normal towards the camera) whose band holds the most points, at least `min_points`, with at
/// most kMaxShareBehindBinFloor of them behind it; fitted by least squares to its band's points.
std::optional<Eigen::Vector4f> findBinFloor(const std::vector<Eigen::Vector3f>& points,
                                            const std::vector<int>& alive,
                                            const Eigen::Vector4f& ground, double bin_mm,
                                            std::size_t min_points) {
  const auto bins = static_cast<std::size_t>(std::ceil(kMaxBinFloorHeightMm / bin_mm));
  std::vector<std::size_t> histogram(bins, 0);
  std::size_t below = 0; // at or behind the first plane (its far side)
  for (const int i : alive) {
    const double h = ground.head<3>().dot(points[static_cast<std::size_t>(i)]) + ground[3];
    if (h < 0.0)
      ++below;
    else if (h < kMaxBinFloorHeightMm)
      ++histogram[static_cast<std::size_t>(h / bin_mm)];
  }
  const auto band = static_cast<std::size_t>(std::ceil(kBinFloorBandMm / bin_mm));
  const auto max_behind = static_cast<std::size_t>(kMaxShareBehindBinFloor * double(alive.size()));
  std::size_t behind = below, best_count = 0, best_bin = 0;
  for (std::size_t b = 0; b < bins; ++b) {
    // Points behind the band that starts `band` bins below b.
    if (b >= band + 1)
      behind += histogram[b - band - 1];
    if (behind > max_behind)
      break;
    std::size_t count = 0;
    for (std::size_t k = (b >= band ? b - band : 0); k <= std::min(bins - 1, b + band); ++k)
      count += histogram[k];
    if (count > best_count) {
      best_count = count;
      best_bin = b;
    }
  }
  if (best_count < std::max<std::size_t>(3, min_points))
    return std::nullopt;
  // Least-squares plane (PCA) through the band's points, then again through those within
  // `bin_mm` of it, so that the feet of the parts in the band do not tilt it.
  const auto fit = [&](const Eigen::Vector4d& around, double within_mm) {
    std::vector<Eigen::Vector3d> near;
    for (const int i : alive) {
      const Eigen::Vector3d p = points[static_cast<std::size_t>(i)].cast<double>();
      if (std::abs(around.head<3>().dot(p) + around[3]) <= within_mm)
        near.push_back(p);
    }
    if (near.size() < 3)
      return around;
    const PrincipalAxes pca = principalAxes(near);
    Eigen::Vector3d normal = pca.axes.col(0);
    if (normal.dot(around.head<3>()) < 0)
      normal = -normal;
    return Eigen::Vector4d(normal.x(), normal.y(), normal.z(), -normal.dot(pca.mean));
  };
  Eigen::Vector4d band_centre = ground.cast<double>();
  band_centre[3] -= (double(best_bin) + 0.5) * bin_mm;
  const Eigen::Vector4d plane = fit(fit(band_centre, kBinFloorBandMm + bin_mm), bin_mm);
  return plane.cast<float>();
}

/// An evenly strided sample (deterministic and spatially uniform) of at most about `max_points`
/// of `indices` into `points`.
pcl::PointCloud<pcl::PointXYZ>::Ptr stridedSample(const std::vector<Eigen::Vector3f>& points,
                                                  const std::vector<int>& indices,
                                                  std::size_t max_points) {
  const std::size_t stride = std::max<std::size_t>(1, indices.size() / max_points);
  auto sample = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (std::size_t j = 0; j < indices.size(); j += stride) {
    const auto& p = points[static_cast<std::size_t>(indices[j])];
    sample->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  return sample;
}

/// The plane RANSAC finds with `model` (inlier distance `distance_mm`, `trials` iterations),
/// refined by least squares on its inliers when `keep_refined` accepts the refined normal;
/// (a, b, c, d) with a unit normal. None when RANSAC finds nothing.
template <class Model, class KeepRefined>
std::optional<Eigen::Vector4f> ransacPlane(const std::shared_ptr<Model>& model, double distance_mm,
                                           int trials, KeepRefined keep_refined) {
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, distance_mm);
  ransac.setMaxIterations(trials);
  if (!ransac.computeModel())
    return std::nullopt;
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  Eigen::VectorXf coefficients;
  ransac.getModelCoefficients(coefficients);
  if (inliers.size() >= 3) {
    Eigen::VectorXf refined;
    model->optimizeModelCoefficients(inliers, coefficients, refined);
    if (refined.size() == 4 && refined.allFinite() &&
        keep_refined(Eigen::Vector3f(refined.head<3>().normalized())))
      coefficients = refined;
  }
  Eigen::Vector4f plane = coefficients.head<4>();
  return plane / plane.head<3>().norm();
}

/// The plane RANSAC finds among `indices` of `points` (an evenly strided sample of at most
/// kMaxSamplePoints), refined by least squares on its inliers: (a, b, c, d) with a unit normal
/// pointing towards the camera (the origin). None when RANSAC finds nothing.
std::optional<Eigen::Vector4f> fitPlane(const std::vector<Eigen::Vector3f>& points,
                                        const std::vector<int>& indices, double distance_mm,
                                        std::uint64_t seed) {
  if (indices.size() < 3)
    return std::nullopt;
  auto model = std::make_shared<SeededPlaneModel>(stridedSample(points, indices, kMaxSamplePoints));
  model->seed(seed);
  auto plane =
      ransacPlane(model, distance_mm, kPlaneTrials, [](const Eigen::Vector3f&) { return true; });
  if (plane && (*plane)[3] < 0) // the camera (origin) on the positive side
    *plane = -*plane;
  return plane;
}

/// The floor search over one scan: the valid points not removed yet and the planes removed so far.
struct FloorSearch {
  FloorSearch(const PointCloud& scene, const FloorParams& floor_params, std::vector<int> valid)
      : scene_mm(scene), params(floor_params), total_valid(valid.size()), alive(std::move(valid)),
        removed(scene.size(), 0) {}

  const PointCloud& scene_mm;
  const FloorParams& params;
  std::size_t total_valid = 0; ///< valid points of the scan
  /// With a part: its points' centroid and largest distance from it (scan frame, mm).
  Eigen::Vector3f part_centre_mm = Eigen::Vector3f::Zero();
  float part_radius_mm = 0;
  std::vector<int> alive;    ///< valid points not removed yet (indices into scene_mm)
  std::vector<char> removed; ///< per point of scene_mm: 1 when removed
  FloorRemovalResult result;
};

/// Throws Error for a mask that does not match the scan or a plane distance that is not positive.
void checkFloorInputs(const PointCloud& scene_mm, const FloorParams& params,
                      const std::vector<char>& part) {
  if (!part.empty() && part.size() != scene_mm.size())
    throw Error("floor removal: " + std::to_string(part.size()) + " part flags for " +
                std::to_string(scene_mm.size()) + " points");
  if (params.distance_mm <= 0)
    throw Error("floor removal needs a positive plane distance (floor.distance_mm), got " +
                std::to_string(params.distance_mm));
}

/// Removes the remaining points within params.distance_mm of `plane` if there are at least
/// `min_count` of them, recording the plane; returns whether it did.
bool removePlane(FloorSearch& search, const Eigen::Vector4f& plane, std::size_t min_count) {
  const PointCloud& scene_mm = search.scene_mm;
  std::vector<int>& alive = search.alive;
  std::vector<char> on_plane(alive.size(), 0);
  const auto distance = static_cast<float>(search.params.distance_mm);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, alive.size(), 16384),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t j = r.begin(); j < r.end(); ++j) {
                        const auto& p = scene_mm.points_mm[static_cast<std::size_t>(alive[j])];
                        on_plane[j] = std::abs(plane.head<3>().dot(p) + plane[3]) <= distance;
                      }
                    });
  const auto count = static_cast<std::size_t>(std::count(on_plane.begin(), on_plane.end(), 1));
  if (count < std::max<std::size_t>(1, min_count))
    return false;
  std::vector<int> still_alive;
  still_alive.reserve(alive.size() - count);
  for (std::size_t j = 0; j < alive.size(); ++j) {
    if (on_plane[j])
      search.removed[static_cast<std::size_t>(alive[j])] = 1;
    else
      still_alive.push_back(alive[j]);
  }
  alive.swap(still_alive);
  logger()->debug("floor plane {}: ({:.3f}, {:.3f}, {:.3f}) at {:.1f} mm from the camera, {} "
                  "points ({:.1f} % of the scan)",
                  search.result.planes.size(), plane[0], plane[1], plane[2], plane[3], count,
                  100.0 * double(count) / double(search.total_valid));
  search.result.planes.push_back(plane);
  search.result.removed_points += count;
  return true;
}

/// Sets the centre (centroid) and radius (largest distance from it) of the flagged part's valid
/// points in `search`, for hasPointsBehind.
void findPartCentreAndRadius(FloorSearch& search, const std::vector<char>& part) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const int i : search.alive)
    if (part[static_cast<std::size_t>(i)]) {
      sum += search.scene_mm.points_mm[static_cast<std::size_t>(i)].cast<double>();
      ++n;
    }
  if (n == 0)
    return;
  search.part_centre_mm = (sum / double(n)).cast<float>();
  for (const int i : search.alive)
    if (part[static_cast<std::size_t>(i)])
      search.part_radius_mm = std::max(
          search.part_radius_mm,
          (search.scene_mm.points_mm[static_cast<std::size_t>(i)] - search.part_centre_mm).norm());
}

/// Whether more than kMaxShareBehindFloor of the valid points around the part (along `plane`,
/// within kAroundPartRadii of its radius) lie beyond `plane`.
bool hasPointsBehind(const FloorSearch& search, const Eigen::Vector4f& plane) {
  const auto beyond = static_cast<float>(-kBehindDistances * search.params.distance_mm);
  const Eigen::Vector3f normal = plane.head<3>();
  const auto along = [&](const Eigen::Vector3f& p) { return p - normal * normal.dot(p); };
  const Eigen::Vector3f centre = along(search.part_centre_mm);
  const float around_mm = kAroundPartRadii * search.part_radius_mm;
  std::size_t near = 0, behind = 0;
  for (const int i : search.alive) {
    const auto& p = search.scene_mm.points_mm[static_cast<std::size_t>(i)];
    if ((along(p) - centre).norm() > around_mm)
      continue;
    ++near;
    behind += normal.dot(p) + plane[3] < beyond;
  }
  return double(behind) > kMaxShareBehindFloor * double(near);
}

/// Flags in `set_aside` the `candidates` within params.distance_mm of `plane` (a face of a part).
void setAsidePlane(const FloorSearch& search, const std::vector<int>& candidates,
                   const Eigen::Vector4f& plane, std::vector<char>& set_aside) {
  logger()->debug("plane ({:.3f}, {:.3f}, {:.3f}) at {:.1f} mm has points behind it: a "
                  "face of a part, not the floor",
                  plane[0], plane[1], plane[2], plane[3]);
  const auto distance = static_cast<float>(search.params.distance_mm);
  for (const int i : candidates) {
    const auto& p = search.scene_mm.points_mm[static_cast<std::size_t>(i)];
    if (std::abs(plane.head<3>().dot(p) + plane[3]) <= distance)
      set_aside[static_cast<std::size_t>(i)] = 1;
  }
}

/// Removes up to params.max_planes planes of at least `min_points` points, largest first. With
/// `support_only`, planes with points behind them are set aside (at most kFloorRetries times).
void removeFloorPlanes(FloorSearch& search, std::size_t min_points, bool support_only,
                       std::uint64_t seed, const ProgressFn& progress) {
  const FloorParams& params = search.params;
  std::vector<char> set_aside(search.scene_mm.size(), 0);
  const int planes = params.enabled ? params.max_planes : 0;
  for (int plane = 0, retries = 0; plane < planes && search.alive.size() >= 3;) {
    reportProgress(progress, static_cast<double>(plane) / planes);
    std::vector<int> candidates;
    candidates.reserve(search.alive.size());
    for (const int i : search.alive)
      if (!set_aside[static_cast<std::size_t>(i)])
        candidates.push_back(i);
    const std::uint64_t attempt = static_cast<std::uint64_t>(plane + 1 + 1000 * retries);
    const auto found = fitPlane(search.scene_mm.points_mm, candidates, params.distance_mm,
                                seed + 0x9e3779b97f4a7c15ULL * attempt);
    if (!found)
      break;
    if (support_only && hasPointsBehind(search, *found)) {
      if (++retries > kFloorRetries)
        break;
      setAsidePlane(search, candidates, *found, set_aside);
      continue;
    }
    if (!removePlane(search, *found, min_points))
      break; // the largest remaining plane is too small: no more floor or walls
    ++plane;
  }
}

/// Whether more of `plane`'s points lie outside the part than in it: a floor reaches beyond
/// the part resting on it, a face of the part does not.
bool reachesBeyondPart(const FloorSearch& search, const std::vector<char>& part,
                       const Eigen::Vector4f& plane) {
  std::size_t inside = 0, outside = 0;
  for (const int i : search.alive) {
    const auto& p = search.scene_mm.points_mm[static_cast<std::size_t>(i)];
    if (std::abs(plane.head<3>().dot(p) + plane[3]) <= search.params.distance_mm)
      ++(part[static_cast<std::size_t>(i)] ? inside : outside);
  }
  return outside > inside;
}

/// The remaining points within params.distance_mm of `plane` (mm).
std::vector<Eigen::Vector3f> planePoints(const FloorSearch& search, const Eigen::Vector4f& plane) {
  std::vector<Eigen::Vector3f> out;
  for (const int i : search.alive) {
    const auto& p = search.scene_mm.points_mm[static_cast<std::size_t>(i)];
    if (std::abs(plane.head<3>().dot(p) + plane[3]) <= search.params.distance_mm)
      out.push_back(p);
  }
  return out;
}

/// Removes the remaining points for which `gone` holds; returns how many.
template <class Gone> std::size_t removeWhere(FloorSearch& search, Gone gone) {
  const auto from = std::stable_partition(search.alive.begin(), search.alive.end(),
                                          [&](int i) { return !gone(i); });
  for (auto it = from; it != search.alive.end(); ++it)
    search.removed[static_cast<std::size_t>(*it)] = 1;
  const auto removed = static_cast<std::size_t>(search.alive.end() - from);
  search.alive.erase(from, search.alive.end());
  search.result.removed_points += removed;
  return removed;
}

/// The largest plane among `indices` of `points` within kWallAngleDeg of parallel to `up` (see
/// kMaxBinWalls), refined by least squares on its inliers, its unit normal turned towards
/// `inside`; none when RANSAC finds none.
std::optional<Eigen::Vector4f> fitWall(const std::vector<Eigen::Vector3f>& points,
                                       const std::vector<int>& indices, const Eigen::Vector3f& up,
                                       const Eigen::Vector3f& inside, double distance_mm,
                                       std::uint64_t seed) {
  if (indices.size() < 3)
    return std::nullopt;
  const auto sample = stridedSample(points, indices, kMaxWallSamplePoints);
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  tree->setInputCloud(sample);
  auto model = std::make_shared<SeededWallModel>(sample);
  model->seed(seed);
  model->setAxis(up);
  const double angle_rad = kWallAngleDeg * std::numbers::pi / 180.0;
  model->setEpsAngle(angle_rad);
  model->setSamplesMaxDist(kWallSampleDistances * distance_mm, tree);
  auto plane = ransacPlane(model, distance_mm, kWallTrials, [&](const Eigen::Vector3f& normal) {
    return std::abs(normal.dot(up)) < std::sin(angle_rad);
  });
  if (plane && plane->head<3>().dot(inside) + (*plane)[3] < 0)
    *plane = -*plane;
  return plane;
}

/// A bin wall: its plane (unit normal into the bin) and the height of its top above the floor.
struct BinWall {
  Eigen::Vector4f plane;
  float top_mm = 0.0f;
};

/// Removes the walls of the bin whose floor (`bin_floor`, normal up; its points `floor_points`)
/// was just removed, one after the other (fitWall, normals towards the floor's centroid): a wall
/// holds at least `min_points` and has at most kMaxShareBehindBinWall of the points left after
/// the floor beyond kBehindDistances x params.distance_mm behind it, but for those as high as its
/// top (within as much: the rim's top, the wall's thickness); a part's face inside the bin has the
/// bin's far side behind it (its wall, or the rim of a wall that was not seen) and is set aside.
/// Each wall goes with the points within params.distance_mm of it or behind it up to that far above
/// its top (the rim). Returns the walls removed.
std::vector<BinWall> removeBinWalls(FloorSearch& search, const Eigen::Vector4f& bin_floor,
                                    const std::vector<Eigen::Vector3f>& floor_points,
                                    std::size_t min_points, std::uint64_t seed) {
  Eigen::Vector3f inside = Eigen::Vector3f::Zero();
  for (const auto& p : floor_points)
    inside += p / float(floor_points.size());
  const Eigen::Vector3f up = bin_floor.head<3>();
  const auto distance = static_cast<float>(search.params.distance_mm);
  const float behind_mm = static_cast<float>(kBehindDistances) * distance;
  const auto& points = search.scene_mm.points_mm;
  const auto height = [&](int i) {
    return up.dot(points[static_cast<std::size_t>(i)]) + bin_floor[3];
  };
  const std::vector<int> above_floor = search.alive;
  std::vector<BinWall> walls;
  std::vector<char> set_aside(points.size(), 0);
  for (int retries = 0, attempt = 1; walls.size() < kMaxBinWalls; ++attempt) {
    std::vector<int> candidates;
    for (const int i : search.alive)
      if (!set_aside[static_cast<std::size_t>(i)])
        candidates.push_back(i);
    const auto plane = fitWall(points, candidates, up, inside, distance,
                               seed + 0x9e3779b97f4a7c15ULL * std::uint64_t(attempt));
    if (!plane)
      break;
    const auto signedDistance = [&](int i) {
      return plane->head<3>().dot(points[static_cast<std::size_t>(i)]) + (*plane)[3];
    };
    BinWall wall{*plane, -std::numeric_limits<float>::infinity()};
    std::size_t on_wall = 0;
    for (const int i : search.alive)
      if (std::abs(signedDistance(i)) <= distance) {
        wall.top_mm = std::max(wall.top_mm, height(i));
        ++on_wall;
      }
    if (on_wall < std::max<std::size_t>(3, min_points))
      break; // the largest wall left is too small: no more walls
    const auto behind = std::count_if(above_floor.begin(), above_floor.end(), [&](int i) {
      return signedDistance(i) < -behind_mm && std::abs(height(i) - wall.top_mm) > behind_mm;
    });
    if (double(behind) > kMaxShareBehindBinWall * double(above_floor.size())) {
      for (const int i : candidates)
        if (std::abs(signedDistance(i)) <= distance)
          set_aside[static_cast<std::size_t>(i)] = 1;
      if (++retries > kWallRetries)
        break;
      continue;
    }
    const std::size_t removed = removeWhere(search, [&](int i) {
      return signedDistance(i) <= distance && height(i) <= wall.top_mm + behind_mm;
    });
    logger()->debug("bin wall {}: ({:.3f}, {:.3f}, {:.3f}) at {:.1f} mm from the camera, {} points "
                    "on it, {} on or behind it removed",
                    walls.size(), wall.plane[0], wall.plane[1], wall.plane[2], wall.plane[3],
                    on_wall, removed);
    walls.push_back(wall);
  }
  return walls;
}

/// Removes the rim of a wall that was not seen (its face in the projector's shadow), across the
/// bin from each wall in `walls`: the points as high as that wall's top (within kBehindDistances
/// x params.distance_mm) beyond the farthest point of the bin's floor (`floor_points`) from it.
void removeUnseenRims(FloorSearch& search, const Eigen::Vector4f& bin_floor,
                      const std::vector<Eigen::Vector3f>& floor_points,
                      const std::vector<BinWall>& walls) {
  const float behind_mm = static_cast<float>(kBehindDistances * search.params.distance_mm);
  for (const BinWall& wall : walls) {
    const Eigen::Vector3f n = wall.plane.head<3>();
    float floor_end = -std::numeric_limits<float>::infinity();
    for (const auto& p : floor_points)
      floor_end = std::max(floor_end, n.dot(p));
    const std::size_t removed = removeWhere(search, [&](int i) {
      const auto& p = search.scene_mm.points_mm[static_cast<std::size_t>(i)];
      return n.dot(p) > floor_end + float(search.params.distance_mm) &&
             bin_floor.head<3>().dot(p) + bin_floor[3] >= wall.top_mm - behind_mm;
    });
    if (removed > 0)
      logger()->debug("{} points as high as the rim beyond the bin's floor across from bin wall "
                      "({:.3f}, {:.3f}, {:.3f}) removed",
                      removed, n.x(), n.y(), n.z());
  }
}

/// `scene_mm` without the `removed` points: NaN in their place when organized, else dropped.
PointCloud withoutRemoved(const PointCloud& scene_mm, const std::vector<char>& removed) {
  if (scene_mm.isOrganized()) {
    PointCloud remaining = scene_mm;
    for (std::size_t i = 0; i < removed.size(); ++i)
      if (removed[i])
        remaining.points_mm[i] = invalidPoint();
    return remaining;
  }
  PointCloud marked = scene_mm;
  for (std::size_t i = 0; i < removed.size(); ++i)
    if (removed[i])
      marked.points_mm[i] = invalidPoint();
  return dropInvalid(marked);
}

/// Removes the bin floor above the first plane removed, if params.bin_floor_fraction asks for it
/// and one is found (with a `part`, only one that reaches beyond it), and with params.bin_walls,
/// in a scene (no `part`), the bin's walls after it (`remaining_with_walls` keeps them).
void removeBinFloor(FloorSearch& search, const std::vector<char>& part, bool support_only,
                    std::uint64_t seed) {
  const FloorParams& params = search.params;
  if (!(params.bin_floor_fraction > 0 && !search.result.planes.empty()))
    return;
  const auto min_bin_floor_points =
      static_cast<std::size_t>(std::ceil(params.bin_floor_fraction * double(search.total_valid)));
  const auto bin_floor =
      findBinFloor(search.scene_mm.points_mm, search.alive, search.result.planes.front(),
                   params.distance_mm, min_bin_floor_points);
  if (!bin_floor || (support_only && !reachesBeyondPart(search, part, *bin_floor)))
    return;
  const std::vector<Eigen::Vector3f> floor_points = planePoints(search, *bin_floor);
  if (!removePlane(search, *bin_floor, min_bin_floor_points))
    return;
  search.result.resting_plane = search.result.planes.back();
  if (support_only || !params.bin_walls)
    return;
  std::vector<char> removed_before_walls = search.removed;
  const std::vector<BinWall> walls =
      removeBinWalls(search, *bin_floor, floor_points, min_bin_floor_points / 4, seed);
  removeUnseenRims(search, *bin_floor, floor_points, walls);
  if (search.removed != removed_before_walls)
    search.result.remaining_with_walls = withoutRemoved(search.scene_mm, removed_before_walls);
}

} // namespace

FloorRemovalResult removeFloor(const PointCloud& scene_mm, const FloorParams& params,
                               std::uint64_t seed, const ProgressFn& progress,
                               const std::vector<char>& part) {
  scene_mm.validate();
  checkFloorInputs(scene_mm, params, part);
  const bool support_only = !part.empty();
  std::vector<int> alive;
  alive.reserve(scene_mm.size());
  for (std::size_t i = 0; i < scene_mm.size(); ++i)
    if (isValid(scene_mm.points_mm[i]))
      alive.push_back(static_cast<int>(i));
  FloorSearch search(scene_mm, params, std::move(alive));
  if (support_only)
    findPartCentreAndRadius(search, part);

  const auto min_points =
      static_cast<std::size_t>(std::ceil(params.min_plane_fraction * double(search.total_valid)));
  removeFloorPlanes(search, min_points, support_only, seed, progress);
  removeBinFloor(search, part, support_only, seed);
  if (!search.result.resting_plane && !search.result.planes.empty())
    search.result.resting_plane = search.result.planes.front();
  search.result.remaining = withoutRemoved(scene_mm, search.removed);
  reportProgress(progress, 1.0);
  return std::move(search.result);
}

} // namespace scanpick::core
