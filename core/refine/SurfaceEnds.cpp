#include "core/refine/SurfaceEnds.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace scanpick::core {
namespace {

/// Mean of the values within `window` of their median, if at least `min_count` are.
std::optional<double> agreeingMean(std::vector<double> values, double window, int min_count) {
  if (values.empty())
    return std::nullopt;
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  const double median = *middle;
  double sum = 0;
  int count = 0;
  for (const double v : values)
    if (std::abs(v - median) <= window) {
      sum += v;
      ++count;
    }
  if (count < min_count)
    return std::nullopt;
  return sum / count;
}

} // namespace

double outerRadius(const std::vector<Eigen::Vector3f>& points_mm,
                   const Eigen::Vector3d& axis_point_mm, const Eigen::Vector3d& axis_direction) {
  std::vector<double> radii;
  radii.reserve(points_mm.size());
  for (const auto& p : points_mm) {
    const Eigen::Vector3d d = p.cast<double>() - axis_point_mm;
    if (d.allFinite())
      radii.push_back((d - d.dot(axis_direction) * axis_direction).norm());
  }
  if (radii.empty())
    return 0.0;
  const auto at = radii.begin() + static_cast<std::ptrdiff_t>(0.99 * double(radii.size() - 1));
  std::nth_element(radii.begin(), at, radii.end());
  return *at;
}

AxialEnds findAxialEnds(const std::vector<Eigen::Vector3f>& points_mm,
                        const Eigen::Vector3d& axis_point_mm, const Eigen::Vector3d& axis_direction,
                        double radius_mm, const Eigen::Vector3d& viewpoint_mm, double min_height_mm,
                        double max_height_mm, const AxialEndsOptions& options,
                        const std::vector<Eigen::Vector3f>& normals) {
  const Eigen::Vector3d sight = (axis_point_mm - viewpoint_mm).normalized();
  if (!(std::abs(sight.dot(axis_direction)) <= options.max_sight_cos) || !(radius_mm > 0))
    return {};
  const Eigen::Vector3d u = axis_direction.unitOrthogonal();
  const Eigen::Vector3d v = axis_direction.cross(u);
  const int bins = std::max(1, static_cast<int>(std::lround(360.0 / options.bin_deg)));
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> lowest(bins, kNone), highest(bins, kNone);
  const double r_min = radius_mm - options.band_inside_mm;
  const double r_max = radius_mm + options.band_outside_mm;
  const bool with_normals = normals.size() == points_mm.size();
  for (std::size_t i = 0; i < points_mm.size(); ++i) {
    const Eigen::Vector3d d = points_mm[i].cast<double>() - axis_point_mm;
    const double h = d.dot(axis_direction);
    if (!(h >= min_height_mm && h <= max_height_mm))
      continue;
    const double x = d.dot(u), y = d.dot(v);
    const double r = std::hypot(x, y);
    if (r < r_min || r > r_max)
      continue;
    if (with_normals) {
      const Eigen::Vector3d n = normals[i].cast<double>();
      if (!((n.dot(u) * x + n.dot(v) * y) / r >= options.min_radial_normal))
        continue;
    }
    const double turn = std::atan2(y, x) + std::numbers::pi; // [0, 2π]
    const int bin = std::min(bins - 1, static_cast<int>(turn / (2 * std::numbers::pi) * bins));
    if (!(lowest[bin] <= h)) // also when unset (NaN)
      lowest[bin] = h;
    if (!(highest[bin] >= h))
      highest[bin] = h;
  }
  const auto seen = [](const std::vector<double>& per_bin) {
    std::vector<double> out;
    for (const double h : per_bin)
      if (!std::isnan(h))
        out.push_back(h);
    return out;
  };
  return {agreeingMean(seen(lowest), options.agreement_mm, options.min_bins),
          agreeingMean(seen(highest), options.agreement_mm, options.min_bins)};
}

std::optional<double> axialShift(const AxialEnds& view, const AxialEnds& scene, double max_shift_mm,
                                 double max_disagreement_mm) {
  // The difference at one end, when both see it and it is near enough to count.
  const auto difference = [&](const std::optional<double>& in_view,
                              const std::optional<double>& in_scene) -> std::optional<double> {
    if (!in_view || !in_scene || !(std::abs(*in_scene - *in_view) <= max_shift_mm))
      return std::nullopt;
    return *in_scene - *in_view;
  };
  const std::optional<double> low = difference(view.low_mm, scene.low_mm);
  const std::optional<double> high = difference(view.high_mm, scene.high_mm);
  if (low && high)
    return std::abs(*low - *high) <= max_disagreement_mm ? std::optional(0.5 * (*low + *high))
                                                         : std::nullopt;
  return low ? low : high;
}

std::optional<double>
outlineShift(const std::vector<Eigen::Vector3f>& view_mm,
             const std::vector<Eigen::Vector3f>& scene_mm, const Eigen::Vector3d& direction,
             const std::vector<const std::vector<Eigen::Vector3f>*>& other_views_mm,
             const OutlineShiftOptions& options) {
  const Eigen::Vector3d u = direction.unitOrthogonal();
  const Eigen::Vector3d v = direction.cross(u);
  struct Extent {
    double low = std::numeric_limits<double>::infinity();
    double high = -std::numeric_limits<double>::infinity();
  };
  // Each point's cell across the direction and its height along it.
  const auto extents = [&](const std::vector<const std::vector<Eigen::Vector3f>*>& clouds) {
    std::unordered_map<std::int64_t, Extent> cells;
    for (const auto* points : clouds)
      for (const auto& p : *points) {
        const Eigen::Vector3d q = p.cast<double>();
        if (!q.allFinite())
          continue;
        const auto cu = static_cast<std::int64_t>(std::floor(q.dot(u) / options.cell_mm));
        const auto cv = static_cast<std::int64_t>(std::floor(q.dot(v) / options.cell_mm));
        Extent& e = cells[(cu << 32) ^ (cv & 0xffffffff)];
        const double h = q.dot(direction);
        e.low = std::min(e.low, h);
        e.high = std::max(e.high, h);
      }
    return cells;
  };
  const auto in_view = extents({&view_mm});
  const auto in_scene = extents({&scene_mm});
  const auto in_others = extents(other_views_mm);
  std::vector<double> low, high;
  for (const auto& [cell, scene] : in_scene) {
    const auto view = in_view.find(cell);
    if (view == in_view.end())
      continue;
    const auto others = in_others.find(cell);
    const bool checked = others != in_others.end();
    if (!checked || others->second.low >= view->second.low - options.confirm_mm)
      low.push_back(scene.low - view->second.low);
    if (!checked || others->second.high <= view->second.high + options.confirm_mm)
      high.push_back(scene.high - view->second.high);
  }
  // Sorted, so that the order of the map's cells does not change the sums.
  std::sort(low.begin(), low.end());
  std::sort(high.begin(), high.end());
  const std::optional<double> low_shift =
      agreeingMean(low, options.agreement_mm, options.min_cells);
  const std::optional<double> high_shift =
      agreeingMean(high, options.agreement_mm, options.min_cells);
  if (!low_shift || !high_shift || !(std::abs(*low_shift) <= options.max_shift_mm) ||
      !(std::abs(*high_shift) <= options.max_shift_mm) ||
      !(std::abs(*low_shift - *high_shift) <= options.max_disagreement_mm))
    return std::nullopt;
  return 0.5 * (*low_shift + *high_shift);
}

} // namespace scanpick::core
