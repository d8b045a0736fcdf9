#include "core/calib/TargetDetection.h"

#include "core/common/Error.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>

namespace scanpick::core::calib {
namespace {

/// At most this many fitted spheres (the largest) take part in matching: the search tries every
/// assignment, and a scan rarely holds more stray spheres than this.
constexpr std::size_t kMaxCandidates = 12;

struct Search {
  Search(const std::vector<Eigen::Vector3d>& fits_, const TargetLayout& layout_, double tolerance)
      : fits(fits_), layout(layout_), tolerance_mm(tolerance),
        current(layout_.sphere_centres_mm.size(), -1), used(fits_.size(), false) {}
  const std::vector<Eigen::Vector3d>& fits;
  const TargetLayout& layout;
  double tolerance_mm;
  std::vector<int> current, best;
  std::vector<bool> used;
  int best_count = 0;
  double best_error = std::numeric_limits<double>::infinity();

  /// Assigns layout sphere `k` (the ones before it are assigned), `count` matched so far with
  /// squared distance errors `error`.
  void run(std::size_t k, int count, double error) {
    const std::size_t n = layout.sphere_centres_mm.size();
    if (count + int(n - k) < std::max(best_count, 3))
      return; // cannot beat the best any more
    if (k == n) {
      if (count > best_count || (count == best_count && error < best_error))
        best_count = count, best_error = error, best = current;
      return;
    }
    for (std::size_t f = 0; f < fits.size(); ++f) {
      if (used[f])
        continue;
      double added = 0;
      bool fits_all = true;
      for (std::size_t j = 0; j < k && fits_all; ++j) {
        if (current[j] < 0)
          continue;
        const double measured = (fits[f] - fits[std::size_t(current[j])]).norm();
        const double expected = (layout.sphere_centres_mm[k] - layout.sphere_centres_mm[j]).norm();
        const double e = measured - expected;
        fits_all = std::abs(e) <= tolerance_mm;
        added += e * e;
      }
      if (!fits_all)
        continue;
      used[f] = true;
      current[k] = int(f);
      run(k + 1, count + 1, error + added);
      used[f] = false;
    }
    current[k] = -1;
    run(k + 1, count, error);
  }
};

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

} // namespace

int TargetObservation::found() const {
  int n = 0;
  for (const auto& c : centres_camera_mm)
    n += c.has_value();
  return n;
}

std::vector<int> matchSpheres(const std::vector<Eigen::Vector3d>& fits, const TargetLayout& layout,
                              double tolerance_mm) {
  const std::vector<Eigen::Vector3d> candidates(
      fits.begin(), fits.begin() + std::ptrdiff_t(std::min(fits.size(), kMaxCandidates)));
  Search search(candidates, layout, tolerance_mm);
  search.run(0, 0, 0.0);
  if (search.best_count < 3)
    return {};
  return search.best;
}

Eigen::Isometry3d rigidFit(const std::vector<Eigen::Vector3d>& from,
                           const std::vector<Eigen::Vector3d>& to) {
  Eigen::Matrix3Xd a(3, from.size()), b(3, to.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    a.col(Eigen::Index(i)) = from[i];
    b.col(Eigen::Index(i)) = to[i];
  }
  Eigen::Isometry3d T;
  T.matrix() = Eigen::umeyama(a, b, false);
  return T;
}

TargetObservation detectTarget(const PointCloud& scan, const TargetLayout& layout,
                               const TargetDetectParams& params) {
  const std::vector<SphereFit> fits = fitSpheres(scan, layout.sphere_radius_mm, params.spheres);
  std::vector<Eigen::Vector3d> centres;
  for (const auto& f : fits)
    centres.push_back(f.centre_mm);
  const std::vector<int> match = matchSpheres(centres, layout, params.match_tolerance_mm);
  const std::size_t n = layout.sphere_centres_mm.size();
  int matched = 0;
  for (const int m : match)
    matched += m >= 0;
  const std::string radius = format("%.1f mm", layout.sphere_radius_mm);
  if (fits.empty())
    throw Error(std::string("no sphere of radius ")
                    .append(radius)
                    .append(" found: check that the calibration target is in view and within the "
                            "sensor's range, that --units is right, and that the target file's "
                            "sphere radius is the spheres' real radius"));
  if (matched < std::max(3, params.min_spheres))
    throw Error(std::string("found ")
                    .append(std::to_string(fits.size()))
                    .append(" sphere(s) of radius ")
                    .append(radius)
                    .append(" but only ")
                    .append(std::to_string(matched))
                    .append(" of the target's ")
                    .append(std::to_string(n))
                    .append(" at the target's distances (at least ")
                    .append(std::to_string(std::max(3, params.min_spheres)))
                    .append(" are needed): keep all spheres in view and unoccluded, and check the "
                            "sphere centres in the target file"));

  TargetObservation obs;
  obs.centres_camera_mm.assign(n, std::nullopt);
  obs.sphere_rms_mm.assign(n, 0.0);
  obs.sphere_points.assign(n, 0);
  std::vector<Eigen::Vector3d> from, to;
  for (std::size_t k = 0; k < n; ++k) {
    if (match[k] < 0)
      continue;
    const SphereFit& f = fits[std::size_t(match[k])];
    obs.centres_camera_mm[k] = f.centre_mm;
    obs.sphere_rms_mm[k] = f.rms_mm;
    obs.sphere_points[k] = f.points;
    from.push_back(layout.sphere_centres_mm[k]);
    to.push_back(f.centre_mm);
  }
  obs.T_camera_target = rigidFit(from, to);
  double sum_sq = 0;
  for (std::size_t i = 0; i < from.size(); ++i)
    sum_sq += (obs.T_camera_target * from[i] - to[i]).squaredNorm();
  obs.fit_rms_mm = std::sqrt(sum_sq / double(from.size()));
  return obs;
}

} // namespace scanpick::core::calib
