#include "core/grasp/ToolVolume.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanpick::core::grasp {

ToolSolid sweptSolid(const ToolSolid& s, double length, double clearance) {
  ToolSolid out = s;
  const double z_min = s.centre_mm.z() - s.half_extents_mm.z() - length - clearance;
  const double z_max = s.centre_mm.z() + s.half_extents_mm.z() + clearance;
  out.centre_mm.z() = 0.5 * (z_min + z_max);
  out.half_extents_mm.x() += clearance;
  out.half_extents_mm.y() += clearance;
  out.half_extents_mm.z() = 0.5 * (z_max - z_min);
  return out;
}

std::vector<ToolSolid> sweptToolSolids(const Gripper& gripper, double approach_length_mm,
                                       double clearance_mm) {
  std::vector<ToolSolid> out;
  for (const ToolSolid& s : toolSolids(gripper))
    out.push_back(sweptSolid(s, approach_length_mm, clearance_mm));
  return out;
}

bool insideSolid(const ToolSolid& s, const Eigen::Vector3d& p_tool) {
  const Eigen::Vector3d v = p_tool - s.centre_mm;
  if (std::abs(v.z()) > s.half_extents_mm.z())
    return false;
  if (s.shape == SolidShape::Box)
    return std::abs(v.x()) <= s.half_extents_mm.x() && std::abs(v.y()) <= s.half_extents_mm.y();
  return v.head<2>().squaredNorm() <= s.half_extents_mm.x() * s.half_extents_mm.x();
}

Eigen::AlignedBox3d solidBounds(const ToolSolid& s, const Eigen::Isometry3d& T_frame_tool) {
  Eigen::AlignedBox3d box;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
    box.extend(T_frame_tool * (s.centre_mm + corner.cwiseProduct(s.half_extents_mm)));
  }
  return box;
}

std::vector<Eigen::Vector3d> solidSurfaceSamples(const ToolSolid& s, double spacing) {
  if (!(spacing > 0))
    throw Error("solid samples: the spacing must be a positive length (mm)");
  std::vector<Eigen::Vector3d> out;
  const Eigen::Vector3d& h = s.half_extents_mm;
  const auto steps = [spacing](double length) {
    return std::max(1, int(std::ceil(length / spacing)));
  };
  if (s.shape == SolidShape::Box) {
    // Each pair of faces perpendicular to axis a, sampled on a grid over the other two axes.
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      const int nb = steps(2 * h[b]), nc = steps(2 * h[c]);
      for (int side = -1; side <= 1; side += 2)
        for (int i = 0; i <= nb; ++i)
          for (int j = 0; j <= nc; ++j) {
            Eigen::Vector3d v;
            v[a] = side * h[a];
            v[b] = -h[b] + 2 * h[b] * i / nb;
            v[c] = -h[c] + 2 * h[c] * j / nc;
            out.push_back(s.centre_mm + v);
          }
    }
    return out;
  }
  const double r = h.x();
  const int nz = steps(2 * h.z());
  const int rings = steps(r);
  for (int ring = 0; ring <= rings; ++ring) {
    const double rr = r * ring / rings;
    const int nt = std::max(1, int(std::ceil(2 * std::numbers::pi * rr / spacing)));
    for (int t = 0; t < nt; ++t) {
      const double th = 2 * std::numbers::pi * t / nt;
      const Eigen::Vector3d xy(rr * std::cos(th), rr * std::sin(th), 0.0);
      if (ring == rings)
        for (int k = 0; k <= nz; ++k)
          out.push_back(s.centre_mm + xy + Eigen::Vector3d(0, 0, -h.z() + 2 * h.z() * k / nz));
      else
        for (int side = -1; side <= 1; side += 2)
          out.push_back(s.centre_mm + xy + Eigen::Vector3d(0, 0, side * h.z()));
    }
  }
  return out;
}

} // namespace scanpick::core::grasp
