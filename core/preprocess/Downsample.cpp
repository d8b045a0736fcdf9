#include "core/preprocess/Downsample.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace scanpick::core {

PointCloud voxelDownsample(const PointCloud& cloud_mm, double voxel_mm) {
  cloud_mm.validate();
  if (voxel_mm <= 0)
    return cloud_mm;
  const Eigen::AlignedBox3f box = boundingBox(cloud_mm);
  if (box.isEmpty())
    return PointCloud::fromPoints({});
  const Eigen::Vector3d extent = (box.max() - box.min()).cast<double>() / voxel_mm;
  if (extent.maxCoeff() >= 2097151.0) // 21 bits per axis in the voxel key
    throw Error("voxel size " + std::to_string(voxel_mm) +
                " mm is too small for a cloud this large: increase downsample.voxel_mm");

  // Sorting (key, index) pairs groups each voxel's points in input order: deterministic.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(cloud_mm.size());
  for (std::size_t i = 0; i < cloud_mm.size(); ++i) {
    const auto& p = cloud_mm.points_mm[i];
    if (!isValid(p))
      continue;
    const Eigen::Vector3d v = (p - box.min()).cast<double>() / voxel_mm;
    const auto ix = static_cast<std::uint64_t>(v.x()), iy = static_cast<std::uint64_t>(v.y()),
               iz = static_cast<std::uint64_t>(v.z());
    keyed.emplace_back((ix << 42) | (iy << 21) | iz, static_cast<std::uint32_t>(i));
  }
  std::sort(keyed.begin(), keyed.end());

  PointCloud out;
  const bool normals = !cloud_mm.normals.empty(), colors = !cloud_mm.colors.empty();
  for (std::size_t begin = 0; begin < keyed.size();) {
    std::size_t end = begin;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
    Eigen::Vector3d rgb = Eigen::Vector3d::Zero();
    while (end < keyed.size() && keyed[end].first == keyed[begin].first) {
      const std::size_t i = keyed[end].second;
      sum += cloud_mm.points_mm[i].cast<double>();
      if (normals && cloud_mm.normals[i].allFinite())
        normal += cloud_mm.normals[i].cast<double>();
      if (colors)
        rgb += Eigen::Vector3d(cloud_mm.colors[i][0], cloud_mm.colors[i][1], cloud_mm.colors[i][2]);
      ++end;
    }
    const double n = static_cast<double>(end - begin);
    out.points_mm.push_back((sum / n).cast<float>());
    if (normals)
      out.normals.push_back(normal.norm() > 0
                                ? Eigen::Vector3f((normal / normal.norm()).cast<float>())
                                : Eigen::Vector3f(invalidPoint()));
    if (colors) {
      const Eigen::Vector3d c = rgb / n;
      out.colors.push_back({static_cast<std::uint8_t>(std::lround(c.x())),
                            static_cast<std::uint8_t>(std::lround(c.y())),
                            static_cast<std::uint8_t>(std::lround(c.z()))});
    }
    begin = end;
  }
  out.width = static_cast<std::uint32_t>(out.points_mm.size());
  out.height = 1;
  return out;
}

} // namespace scanpick::core
