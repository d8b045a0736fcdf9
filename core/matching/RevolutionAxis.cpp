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

RevolvedBody::RevolvedBody(const std::vector<Eigen::Vector3f>& points_mm,
                           const RevolutionAxis& axis, double cell_mm,
                           const std::vector<std::uint32_t>& excluded)
    : m_origin(axis.point_mm.cast<float>()), m_along(axis.direction.normalized().cast<float>()),
      m_cell(static_cast<float>(cell_mm)) {
  std::vector<bool> skip(points_mm.size(), false);
  for (const std::uint32_t k : excluded)
    if (k < skip.size())
      skip[k] = true;
  std::vector<Eigen::Vector2f> profile; // (height, distance) of each point used
  for (std::size_t i = 0; i < points_mm.size(); ++i) {
    if (skip[i] || !points_mm[i].allFinite())
      continue;
    const Eigen::Vector3f d = points_mm[i] - m_origin;
    const float h = d.dot(m_along);
    profile.emplace_back(h, (d - h * m_along).norm());
  }
  if (profile.empty())
    return;
  float h_max = profile.front().x(), r_max = 0.0f;
  m_h_min = h_max;
  for (const auto& hr : profile) {
    m_h_min = std::min(m_h_min, hr.x());
    h_max = std::max(h_max, hr.x());
    r_max = std::max(r_max, hr.y());
  }
  // One cell of margin on every side, for the widening.
  m_h_min -= m_cell;
  m_rows = int((h_max - m_h_min) / m_cell) + 2;
  m_columns = int(r_max / m_cell) + 2;
  m_cells.assign(std::size_t(m_rows) * std::size_t(m_columns), 0);
  for (const auto& hr : profile) {
    const int row = int((hr.x() - m_h_min) / m_cell), column = int(hr.y() / m_cell);
    for (int i = std::max(0, row - 1); i <= std::min(m_rows - 1, row + 1); ++i)
      for (int j = std::max(0, column - 1); j <= std::min(m_columns - 1, column + 1); ++j)
        m_cells[std::size_t(i) * std::size_t(m_columns) + std::size_t(j)] = 1;
  }
}

[[gnu::always_inline]] inline bool RevolvedBody::occupied(float h, float r) const {
  const float row = std::floor((h - m_h_min) / m_cell), column = std::floor(r / m_cell);
  return row >= 0.0f && column >= 0.0f && row < float(m_rows) && column < float(m_columns) &&
         m_cells[std::size_t(row) * std::size_t(m_columns) + std::size_t(column)] != 0;
}

bool RevolvedBody::contains(const Eigen::Vector3f& p_mm) const {
  const Eigen::Vector3f d = p_mm - m_origin;
  const float h = d.dot(m_along);
  return occupied(h, (d - h * m_along).norm());
}

bool RevolvedBody::blocks(const Eigen::Vector3f& from_mm, const Eigen::Vector3f& to_mm) const {
  if (m_cells.empty())
    return false;
  const Eigen::Vector3f ray = to_mm - from_mm;
  const float length = ray.norm();
  if (!(length > 0.0f))
    return false;
  const Eigen::Vector3f step = ray * (m_cell / length);
  const auto steps = static_cast<int>(length / m_cell);
  const float h_max = m_h_min + float(m_rows) * m_cell, r_max = float(m_columns) * m_cell;
  Eigen::Vector3f d = from_mm - m_origin; // from the axis point
  const float step_h = step.dot(m_along);
  const Eigen::Vector3f step_across = step - step_h * m_along;
  bool left = false; // the path has left the cells it starts in
  for (int k = 1; k <= steps; ++k) {
    d += step;
    const float h = d.dot(m_along);
    const Eigen::Vector3f across = d - h * m_along;
    const float r = across.norm();
    // Outside the body's extent and moving away from it: nothing further can block.
    if ((h < m_h_min && step_h <= 0.0f) || (h > h_max && step_h >= 0.0f) ||
        (r > r_max && across.dot(step_across) >= 0.0f))
      return false;
    const bool inside = occupied(h, r);
    if (!inside)
      left = true;
    else if (left)
      return true;
  }
  return false;
}

} // namespace scanpick::core
