#include "core/cloud/PointCloud.h"

#include "core/common/Error.h"

#include <algorithm>

namespace scanpick::core {

std::size_t PointCloud::validCount() const {
  return static_cast<std::size_t>(
      std::count_if(points_mm.begin(), points_mm.end(), [](const auto& p) { return isValid(p); }));
}

bool PointCloud::hasValidPoint() const {
  return std::any_of(points_mm.begin(), points_mm.end(), [](const auto& p) { return isValid(p); });
}

PointCloud PointCloud::fromPoints(std::vector<Eigen::Vector3f> points) {
  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(points.size());
  cloud.height = 1;
  cloud.points_mm = std::move(points);
  return cloud;
}

void PointCloud::validate() const {
  if (static_cast<std::size_t>(width) * height != points_mm.size())
    throw Error("point cloud is inconsistent: width x height = " + std::to_string(width) + " x " +
                std::to_string(height) + " but it holds " + std::to_string(points_mm.size()) +
                " points");
  const auto check = [&](std::size_t n, const char* name) {
    if (n != 0 && n != points_mm.size())
      throw Error(std::string("point cloud is inconsistent: ") + name + " has " +
                  std::to_string(n) + " entries for " + std::to_string(points_mm.size()) +
                  " points");
  };
  check(normals.size(), "normals");
  check(colors.size(), "colors");
  check(intensity.size(), "intensity");
  check(confidence.size(), "confidence");
}

Eigen::AlignedBox3f boundingBox(const PointCloud& cloud) {
  Eigen::AlignedBox3f box;
  for (const auto& p : cloud.points_mm)
    if (isValid(p))
      box.extend(p);
  return box;
}

PointCloud selectPoints(const PointCloud& cloud, const std::function<bool(std::size_t)>& keep) {
  PointCloud out;
  for (std::size_t i = 0; i < cloud.points_mm.size(); ++i) {
    if (!keep(i))
      continue;
    out.points_mm.push_back(cloud.points_mm[i]);
    if (!cloud.normals.empty())
      out.normals.push_back(cloud.normals[i]);
    if (!cloud.colors.empty())
      out.colors.push_back(cloud.colors[i]);
    if (!cloud.intensity.empty())
      out.intensity.push_back(cloud.intensity[i]);
    if (!cloud.confidence.empty())
      out.confidence.push_back(cloud.confidence[i]);
  }
  out.width = static_cast<std::uint32_t>(out.points_mm.size());
  out.height = 1;
  return out;
}

PointCloud dropInvalid(const PointCloud& cloud) {
  return selectPoints(cloud, [&](std::size_t i) { return isValid(cloud.points_mm[i]); });
}

PointCloud transformed(const PointCloud& cloud, const Eigen::Isometry3f& T) {
  PointCloud out = cloud;
  for (auto& p : out.points_mm)
    if (isValid(p))
      p = T * p;
  for (auto& n : out.normals)
    if (n.allFinite())
      n = T.linear() * n;
  return out;
}

} // namespace scanpick::core
