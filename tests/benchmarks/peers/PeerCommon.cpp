#include "PeerCommon.h"

#include "core/common/Error.h"
#include "core/model/ModelFile.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/refine/RefineModel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <pcl/features/normal_3d_omp.h>

namespace scanpick::peers {
namespace {

/// Points this close to the bin's walls or floor (mm) are left out with them.
constexpr double kBinMarginMm = 5.0;

/// Median distance from every n-th point to its nearest neighbour (mm).
double medianSpacing(const core::PointCloud& cloud) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr points(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : cloud.points_mm)
    if (core::isValid(p))
      points->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  if (points->size() < 2)
    return 0.0;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(points);
  const std::size_t stride = std::max<std::size_t>(1, points->size() / 2000);
  std::vector<double> d;
  std::vector<int> index(2);
  std::vector<float> sq(2);
  for (std::size_t i = 0; i < points->size(); i += stride)
    if (tree.nearestKSearch((*points)[i], 2, index, sq) == 2)
      d.push_back(std::sqrt(double(sq[1])));
  std::nth_element(d.begin(), d.begin() + long(d.size() / 2), d.end());
  return d[d.size() / 2];
}

} // namespace

std::vector<PeerModel> loadPeerModels(const std::vector<std::string>& paths,
                                      std::vector<core::TaughtModel>& storage,
                                      PeerSettings& settings) {
  storage.clear();
  storage.reserve(paths.size());
  for (const auto& path : paths)
    storage.push_back(core::loadModel(path));
  settings = {};
  settings.spacing_mm = medianSpacing(storage.front().cloud_mm);
  std::vector<PeerModel> models;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    PeerModel m;
    m.path = paths[i];
    m.taught = &storage[i];
    // The normals scanpick's own refinement gives the taught crop (RefineModel: PCA of the
    // neighbours, turned towards the teach camera), on every valid point.
    const core::TaughtModel& taught = storage[i];
    const core::RefineModel with_normals(taught.cloud_mm, int(taught.cloud_mm.size()) + 1,
                                         taught.T_teach_model.inverse().translation());
    m.cloud_mm = core::PointCloud::fromPoints(with_normals.points());
    m.cloud_mm.normals = with_normals.normals();
    m.diameter_mm = double(core::boundingBox(m.cloud_mm).diagonal().norm());
    settings.diameter_mm = std::max(settings.diameter_mm, m.diameter_mm);
    models.push_back(std::move(m));
  }
  settings.voxel_mm = std::max(settings.spacing_mm, 0.01 * settings.diameter_mm);
  for (auto& m : models)
    m.sampled_mm = core::voxelDownsample(m.cloud_mm, settings.voxel_mm);
  return models;
}

PeerScene prepareScene(const core::PointCloud& scene_mm, const core::TaughtModel& first,
                       const PeerSettings& settings) {
  const core::FloorRemovalResult floor =
      core::removeFloor(scene_mm, first.params.floor, first.params.seed);
  core::PointCloud remaining = core::dropInvalid(floor.remaining);
  // A region of interest, as users of these libraries set one: the inside of the bin, whose
  // walls would otherwise confirm flat faces of a model. It is the smallest rectangle around the
  // bin's floor (the second plane removeFloor took, found in the scan, no ground truth), less
  // kBinMarginMm; without such a plane the scene stays whole.
  if (floor.planes.size() >= 2 && scene_mm.size() == floor.remaining.size()) {
    const Eigen::Vector4f plane = floor.planes[1];
    const Eigen::Vector3f normal = plane.head<3>();
    std::vector<Eigen::Vector3f> on_floor;
    for (std::size_t i = 0; i < scene_mm.size(); ++i)
      if (core::isValid(scene_mm.points_mm[i]) && !core::isValid(floor.remaining.points_mm[i]) &&
          std::abs(normal.dot(scene_mm.points_mm[i]) + plane[3]) <= first.params.floor.distance_mm)
        on_floor.push_back(scene_mm.points_mm[i]);
    if (on_floor.size() >= 100) {
      Eigen::Vector3f centre = Eigen::Vector3f::Zero();
      for (const auto& p : on_floor)
        centre += p;
      centre /= float(on_floor.size());
      // The rectangle's sides: the turn (1 degree steps) of two axes in the plane that gives the
      // smallest box around the floor points.
      const Eigen::Vector3f a = normal.unitOrthogonal(), b = normal.cross(a);
      const std::size_t stride = std::max<std::size_t>(1, on_floor.size() / 4000);
      Eigen::Vector3f u = a, v = b;
      Eigen::Vector2f low = Eigen::Vector2f::Zero(), high = Eigen::Vector2f::Zero();
      float best_area = std::numeric_limits<float>::max();
      for (int degree = 0; degree < 90; ++degree) {
        const float angle = float(degree) * 3.14159265f / 180.0f;
        const Eigen::Vector3f cu = std::cos(angle) * a + std::sin(angle) * b, cv = normal.cross(cu);
        Eigen::Vector2f lo = Eigen::Vector2f::Constant(1e9f), hi = -lo;
        for (std::size_t i = 0; i < on_floor.size(); i += stride) {
          const Eigen::Vector2f q(cu.dot(on_floor[i] - centre), cv.dot(on_floor[i] - centre));
          lo = lo.cwiseMin(q);
          hi = hi.cwiseMax(q);
        }
        const float area = (hi - lo).prod();
        if (area < best_area) {
          best_area = area;
          u = cu;
          v = cv;
          low = lo;
          high = hi;
        }
      }
      low.array() += float(kBinMarginMm);
      high.array() -= float(kBinMarginMm);
      remaining = core::selectPoints(remaining, [&](std::size_t i) {
        const Eigen::Vector3f d = remaining.points_mm[i] - centre;
        const Eigen::Vector2f q(u.dot(d), v.dot(d));
        return (q.array() >= low.array()).all() && (q.array() <= high.array()).all();
      });
    }
  }
  const core::PointCloud sampled = core::voxelDownsample(remaining, settings.voxel_mm);
  PeerScene scene;
  scene.points.reset(new pcl::PointCloud<pcl::PointXYZ>);
  scene.points->reserve(sampled.size());
  for (const auto& p : sampled.points_mm)
    scene.points->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  scene.normals.reset(new pcl::PointCloud<pcl::Normal>);
  if (scene.points->empty())
    return scene;
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> estimation(2);
  estimation.setInputCloud(scene.points);
  estimation.setRadiusSearch(3.0 * settings.voxel_mm);
  estimation.setViewPoint(0.0f, 0.0f, 0.0f);
  estimation.compute(*scene.normals);
  scene.tree.setInputCloud(scene.points);
  return scene;
}

std::vector<PeerDetection> scoreAndSuppress(const std::vector<Hypothesis>& hypotheses,
                                            const std::vector<PeerModel>& models,
                                            const PeerScene& scene, const PeerSettings& settings,
                                            double min_score) {
  struct Scored {
    PeerDetection detection;
    std::vector<int> confirmed; ///< scene point indices, sorted
  };
  std::vector<Scored> scored;
  if (scene.points->empty())
    return {};
  const float tolerance_sq = float(settings.voxel_mm * settings.voxel_mm);
  std::vector<int> index(1);
  std::vector<float> sq(1);
  for (const auto& h : hypotheses) {
    const core::PointCloud& sampled = models[h.view].sampled_mm;
    const Eigen::Isometry3f T = h.T_scene_model.cast<float>();
    std::size_t facing = 0;
    Scored s;
    for (std::size_t i = 0; i < sampled.size(); ++i) {
      const Eigen::Vector3f p = T * sampled.points_mm[i];
      const Eigen::Vector3f n = T.linear() * sampled.normals[i];
      // The camera sits at the scene frame's origin: a point whose normal turns away from it is
      // not expected in the scan.
      if (n.dot(-p) <= 0.0f)
        continue;
      ++facing;
      if (scene.tree.nearestKSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), 1, index, sq) == 1 &&
          sq[0] <= tolerance_sq)
        s.confirmed.push_back(index[0]);
    }
    if (facing == 0)
      continue;
    s.detection.hypothesis = h;
    s.detection.score = double(s.confirmed.size()) / double(facing);
    if (s.detection.score < min_score)
      continue;
    std::sort(s.confirmed.begin(), s.confirmed.end());
    s.confirmed.erase(std::unique(s.confirmed.begin(), s.confirmed.end()), s.confirmed.end());
    scored.push_back(std::move(s));
  }
  std::stable_sort(scored.begin(), scored.end(), [](const Scored& a, const Scored& b) {
    return a.detection.score > b.detection.score;
  });
  std::vector<PeerDetection> kept;
  std::vector<const Scored*> kept_scored;
  for (const auto& s : scored) {
    bool duplicate = false;
    for (const Scored* k : kept_scored) {
      std::vector<int> common;
      std::set_intersection(s.confirmed.begin(), s.confirmed.end(), k->confirmed.begin(),
                            k->confirmed.end(), std::back_inserter(common));
      if (2 * common.size() > s.confirmed.size()) {
        duplicate = true;
        break;
      }
    }
    if (duplicate)
      continue;
    kept.push_back(s.detection);
    kept_scored.push_back(&s);
  }
  return kept;
}

} // namespace scanpick::peers
