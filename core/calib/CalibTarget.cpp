#include "core/calib/CalibTarget.h"

#include "core/common/Error.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace scanpick::core::calib {
namespace {

std::string mm(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f mm", value);
  return buffer;
}

} // namespace

TargetLayout defaultTarget() {
  TargetLayout t;
  t.sphere_centres_mm = {{-70, -55, 7.5}, {70, -45, 7.5}, {60, 45, 7.5}, {-45, 60, 7.5}};
  return t;
}

double smallestDistanceGap_mm(const TargetLayout& layout) {
  const auto& s = layout.sphere_centres_mm;
  std::vector<double> distances;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      distances.push_back((s[i] - s[j]).norm());
  if (distances.size() < 3)
    return std::numeric_limits<double>::infinity();
  std::sort(distances.begin(), distances.end());
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < distances.size(); ++i)
    gap = std::min(gap, distances[i] - distances[i - 1]);
  return gap;
}

void validateTarget(const TargetLayout& layout, double min_gap_mm) {
  const auto& s = layout.sphere_centres_mm;
  if (s.size() < 3)
    throw Error(
        std::string("the calibration target has ")
            .append(std::to_string(s.size()))
            .append(" spheres: it needs at least 3 (give their centres in the target file's "
                    "\"spheres_mm\")"));
  if (!(layout.sphere_radius_mm > 0) || !std::isfinite(layout.sphere_radius_mm))
    throw Error("the calibration target's sphere radius must be a positive number of mm "
                "(\"sphere_radius_mm\" in the target file)");
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s[i].allFinite())
      throw Error("the calibration target's sphere centres must be finite numbers (mm)");
    for (std::size_t j = i + 1; j < s.size(); ++j)
      if ((s[i] - s[j]).norm() < 2 * layout.sphere_radius_mm)
        throw Error(std::string("spheres ")
                        .append(std::to_string(i + 1))
                        .append(" and ")
                        .append(std::to_string(j + 1))
                        .append(" of the calibration target overlap: their centres must lie at "
                                "least two radii apart"));
  }
  // Collinear centres leave the turn about their line open.
  double widest = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j)
      for (std::size_t k = j + 1; k < s.size(); ++k) {
        const Eigen::Vector3d a = s[j] - s[i], b = s[k] - s[i];
        widest = std::max(widest, a.cross(b).norm() / std::max(a.norm(), b.norm()));
      }
  if (widest < layout.sphere_radius_mm)
    throw Error("the calibration target's spheres lie (nearly) on one line: place at least one "
                "sphere away from the line through the others");
  const double gap = smallestDistanceGap_mm(layout);
  if (gap < min_gap_mm)
    throw Error(
        std::string("two distances between the calibration target's spheres differ by only ")
            .append(mm(gap))
            .append(": the spheres could be matched the wrong way round; move them so that "
                    "all distances between two spheres differ by at least ")
            .append(mm(min_gap_mm)));
}

} // namespace scanpick::core::calib
