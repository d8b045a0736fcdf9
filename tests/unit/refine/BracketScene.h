#pragma once
// Synthetic data for the refinement tests and benchmark: an exact ray caster for solids made of
// axis-aligned boxes, each optionally drilled by a round hole along one axis, posed anywhere in
// front of a pinhole camera at the origin looking along +z, plus an optional floor plane.
// The default part is an asymmetric L-bracket with two holes. Header-only and deterministic.
#include "core/cloud/PointCloud.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace scanpick::test {

/// A box [min, max] (part frame, mm) minus an optional cylinder of radius hole_radius along
/// axis hole_axis through hole_centre.
struct DrilledBox {
  Eigen::Vector3d min, max;
  double hole_radius = 0;
  int hole_axis = 2;
  Eigen::Vector3d hole_centre = Eigen::Vector3d::Zero();

  /// First entry of the ray o + t d (t > eps) into the solid, part frame.
  [[nodiscard]] std::optional<double> hit(const Eigen::Vector3d& o,
                                          const Eigen::Vector3d& d) const {
    double t0 = -std::numeric_limits<double>::infinity(),
           t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (std::abs(d[a]) < 1e-12) {
        if (o[a] < min[a] || o[a] > max[a])
          return std::nullopt;
        continue;
      }
      double ta = (min[a] - o[a]) / d[a], tb = (max[a] - o[a]) / d[a];
      if (ta > tb)
        std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    if (t0 > t1 || t0 <= 1e-6)
      return std::nullopt;
    if (hole_radius <= 0)
      return t0;
    // The ray's interval inside the infinite hole cylinder.
    const int u = (hole_axis + 1) % 3, v = (hole_axis + 2) % 3;
    const double ou = o[u] - hole_centre[u], ov = o[v] - hole_centre[v];
    const double A = d[u] * d[u] + d[v] * d[v], B = 2 * (ou * d[u] + ov * d[v]);
    const double C = ou * ou + ov * ov - hole_radius * hole_radius;
    double c0, c1;
    if (A < 1e-12) {
      if (C >= 0)
        return t0;
      c0 = -std::numeric_limits<double>::infinity(), c1 = std::numeric_limits<double>::infinity();
    } else {
      const double disc = B * B - 4 * A * C;
      if (disc <= 0)
        return t0;
      c0 = (-B - std::sqrt(disc)) / (2 * A), c1 = (-B + std::sqrt(disc)) / (2 * A);
    }
    if (t0 < c0 || t0 > c1)
      return t0; // enters the box outside the hole
    if (c1 < t1)
      return c1;         // enters through the hole's wall
    return std::nullopt; // passes through the hole
  }
};

/// A rigid solid: the union of drilled boxes, placed by T_camera_part.
struct PlacedSolid {
  std::vector<DrilledBox> pieces;
  Eigen::Isometry3d T_camera_part = Eigen::Isometry3d::Identity();
};

/// The L-bracket (part frame, mm): a 60 x 40 x 5 base drilled by a Ø12 hole at (38, 22) and a
/// 5 x 40 x 35 upright leg at x = 0..5 drilled by a Ø8 hole along x at (y 12, z 24). Legs of
/// different lengths and off-centre holes: no rotation maps it onto itself.
inline std::vector<DrilledBox> lBracket() {
  DrilledBox base{{0, 0, 0}, {60, 40, 5}, 6.0, 2, {38, 22, 0}};
  DrilledBox leg{{0, 0, 5}, {5, 40, 40}, 4.0, 0, {0, 12, 24}};
  return {base, leg};
}

/// Renders an organized width x height cloud (camera at the origin looking along +z, focal
/// f_px, principal point at the centre). Gaussian noise of sigma_mm along z and a share
/// `dropout` of pixels set to NaN, both from `seed`. `labels` gets the solid index per pixel
/// (-1 floor, -2 nothing).
inline core::PointCloud renderSolids(const std::vector<PlacedSolid>& solids,
                                     std::optional<double> floor_z_mm, int width, int height,
                                     double f_px, double sigma_mm, double dropout,
                                     std::uint64_t seed, std::vector<int>* labels = nullptr) {
  core::PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(width);
  cloud.height = static_cast<std::uint32_t>(height);
  cloud.points_mm.assign(static_cast<std::size_t>(width) * height, core::invalidPoint());
  if (labels)
    labels->assign(cloud.points_mm.size(), -2);
  std::vector<Eigen::Isometry3d> T_part_camera;
  for (const auto& s : solids)
    T_part_camera.push_back(s.T_camera_part.inverse());
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) {
      const Eigen::Vector3d d((c - (width - 1) / 2.0) / f_px, (r - (height - 1) / 2.0) / f_px, 1.0);
      double best = std::numeric_limits<double>::infinity();
      int id = -2;
      if (floor_z_mm)
        best = *floor_z_mm, id = -1;
      for (std::size_t s = 0; s < solids.size(); ++s) {
        const Eigen::Vector3d o = T_part_camera[s].translation();
        const Eigen::Vector3d dp = T_part_camera[s].linear() * d;
        for (const auto& piece : solids[s].pieces)
          if (const auto t = piece.hit(o, dp); t && *t < best)
            best = *t, id = static_cast<int>(s);
      }
      // Draw both numbers for every pixel so the noise of one pixel never depends on another's.
      const double n = noise(rng), drop = uniform(rng);
      if (id == -2 || drop < dropout)
        continue;
      const std::size_t i = static_cast<std::size_t>(r) * width + c;
      cloud.points_mm[i] = (best * d * (1.0 + sigma_mm * n / best)).cast<float>();
      if (labels)
        (*labels)[i] = id;
    }
  return cloud;
}

/// Largest z (camera frame) of the solid's box corners: where a floor under it may go.
inline double deepestZ(const PlacedSolid& solid) {
  double z = -std::numeric_limits<double>::infinity();
  for (const auto& piece : solid.pieces)
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d corner((k & 1) ? piece.max.x() : piece.min.x(),
                                   (k & 2) ? piece.max.y() : piece.min.y(),
                                   (k & 4) ? piece.max.z() : piece.min.z());
      z = std::max(z, (solid.T_camera_part * corner).z());
    }
  return z;
}

/// Rotation of angle_deg about `axis` (normalized here).
inline Eigen::Matrix3d rotationDeg(double angle_deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

/// Translation error (mm) and rotation error (degrees) between two poses.
inline std::pair<double, double> poseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const double t = (a.translation() - b.translation()).norm();
  const Eigen::AngleAxisd aa(a.linear().transpose() * b.linear());
  return {t, std::abs(aa.angle()) * 180.0 / M_PI};
}

/// The model as teach() would store it: one view of the L-bracket, model frame = teach camera
/// axes with the origin at the points' centroid.
struct TaughtView {
  core::PointCloud model;                                          ///< model frame, unorganized
  Eigen::Isometry3d T_camera_part = Eigen::Isometry3d::Identity(); ///< bracket in the teach view
  Eigen::Isometry3d T_teach_model = Eigen::Isometry3d::Identity(); ///< model frame in the view
  /// Where the model sits in a scene that shows the bracket at T_scene_part.
  [[nodiscard]] Eigen::Isometry3d modelPose(const Eigen::Isometry3d& T_scene_part) const {
    return T_scene_part * T_camera_part.inverse() * T_teach_model;
  }
};

/// Teach view: base plate facing the camera (flipped about x), turned 35° about y so the upright
/// leg's inner face is seen too, the part's middle 500 mm in front of a camera with f = 1000 px
/// (0.5 mm between samples), 0.1 mm noise, seed 11.
inline TaughtView teachBracketView() {
  TaughtView out;
  PlacedSolid teach{lBracket(), Eigen::Isometry3d::Identity()};
  teach.T_camera_part.linear() =
      rotationDeg(35, Eigen::Vector3d::UnitY()) * rotationDeg(180, Eigen::Vector3d::UnitX());
  teach.T_camera_part.translation() =
      Eigen::Vector3d(0, 0, 500) - teach.T_camera_part.linear() * Eigen::Vector3d(30, 20, 20);
  core::PointCloud valid =
      core::dropInvalid(renderSolids({teach}, std::nullopt, 400, 300, 1000, 0.1, 0, 11));
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : valid.points_mm)
    centroid += p.cast<double>();
  centroid /= static_cast<double>(valid.size());
  for (auto& p : valid.points_mm)
    p -= centroid.cast<float>();
  out.model = std::move(valid);
  out.T_camera_part = teach.T_camera_part;
  out.T_teach_model.translation() = centroid;
  return out;
}

} // namespace scanpick::test
