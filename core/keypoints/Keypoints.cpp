#include "core/keypoints/Keypoints.h"

#include "core/common/Error.h"
#include "core/keypoints/Neighbourhoods.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

/// Points are processed in blocks between progress reports; each block is a parallel loop
/// whose per-point results do not depend on scheduling.
constexpr std::size_t kBlock = 65536;

template <typename Body>
void forEachValid(std::size_t n, const ProgressFn& progress, double begin, double end, Body body) {
  for (std::size_t b = 0; b < n; b += kBlock) {
    reportProgress(progress,
                   begin + (end - begin) * static_cast<double>(b) / static_cast<double>(n));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(b, std::min(n, b + kBlock), 512),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<int> scratch;
                        for (std::size_t j = r.begin(); j < r.end(); ++j)
                          body(j, scratch);
                      });
  }
}

Keypoints collect(const PointCloud& cloud, const std::vector<int>& valid,
                  const std::vector<char>& keep) {
  Keypoints out;
  for (std::size_t j = 0; j < valid.size(); ++j)
    if (keep[j]) {
      out.source_indices.push_back(valid[j]);
      out.points_mm.push_back(cloud.points_mm[static_cast<std::size_t>(valid[j])]);
    }
  return out;
}

void requirePositive(double value, const char* key) {
  if (!(value > 0))
    throw Error(std::string("keypoint extraction needs a positive ") + key + ", got " +
                std::to_string(value));
}

/// Unit normals of the valid points (NaN where undefined), oriented towards the origin.
std::vector<Eigen::Vector3f> pointNormals(const PointCloud& cloud, const detail::Neighbourhoods& nb,
                                          double radius_mm, const ProgressFn& progress) {
  const auto& valid = nb.validIndices();
  std::vector<Eigen::Vector3f> normals(valid.size(), invalidPoint());
  const bool own = !cloud.normals.empty() && std::all_of(valid.begin(), valid.end(), [&](int i) {
    return cloud.normals[static_cast<std::size_t>(i)].allFinite();
  });
  forEachValid(valid.size(), progress, 0.0, 1.0, [&](std::size_t j, std::vector<int>& /*scratch*/) {
    const auto i = static_cast<std::size_t>(valid[j]);
    const Eigen::Vector3f& p = cloud.points_mm[i];
    Eigen::Vector3f n;
    if (own) {
      n = cloud.normals[i].normalized();
    } else {
      // One pass, relative to the point itself: offsets are at most the radius, so float sums
      // keep their precision.
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      Eigen::Matrix3f outer = Eigen::Matrix3f::Zero();
      std::size_t found = 0;
      nb.forEachWithin(valid[j], radius_mm, [&](int k) {
        const Eigen::Vector3f d = cloud.points_mm[static_cast<std::size_t>(k)] - p;
        sum += d;
        outer.noalias() += d * d.transpose();
        ++found;
      });
      if (found < 3)
        return;
      const double count = static_cast<double>(found);
      const Eigen::Vector3d mean = sum.cast<double>() / count;
      const Eigen::Matrix3d cov = outer.cast<double>() / count - mean * mean.transpose();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
      solver.computeDirect(cov);
      n = solver.eigenvectors().col(0).cast<float>();
    }
    if (n.dot(-p) < 0)
      n = -n;
    normals[j] = n;
  });
  return normals;
}

} // namespace

Keypoints neighbourhoodAnalysis(const PointCloud& cloud_mm, const KeypointParams& params,
                                const ProgressFn& progress) {
  requirePositive(params.neighbourhood_radius_mm,
                  "neighbourhood radius (keypoints.neighbourhood_radius_mm)");
  cloud_mm.validate();
  if (params.position_range_mm < 0) { // the thesis's "-1": every point is a keypoint
    std::vector<int> valid;
    for (std::size_t i = 0; i < cloud_mm.size(); ++i)
      if (isValid(cloud_mm.points_mm[i]))
        valid.push_back(static_cast<int>(i));
    return collect(cloud_mm, valid, std::vector<char>(valid.size(), 1));
  }
  const detail::Neighbourhoods nb(cloud_mm, params.neighbourhood_radius_mm);
  const auto& valid = nb.validIndices();
  std::vector<char> keep(valid.size(), 0);
  const double range_sq = params.position_range_mm * params.position_range_mm;
  forEachValid(valid.size(), progress, 0.0, 1.0, [&](std::size_t j, std::vector<int>& /*scratch*/) {
    // The centroid's offset from the point.
    const auto [sum, found] = nb.offsetSum(valid[j], params.neighbourhood_radius_mm);
    keep[j] = (sum / static_cast<double>(found)).squaredNorm() >= range_sq;
  });
  reportProgress(progress, 1.0);
  return collect(cloud_mm, valid, keep);
}

Keypoints normalsGradientAnalysis(const PointCloud& cloud_mm, const KeypointParams& params,
                                  const ProgressFn& progress) {
  requirePositive(params.normal_radius_mm, "normal radius (keypoints.normal_radius_mm)");
  if (params.gradient_neighbours < 1)
    throw Error("normals gradient analysis needs at least one neighbour "
                "(keypoints.gradient_neighbours), got " +
                std::to_string(params.gradient_neighbours));
  cloud_mm.validate();
  const detail::Neighbourhoods nb(cloud_mm, params.normal_radius_mm);
  const auto& valid = nb.validIndices();
  std::vector<int> position(cloud_mm.size(), -1); // input index -> valid position
  for (std::size_t j = 0; j < valid.size(); ++j)
    position[static_cast<std::size_t>(valid[j])] = static_cast<int>(j);
  const auto normals =
      pointNormals(cloud_mm, nb, params.normal_radius_mm, subProgress(progress, 0.0, 0.5));

  // findPeak's inner loop for every point at once: the largest normal turn towards one of the
  // n nearest neighbours, and that neighbour.
  std::vector<float> max_angle(valid.size(), 0.0f);
  std::vector<int> max_angle_point(valid.size(), -1);
  forEachValid(valid.size(), subProgress(progress, 0.5, 0.95), 0.0, 1.0,
               [&](std::size_t j, std::vector<int>& neighbours) {
                 if (!normals[j].allFinite())
                   return;
                 nb.nearest(valid[j], params.gradient_neighbours, neighbours);
                 for (int k : neighbours) {
                   const int pk = position[static_cast<std::size_t>(k)];
                   const auto& nk = normals[static_cast<std::size_t>(pk)];
                   if (!nk.allFinite())
                     continue;
                   const float angle = std::acos(std::clamp(normals[j].dot(nk), -1.0f, 1.0f));
                   if (angle > max_angle[j]) {
                     max_angle[j] = angle;
                     max_angle_point[j] = pk;
                   }
                 }
               });

  // The walk of findPeak: follow the largest turn while it keeps growing.
  std::vector<char> peak(valid.size(), 0);
  const auto s = static_cast<float>(params.gradient_sensitivity_rad);
  for (std::size_t j = 0; j < valid.size(); ++j) {
    if (max_angle[j] < s || max_angle_point[j] < 0)
      continue; // first step below the sensitivity: a flat region
    std::size_t current = j;
    float alpha = 0.0f;
    // Each step strictly raises alpha, so the walk ends; the bound only guards pathological data.
    for (std::size_t step = 0; step < valid.size(); ++step) {
      if (!(max_angle[current] > alpha) || max_angle_point[current] < 0)
        break;
      alpha = max_angle[current];
      current = static_cast<std::size_t>(max_angle_point[current]);
    }
    peak[current] = 1;
  }
  reportProgress(progress, 1.0);
  return collect(cloud_mm, valid, peak);
}

Keypoints extractKeypoints(const PointCloud& cloud_mm, const KeypointParams& params,
                           const ProgressFn& progress) {
  switch (params.method) {
  case KeypointParams::Method::Neighbourhood:
    return neighbourhoodAnalysis(cloud_mm, params, progress);
  case KeypointParams::Method::NormalsGradient:
    return normalsGradientAnalysis(cloud_mm, params, progress);
  case KeypointParams::Method::Both:
    break;
  }
  const Keypoints edges = neighbourhoodAnalysis(cloud_mm, params, subProgress(progress, 0.0, 0.4));
  const Keypoints peaks =
      normalsGradientAnalysis(cloud_mm, params, subProgress(progress, 0.4, 1.0));
  std::vector<int> merged;
  std::set_union(edges.source_indices.begin(), edges.source_indices.end(),
                 peaks.source_indices.begin(), peaks.source_indices.end(),
                 std::back_inserter(merged));
  Keypoints out;
  out.source_indices = merged;
  for (int i : merged)
    out.points_mm.push_back(cloud_mm.points_mm[static_cast<std::size_t>(i)]);
  return out;
}

} // namespace scanpick::core
