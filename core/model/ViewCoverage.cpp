#include "core/model/ViewCoverage.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanpick::core {
namespace {

/// `count` directions spread evenly over the unit sphere (a Fibonacci lattice).
std::vector<Eigen::Vector3d> sphereDirections(int count) {
  std::vector<Eigen::Vector3d> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - z * z);
    out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

/// From the part's model origin towards the teach camera (the teach scan's origin), model frame.
Eigen::Vector3d towardsCamera_model(const TaughtModel& view) {
  const Eigen::Vector3d camera_model = view.T_teach_model.inverse().translation();
  return camera_model.norm() > 0 ? camera_model.normalized() : Eigen::Vector3d::UnitZ();
}

} // namespace

ViewCoverage viewCoverage(const std::vector<std::shared_ptr<const TaughtModel>>& views,
                          const ViewCoverageOptions& options) {
  if (views.empty())
    throw Error("no view to measure the coverage of: teach the part first");
  if (!(options.tolerance_deg > 0 && options.tolerance_deg < 180) || options.directions < 10 ||
      options.suggestions < 0)
    throw Error("view coverage: the tolerance must lie in (0, 180) degrees and at least 10 "
                "directions be sampled");
  ViewCoverage out;
  for (const auto& view : views) {
    if (view->T_part_model)
      out.view_directions_part.push_back(view->T_part_model->linear() * towardsCamera_model(*view));
    else
      ++out.unplaced;
  }
  if (out.view_directions_part.empty()) {
    out.view_directions_part.push_back(towardsCamera_model(*views.front()));
    out.unplaced = views.size() - 1;
  }

  const double reach = std::cos(options.tolerance_deg * std::numbers::pi / 180.0);
  const std::vector<Eigen::Vector3d> sphere = sphereDirections(options.directions);
  // Cosine of the angle from each direction to the nearest view (or suggestion so far).
  std::vector<double> nearest(sphere.size(), -1.0);
  const auto cover = [&](const Eigen::Vector3d& from) {
    for (std::size_t i = 0; i < sphere.size(); ++i)
      nearest[i] = std::max(nearest[i], sphere[i].dot(from));
  };
  for (const auto& d : out.view_directions_part)
    cover(d);
  // A part seen from every side is seen from any direction.
  if (std::any_of(views.begin(), views.end(), [](const auto& view) { return view->all_around; }))
    std::fill(nearest.begin(), nearest.end(), 1.0);
  const auto covered = [&] {
    return std::count_if(nearest.begin(), nearest.end(), [&](double c) { return c >= reach; });
  };
  out.covered = double(covered()) / double(sphere.size());
  while (int(out.missing_part.size()) < options.suggestions &&
         covered() < std::ptrdiff_t(sphere.size())) {
    const auto farthest = std::min_element(nearest.begin(), nearest.end()) - nearest.begin();
    out.missing_part.push_back(sphere[std::size_t(farthest)]);
    cover(out.missing_part.back());
  }
  return out;
}

} // namespace scanpick::core
