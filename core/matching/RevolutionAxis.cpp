#include "core/matching/RevolutionAxis.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace scanpick::core {
namespace {
/// cos 25°: a normal this close to the axis direction faces along the axis.
constexpr double kAlongAxisCos = 0.906;
} // namespace

std::optional<RevolutionAxis> fitRevolutionAxis(const std::vector<Eigen::Vector3f>& points_mm,
                                                const std::vector<Eigen::Vector3f>& normals,
                                                double angle_tolerance_rad,
                                                double min_inlier_share) {
  std::vector<std::size_t> used;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < points_mm.size() && i < normals.size(); ++i)
    if (points_mm[i].allFinite() && normals[i].allFinite()) {
      used.push_back(i);
      centroid += points_mm[i].cast<double>();
    }
  constexpr std::size_t kMinPoints = 20;
  if (used.size() < kMinPoints)
    return std::nullopt;
  centroid /= double(used.size());

  // Fitted on all the points, then twice again on the inliers of the last fit: a detail off the
  // surface (a cup's handle) pulls the first fit off the axis by a few millimetres.
  std::vector<std::size_t> fitted = used;
  Eigen::Vector3d a, c;
  std::size_t counted = 0, inliers = 0;
  constexpr int kFits = 3;
  for (int fit = 0; fit < kFits; ++fit) {
    if (fitted.size() < kMinPoints)
      return std::nullopt;
    // Residual of point i for the complex (a, b): m_i · a + n_i · b, with m_i = q_i × n_i, q_i the
    // point about the centroid and b = c × a (c the axis point about the centroid).
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero(),
                    C = Eigen::Matrix3d::Zero();
    for (const std::size_t i : fitted) {
      const Eigen::Vector3d n = normals[i].cast<double>().normalized();
      const Eigen::Vector3d m = (points_mm[i].cast<double>() - centroid).cross(n);
      A += m * m.transpose();
      B += m * n.transpose();
      C += n * n.transpose();
    }
    // Normals all (nearly) parallel: a plane, whose axis point is free.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> normal_spread(C);
    if (normal_spread.eigenvalues()(1) < 0.02 * double(fitted.size()))
      return std::nullopt;
    Eigen::Matrix3d C_pinv = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const double lambda = normal_spread.eigenvalues()(k);
      if (lambda > 1e-9 * double(fitted.size()))
        C_pinv += normal_spread.eigenvectors().col(k) *
                  normal_spread.eigenvectors().col(k).transpose() / lambda;
    }
    // For a fixed direction a the best b is −C⁺Bᵀa; what is left is the Schur complement.
    const Eigen::Matrix3d schur = A - B * C_pinv * B.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axis_solver(schur);
    a = axis_solver.eigenvectors().col(0).normalized();
    const Eigen::Vector3d b = -C_pinv * B.transpose() * a;
    c = a.cross(b); // b = c × a with c ⊥ a

    const double max_sin = std::sin(angle_tolerance_rad);
    counted = inliers = 0;
    std::vector<std::size_t> next;
    for (const std::size_t i : used) {
      const Eigen::Vector3d d = points_mm[i].cast<double>() - centroid - c;
      const Eigen::Vector3d radial = d - d.dot(a) * a;
      const Eigen::Vector3d n = normals[i].cast<double>().normalized();
      // On the axis, or facing along it (a flat end face), every normal passes: such points
      // cannot tell a surface of revolution from any other.
      if (radial.norm() < 1.0 || std::abs(n.dot(a)) > kAlongAxisCos) {
        next.push_back(i);
        continue;
      }
      ++counted;
      const Eigen::Vector3d out_of_meridian = a.cross(radial.normalized());
      if (std::abs(n.dot(out_of_meridian)) <= max_sin) {
        ++inliers;
        next.push_back(i);
      }
    }
    fitted = std::move(next);
  }
  if (counted < kMinPoints)
    return std::nullopt;
  RevolutionAxis axis;
  axis.point_mm = centroid + c;
  axis.direction = a;
  axis.inlier_share = double(inliers) / double(counted);
  if (axis.inlier_share < min_inlier_share)
    return std::nullopt;
  return axis;
}

std::vector<std::uint32_t> detailPoints(const std::vector<Eigen::Vector3f>& points_mm,
                                        const RevolutionAxis& axis, double cell_mm,
                                        double max_span_deg) {
  // A frame with z along the axis: each point's height, distance and angle about it.
  const Eigen::Vector3d z = axis.direction.normalized();
  const Eigen::Vector3d x = z.unitOrthogonal(), y = z.cross(x);
  using Cell = std::pair<long, long>;
  std::map<Cell, std::vector<double>> cell_angles;
  std::vector<Cell> cell_of(points_mm.size());
  for (std::size_t i = 0; i < points_mm.size(); ++i) {
    const Eigen::Vector3d d = points_mm[i].cast<double>() - axis.point_mm;
    const double h = d.dot(z), r = std::hypot(d.dot(x), d.dot(y));
    cell_of[i] = {std::lround(std::floor(h / cell_mm)), std::lround(std::floor(r / cell_mm))};
    cell_angles[cell_of[i]].push_back(std::atan2(d.dot(y), d.dot(x)));
  }
  // A cell's span: the full turn less the widest gap between its angles.
  std::map<Cell, double> span_deg;
  for (auto& [cell, angles] : cell_angles) {
    std::sort(angles.begin(), angles.end());
    double widest_gap = angles.front() + 2.0 * std::numbers::pi - angles.back();
    for (std::size_t k = 1; k < angles.size(); ++k)
      widest_gap = std::max(widest_gap, angles[k] - angles[k - 1]);
    span_deg[cell] = (2.0 * std::numbers::pi - widest_gap) * 180.0 / std::numbers::pi;
  }
  std::vector<std::uint32_t> detail;
  for (std::size_t i = 0; i < points_mm.size(); ++i)
    if (span_deg[cell_of[i]] < max_span_deg)
      detail.push_back(static_cast<std::uint32_t>(i));
  return detail;
}

} // namespace scanpick::core
