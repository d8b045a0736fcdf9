#pragma once
// A tiny exact ray caster for tests and benchmarks: a pinhole camera at the origin looking along
// +z, a projector elsewhere, a floor plane, boxes and upright cylinders. A pixel is valid only if
// its surface point is also lit by the projector, as with structured light (so projector
// shadows appear as in real scans). Header-only, deterministic (optional seeded z-noise).
#include "core/cloud/PointCloud.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace scanpick::test {

struct RaycastScene {
  std::optional<double> floor_z_mm;       ///< plane z = floor_z (facing the camera)
  std::vector<Eigen::AlignedBox3d> boxes; ///< axis-aligned boxes, mm
  struct Cylinder {
    Eigen::Vector2d centre_xy;
    double radius, z_top, z_bottom;
  };
  std::vector<Cylinder> cylinders; ///< axis along z, top (near the camera) at z_top
  std::vector<int> labels;         ///< filled by render: object id per pixel, -1 floor/none

  /// Nearest hit along o + t d (t > eps); returns t and the object id (-1 floor) or nullopt.
  std::optional<std::pair<double, int>> hit(const Eigen::Vector3d& o,
                                            const Eigen::Vector3d& d) const {
    double best = std::numeric_limits<double>::infinity();
    int id = -2;
    const double eps = 1e-6;
    if (floor_z_mm && std::abs(d.z()) > 1e-12) {
      const double t = (*floor_z_mm - o.z()) / d.z();
      if (t > eps && t < best)
        best = t, id = -1;
    }
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      double t0 = -std::numeric_limits<double>::infinity(),
             t1 = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
          if (o[a] < boxes[b].min()[a] || o[a] > boxes[b].max()[a])
            t0 = 1, t1 = 0;
          continue;
        }
        double ta = (boxes[b].min()[a] - o[a]) / d[a], tb = (boxes[b].max()[a] - o[a]) / d[a];
        if (ta > tb)
          std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
      }
      if (t0 <= t1 && t0 > eps && t0 < best)
        best = t0, id = static_cast<int>(b);
    }
    for (std::size_t c = 0; c < cylinders.size(); ++c) {
      const auto& cy = cylinders[c];
      const int cid = static_cast<int>(boxes.size() + c);
      if (std::abs(d.z()) > 1e-12) { // top cap
        const double t = (cy.z_top - o.z()) / d.z();
        if (t > eps && t < best && ((o + t * d).head<2>() - cy.centre_xy).norm() <= cy.radius)
          best = t, id = cid;
      }
      const Eigen::Vector2d oc = o.head<2>() - cy.centre_xy, dd = d.head<2>();
      const double A = dd.squaredNorm(), B = 2 * oc.dot(dd),
                   C = oc.squaredNorm() - cy.radius * cy.radius;
      const double disc = B * B - 4 * A * C;
      if (A > 1e-12 && disc >= 0) {
        for (double t : {(-B - std::sqrt(disc)) / (2 * A), (-B + std::sqrt(disc)) / (2 * A)}) {
          const double z = o.z() + t * d.z();
          if (t > eps && t < best && z >= cy.z_top && z <= cy.z_bottom)
            best = t, id = cid;
        }
      }
    }
    if (id == -2)
      return std::nullopt;
    return std::make_pair(best, id);
  }

  /// Renders an organized width x height cloud with focal length f_px (principal point at the
  /// centre) and the projector at `projector_mm`; z-noise sigma_mm from `seed`.
  core::PointCloud render(int width, int height, double f_px, const Eigen::Vector3d& projector_mm,
                          double noise_sigma_mm = 0.0, std::uint64_t seed = 1) {
    core::PointCloud cloud;
    cloud.width = static_cast<std::uint32_t>(width);
    cloud.height = static_cast<std::uint32_t>(height);
    cloud.points_mm.assign(static_cast<std::size_t>(width) * height, core::invalidPoint());
    labels.assign(cloud.points_mm.size(), -1);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, noise_sigma_mm > 0 ? noise_sigma_mm : 1.0);
    for (int r = 0; r < height; ++r)
      for (int c = 0; c < width; ++c) {
        const Eigen::Vector3d d((c - (width - 1) / 2.0) / f_px, (r - (height - 1) / 2.0) / f_px,
                                1.0);
        const auto h = hit(Eigen::Vector3d::Zero(), d);
        if (!h)
          continue;
        Eigen::Vector3d p = h->first * d;
        const Eigen::Vector3d to_point = p - projector_mm;
        const auto lit = hit(projector_mm, to_point);
        if (!lit || lit->first < 1.0 - 1e-6)
          continue; // the projector's light is blocked first
        if (noise_sigma_mm > 0)
          p *= 1.0 + noise(rng) / p.z();
        const std::size_t i = static_cast<std::size_t>(r) * width + c;
        cloud.points_mm[i] = p.cast<float>();
        labels[i] = h->second;
      }
    return cloud;
  }
};

} // namespace scanpick::test
