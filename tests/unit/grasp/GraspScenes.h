#pragma once
// Scenes built in code for the grasp planner's tests. Camera frame: the camera at the origin looks
// down its +z axis, so up is -z; the bin's floor lies at z = 1000 mm.

#include "core/cloud/PointCloud.h"
#include "core/common/Detection.h"

#include <Eigen/Geometry>
#include <vector>

namespace scanpick::core::grasp::test {

inline constexpr double kFloorZ = 1000.0;

/// Points on the rectangle origin + s u + t v, s in [0, a], t in [0, b], `step` apart.
inline void addPlane(std::vector<Eigen::Vector3f>& out, const Eigen::Vector3d& origin,
                     const Eigen::Vector3d& u, const Eigen::Vector3d& v, double a, double b,
                     double step) {
  for (double s = 0.0; s <= a + 1e-9; s += step)
    for (double t = 0.0; t <= b + 1e-9; t += step)
      out.push_back((origin + s * u + t * v).cast<float>());
}

/// Surface points of a box centred at the origin with half sizes `h` (its own frame), `step`
/// apart.
inline std::vector<Eigen::Vector3f> boxSurface(const Eigen::Vector3d& h, double step = 2.0) {
  std::vector<Eigen::Vector3f> out;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  for (double side : {-1.0, 1.0}) {
    addPlane(out, Eigen::Vector3d(-h.x(), -h.y(), side * h.z()), X, Y, 2 * h.x(), 2 * h.y(), step);
    addPlane(out, Eigen::Vector3d(-h.x(), side * h.y(), -h.z()), X, Z, 2 * h.x(), 2 * h.z(), step);
    addPlane(out, Eigen::Vector3d(side * h.x(), -h.y(), -h.z()), Y, Z, 2 * h.y(), 2 * h.z(), step);
  }
  return out;
}

/// Appends `points` moved by T.
inline void addPosed(std::vector<Eigen::Vector3f>& out, const std::vector<Eigen::Vector3f>& points,
                     const Eigen::Isometry3d& T) {
  for (const auto& p : points)
    out.push_back((T * p.cast<double>()).cast<float>());
}

/// A box part's pose resting on the floor at (x, y), turned by `yaw_deg` about up.
inline Eigen::Isometry3d onFloor(double x, double y, double half_height, double yaw_deg = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, kFloorZ - half_height);
  T.linear() = Eigen::AngleAxisd(yaw_deg * EIGEN_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  return T;
}

inline Detection detectionAt(const Eigen::Isometry3d& T, double score = 0.9) {
  Detection d;
  d.T_scene_model = T;
  d.score = score;
  return d;
}

/// A bin's inside: floor at kFloorZ over |x| <= hx, |y| <= hy, walls up to `rim` above it, and a
/// table 10 mm below the floor outside the walls out to `table` mm from the centre.
inline std::vector<Eigen::Vector3f> binPoints(double hx, double hy, double rim, double table,
                                              double step = 4.0) {
  std::vector<Eigen::Vector3f> out;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  addPlane(out, {-hx, -hy, kFloorZ}, X, Y, 2 * hx, 2 * hy, step);
  for (double side : {-1.0, 1.0}) {
    addPlane(out, {side * hx, -hy, kFloorZ - rim}, Y, Z, 2 * hy, rim, step);
    addPlane(out, {-hx, side * hy, kFloorZ - rim}, X, Z, 2 * hx, rim, step);
  }
  if (table > 0.0) {
    std::vector<Eigen::Vector3f> around;
    addPlane(around, {-table, -table, kFloorZ + 10.0}, X, Y, 2 * table, 2 * table, step);
    for (const auto& p : around)
      if (std::abs(p.x()) > hx + 15.0 || std::abs(p.y()) > hy + 15.0)
        out.push_back(p);
  }
  return out;
}

} // namespace scanpick::core::grasp::test
