#include "core/matching/RevolutionAxis.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

namespace scanpick::core {
namespace {
/// cos 25°: a normal this close to the axis direction faces along the axis.
constexpr double kAlongAxisCos = 0.906;

/// An axis about the centroid of the points: unit direction `a` and the axis point `c` (mm,
/// relative to the centroid, perpendicular to `a`).
struct CentredAxis {
  Eigen::Vector3d a, c;
};

/// The least-squares axis of the `fitted` points about `centroid` (mm); none when their normals
/// are all (nearly) parallel: a plane, whose axis point is free.
std::optional<CentredAxis> solveAxis(const std::vector<Eigen::Vector3f>& points_mm,
                                     const std::vector<Eigen::Vector3f>& normals,
                                     const std::vector<std::size_t>& fitted,
                                     const Eigen::Vector3d& centroid) {
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
  CentredAxis axis;
  axis.a = axis_solver.eigenvectors().col(0).normalized();
  const Eigen::Vector3d b = -C_pinv * B.transpose() * axis.a;
  axis.c = axis.a.cross(b); // b = c × a with c ⊥ a
  return axis;
}

/// The `used` points that fit `axis` (about `centroid`): those whose normal lies within
/// `angle_tolerance_rad` of the plane through the axis and the point, and those that cannot tell
/// (on the axis, or facing along it). `counted` and `inliers` count the points that can tell and
/// those of them that fit.
std::vector<std::size_t> axisInliers(const std::vector<Eigen::Vector3f>& points_mm,
                                     const std::vector<Eigen::Vector3f>& normals,
                                     const std::vector<std::size_t>& used,
                                     const Eigen::Vector3d& centroid, const CentredAxis& axis,
                                     double angle_tolerance_rad, std::size_t& counted,
                                     std::size_t& inliers) {
  const Eigen::Vector3d &a = axis.a, &c = axis.c;
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
  return next;
}

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
  CentredAxis fit_axis;
  std::size_t counted = 0, inliers = 0;
  constexpr int kFits = 3;
  for (int fit = 0; fit < kFits; ++fit) {
    if (fitted.size() < kMinPoints)
      return std::nullopt;
    const std::optional<CentredAxis> solved = solveAxis(points_mm, normals, fitted, centroid);
    if (!solved)
      return std::nullopt;
    fit_axis = *solved;
    fitted = axisInliers(points_mm, normals, used, centroid, fit_axis, angle_tolerance_rad, counted,
                         inliers);
  }
  if (counted < kMinPoints)
    return std::nullopt;
  RevolutionAxis axis;
  axis.point_mm = centroid + fit_axis.c;
  axis.direction = fit_axis.a;
  axis.inlier_share = double(inliers) / double(counted);
  if (axis.inlier_share < min_inlier_share)
    return std::nullopt;
  return axis;
}

namespace {

/// Rings of wall points: those at one height (within kRingHeightMm) and one distance from the
/// axis (no gap over kRingGapMm between neighbours).
constexpr double kRingHeightMm = 2.0;
constexpr double kRingGapMm = 1.0;

/// Each wall point's distance from the axis about the mean of its ring (the residual), and that
/// residual's derivatives by the axis's turn towards u and v and its move along u and v.
struct RingResiduals {
  std::vector<double> residual;
  std::vector<Eigen::Vector4d> gradient;
  std::vector<std::size_t> point; ///< which wall point (rings of fewer than 3 are left out)
};

RingResiduals ringResiduals(const std::vector<Eigen::Vector3d>& wall, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& c, const std::vector<bool>& used) {
  const Eigen::Vector3d u = a.unitOrthogonal(), v = a.cross(u);
  struct Sample {
    long ring_height;
    double r;
    Eigen::Vector4d gradient;
    std::size_t point;
  };
  std::vector<Sample> samples;
  for (std::size_t i = 0; i < wall.size(); ++i) {
    if (!used[i])
      continue;
    const Eigen::Vector3d q = wall[i] - c;
    const double h = q.dot(a);
    const Eigen::Vector3d w = q - h * a;
    const double r = w.norm();
    if (!(r > kRingGapMm))
      continue;
    const Eigen::Vector3d radial = w / r;
    samples.push_back(
        {std::lround(std::floor(h / kRingHeightMm)), r,
         Eigen::Vector4d(-h * radial.dot(u), -h * radial.dot(v), -radial.dot(u), -radial.dot(v)),
         i});
  }
  std::sort(samples.begin(), samples.end(), [](const Sample& x, const Sample& y) {
    return x.ring_height != y.ring_height ? x.ring_height < y.ring_height : x.r < y.r;
  });
  RingResiduals out;
  for (std::size_t begin = 0; begin < samples.size();) {
    std::size_t end = begin + 1;
    while (end < samples.size() && samples[end].ring_height == samples[begin].ring_height &&
           samples[end].r - samples[end - 1].r <= kRingGapMm)
      ++end;
    if (end - begin >= 3) {
      double r_mean = 0.0;
      Eigen::Vector4d g_mean = Eigen::Vector4d::Zero();
      for (std::size_t k = begin; k < end; ++k) {
        r_mean += samples[k].r;
        g_mean += samples[k].gradient;
      }
      r_mean /= double(end - begin);
      g_mean /= double(end - begin);
      for (std::size_t k = begin; k < end; ++k) {
        out.residual.push_back(samples[k].r - r_mean);
        out.gradient.push_back(samples[k].gradient - g_mean);
        out.point.push_back(samples[k].point);
      }
    }
    begin = end;
  }
  return out;
}

double meanSquare(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values)
    sum += v * v;
  return values.empty() ? 0.0 : sum / double(values.size());
}

} // namespace

RevolutionAxis refineRevolutionAxis(const std::vector<Eigen::Vector3f>& points_mm,
                                    const std::vector<Eigen::Vector3f>& normals,
                                    const RevolutionAxis& axis,
                                    const std::vector<std::uint32_t>& excluded) {
  constexpr std::size_t kMinPoints = 20;
  constexpr double kMinRadialCos = 0.5; // a normal within 60° of radial
  constexpr int kMaxSteps = 10;
  std::vector<bool> skip(points_mm.size(), false);
  for (const std::uint32_t k : excluded)
    if (k < skip.size())
      skip[k] = true;
  Eigen::Vector3d a = axis.direction.normalized(), c = axis.point_mm;
  std::vector<Eigen::Vector3d> wall;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t counted = 0;
  for (std::size_t i = 0; i < points_mm.size() && i < normals.size(); ++i) {
    if (!points_mm[i].allFinite())
      continue;
    centroid += points_mm[i].cast<double>();
    ++counted;
    if (skip[i] || !normals[i].allFinite())
      continue;
    const Eigen::Vector3d p = points_mm[i].cast<double>(),
                          n = normals[i].cast<double>().normalized();
    const Eigen::Vector3d w = (p - c) - (p - c).dot(a) * a;
    if (w.norm() > kRingGapMm && std::abs(n.dot(w.normalized())) >= kMinRadialCos)
      wall.push_back(p);
  }
  if (wall.size() < kMinPoints)
    return axis;
  centroid /= double(counted);
  std::vector<bool> used(wall.size(), true);
  for (int step = 0; step < kMaxSteps; ++step) {
    RingResiduals rings = ringResiduals(wall, a, c, used);
    if (rings.residual.size() < kMinPoints)
      break;
    // Outliers: beyond three robust standard deviations (1.4826 × the median absolute residual).
    std::vector<double> magnitude;
    for (const double e : rings.residual)
      magnitude.push_back(std::abs(e));
    std::nth_element(magnitude.begin(), magnitude.begin() + long(magnitude.size() / 2),
                     magnitude.end());
    const double limit = 3.0 * 1.4826 * std::max(1e-6, magnitude[magnitude.size() / 2]);
    Eigen::Matrix4d JtJ = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Jte = Eigen::Vector4d::Zero();
    std::vector<double> kept;
    for (std::size_t k = 0; k < rings.residual.size(); ++k) {
      if (std::abs(rings.residual[k]) > limit) {
        used[rings.point[k]] = false;
        continue;
      }
      JtJ += rings.gradient[k] * rings.gradient[k].transpose();
      Jte += rings.gradient[k] * rings.residual[k];
      kept.push_back(rings.residual[k]);
    }
    const Eigen::LDLT<Eigen::Matrix4d> solver(JtJ);
    if (solver.info() != Eigen::Success || kept.size() < kMinPoints)
      break;
    const Eigen::Vector4d x = -solver.solve(Jte);
    if (!x.allFinite())
      break;
    const Eigen::Vector3d u = a.unitOrthogonal(), v = a.cross(u);
    const Eigen::Vector3d a_next = (a + x(0) * u + x(1) * v).normalized();
    const Eigen::Vector3d c_next = c + x(2) * u + x(3) * v;
    // Kept only when the spread of the same points about their rings falls.
    const RingResiduals after = ringResiduals(wall, a_next, c_next, used);
    if (after.residual.size() < kMinPoints || !(meanSquare(after.residual) < meanSquare(kept)))
      break;
    a = a_next;
    c = c_next;
    if (x.head<2>().norm() < 1e-7 && x.tail<2>().norm() < 1e-5)
      break;
  }
  RevolutionAxis refined = axis;
  refined.direction = a;
  refined.point_mm = c + (centroid - c).dot(a) * a;
  return refined;
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
