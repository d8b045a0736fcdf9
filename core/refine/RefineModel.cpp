#include "core/refine/RefineModel.h"

#include "core/common/Error.h"
#include "core/refine/SceneIndex.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_set>

namespace scanpick::core {

namespace {

using VoxelKey = std::array<std::int64_t, 3>;

VoxelKey voxelOf(const Eigen::Vector3f& p, const Eigen::Vector3f& origin, double voxel_mm) {
  const Eigen::Vector3d q = (p - origin).cast<double>() / voxel_mm;
  return {static_cast<std::int64_t>(std::floor(q.x())),
          static_cast<std::int64_t>(std::floor(q.y())),
          static_cast<std::int64_t>(std::floor(q.z()))};
}

/// (voxel, point index) pairs sorted by voxel then index: deterministic whatever the input order.
std::vector<std::pair<VoxelKey, std::uint32_t>>
sortedVoxels(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& origin,
             double voxel_mm) {
  std::vector<std::pair<VoxelKey, std::uint32_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    keyed[i] = {voxelOf(points[i], origin, voxel_mm), static_cast<std::uint32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  return keyed;
}

struct VoxelHash {
  std::size_t operator()(const VoxelKey& k) const {
    return std::hash<std::int64_t>()(k[0] * 73856093 ^ k[1] * 19349663 ^ k[2] * 83492791);
  }
};

/// How many voxels of edge `voxel_mm` the points occupy (hashed: the bisection asks 30 times).
std::size_t occupiedVoxels(const std::vector<Eigen::Vector3f>& points,
                           const Eigen::Vector3f& origin, double voxel_mm) {
  std::unordered_set<VoxelKey, VoxelHash> occupied;
  occupied.reserve(points.size());
  for (const auto& p : points)
    occupied.insert(voxelOf(p, origin, voxel_mm));
  return occupied.size();
}

void requireModelPoints(int max_points) {
  if (max_points < 3)
    throw Error("The refinement needs at least 3 model points (refine.model_points is " +
                std::to_string(max_points) + ").");
}

std::shared_ptr<const SceneIndex>
indexModel(const PointCloud& model_mm, int max_points,
           const std::optional<Eigen::Vector3d>& viewpoint_model_mm) {
  requireModelPoints(max_points);
  if (!model_mm.hasValidPoint())
    throw Error("The model cloud to refine has no valid point (empty or all NaN): teach the model "
                "again from a crop that holds the part.");
  SceneIndexOptions options;
  options.normal_radius_mm = RefineModel::kNormalRadiusMm;
  if (viewpoint_model_mm) {
    options.viewpoint_mm = *viewpoint_model_mm;
  } else {
    // A camera far along -z: the model frame has the teach camera's axes, so its points were
    // seen looking along +z.
    const auto box = boundingBox(model_mm);
    options.viewpoint_mm = box.center().cast<double>() - Eigen::Vector3d(0, 0, 1e6);
  }
  return std::make_shared<const SceneIndex>(model_mm, options);
}
} // namespace

RefineModel::RefineModel(const PointCloud& model_mm, int max_points,
                         const std::optional<Eigen::Vector3d>& viewpoint_model_mm)
    : RefineModel(indexModel(model_mm, max_points, viewpoint_model_mm), max_points) {}

RefineModel::RefineModel(std::shared_ptr<const SceneIndex> surface, int max_points)
    : m_surface(std::move(surface)) {
  requireModelPoints(max_points);
  if (!m_surface)
    throw Error("RefineModel needs the model's indexed surface");
  const SceneIndex& full = *m_surface;

  std::vector<Eigen::Vector3f> points, normals;
  for (std::size_t i = 0; i < full.size(); ++i)
    if (full.normals()[i].allFinite()) {
      points.push_back(full.points()[i]);
      normals.push_back(full.normals()[i]);
    }
  if (points.size() < 3)
    throw Error("Only " + std::to_string(points.size()) +
                " model points have a surface normal: "
                "the model is too sparse for refinement (teach from a denser scan).");

  if (points.size() <= static_cast<std::size_t>(max_points)) {
    m_points = std::move(points);
    m_normals = std::move(normals);
  } else {
    // The finest voxel edge that leaves no more than max_points cells, by bisection in log space.
    Eigen::AlignedBox3f box;
    for (const auto& p : points)
      box.extend(p);
    const Eigen::Vector3f origin = box.min();
    double lo = 1e-4, hi = std::max(1e-3, static_cast<double>(box.diagonal().norm()) * 2.0);
    for (int step = 0; step < 30; ++step) {
      const double mid = std::sqrt(lo * hi);
      if (occupiedVoxels(points, origin, mid) <= static_cast<std::size_t>(max_points))
        hi = mid;
      else
        lo = mid;
    }
    m_voxel_mm = hi;
    const auto keyed = sortedVoxels(points, origin, hi);
    // One point per cell, the one nearest the cell centre (ties: lowest index, first in order).
    for (std::size_t begin = 0; begin < keyed.size();) {
      std::size_t end = begin;
      while (end < keyed.size() && keyed[end].first == keyed[begin].first)
        ++end;
      const auto& key = keyed[begin].first;
      const Eigen::Vector3d centre =
          origin.cast<double>() + hi * Eigen::Vector3d(static_cast<double>(key[0]) + 0.5,
                                                       static_cast<double>(key[1]) + 0.5,
                                                       static_cast<double>(key[2]) + 0.5);
      std::uint32_t best = keyed[begin].second;
      double best_d = (points[best].cast<double>() - centre).squaredNorm();
      for (std::size_t j = begin + 1; j < end; ++j) {
        const double d = (points[keyed[j].second].cast<double>() - centre).squaredNorm();
        if (d < best_d)
          best = keyed[j].second, best_d = d;
      }
      m_points.push_back(points[best]);
      m_normals.push_back(normals[best]);
      begin = end;
    }
  }

  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : m_points)
    centroid += p.cast<double>();
  centroid /= static_cast<double>(m_points.size());
  for (const auto& p : m_points)
    m_radius_mm = std::max(m_radius_mm, (p.cast<double>() - centroid).norm());
}

} // namespace scanpick::core
