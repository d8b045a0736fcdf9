#pragma once
/// @file PrincipalAxes.h
/// The mean and principal axes of a set of 3D points (PCA), as plane fits, noise estimates and
/// size measures use them.

#include <Eigen/Eigenvalues>
#include <cstddef>
#include <vector>

namespace scanpick::core {

/// The mean of some points and the eigen-decomposition of their scatter about it: `variances`
/// in increasing order (mean squared distance along each axis, in the points' units squared),
/// `axes` the matching unit directions as columns, so that axes.col(0) is the normal of their
/// least-squares plane.
struct PrincipalAxes {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

/// PCA of the `count` points `point(0)` … `point(count - 1)` (Eigen 3-vectors, float or double).
/// No points: the zero mean and variances, the identity axes.
template <class PointAt> PrincipalAxes principalAxes(std::size_t count, const PointAt& point) {
  PrincipalAxes pca;
  if (count == 0)
    return pca;
  for (std::size_t i = 0; i < count; ++i)
    pca.mean += point(i).template cast<double>();
  pca.mean /= double(count);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d d = point(i).template cast<double>() - pca.mean;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter / double(count));
  pca.variances = solver.eigenvalues().cwiseMax(0.0);
  pca.axes = solver.eigenvectors();
  return pca;
}

/// PCA of a vector of points.
template <class Vector3> PrincipalAxes principalAxes(const std::vector<Vector3>& points) {
  return principalAxes(points.size(), [&](std::size_t i) { return points[i]; });
}

} // namespace scanpick::core
