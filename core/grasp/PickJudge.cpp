#include "core/grasp/PickJudge.h"

#include "core/grasp/ToolVolume.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scanpick::core::grasp {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / kDeg;
}

/// The nearest true grasp: among those within the approach tolerance first, else any.
void landing(const Eigen::Isometry3d& T, const std::vector<TruthInstance>& instances,
             const PickJudgeParams& p, PickVerdict& v) {
  double best_ok = std::numeric_limits<double>::infinity();
  double best_any = std::numeric_limits<double>::infinity();
  for (const auto& inst : instances)
    for (const auto& G : inst.T_scene_tool) {
      const double d = (G.translation() - T.translation()).norm();
      const double a = angleDeg(G.linear().col(2), T.linear().col(2));
      if (a <= p.approach_tol_deg && d < best_ok) {
        best_ok = d;
        v.instance = inst.id;
        v.position_error_mm = d;
        v.approach_error_deg = a;
      }
      if (!std::isfinite(best_ok) && d < best_any) {
        best_any = d;
        v.position_error_mm = d;
        v.approach_error_deg = a;
      }
    }
  v.wrong = !(best_ok <= p.position_tol_mm);
  if (v.wrong)
    v.instance = -1;
}

std::string hitText(const ToolSolid& s, int id, int points) {
  std::string out = s.name;
  out.append(" hits instance ")
      .append(std::to_string(id))
      .append(" (")
      .append(std::to_string(points))
      .append(" points)");
  return out;
}

} // namespace

PickVerdict judgePick(const Eigen::Isometry3d& T_scene_tool, const Gripper& gripper,
                      const std::vector<TruthInstance>& instances, const std::optional<BinBox>& bin,
                      const PickJudgeParams& p) {
  PickVerdict v;
  landing(T_scene_tool, instances, p, v);
  const Eigen::Isometry3d T_tool_scene = T_scene_tool.inverse();
  for (const auto& solid : sweptToolSolids(gripper, p.approach_length_mm)) {
    const Eigen::AlignedBox3d box = solidBounds(solid, T_scene_tool);
    for (const auto& inst : instances) {
      if (inst.id == v.instance || !box.intersects(inst.bounds_mm))
        continue;
      int hits = 0;
      for (const auto& q : inst.surface_mm)
        if (box.contains(q) && insideSolid(solid, T_tool_scene * q))
          ++hits;
      if (hits > p.max_collision_points)
        v.collisions.push_back(hitText(solid, inst.id, hits));
    }
    if (!bin)
      continue;
    for (const auto& q : solidSurfaceSamples(solid, p.bin_sample_mm)) {
      const std::string hit = binCollision(*bin, T_scene_tool * q);
      if (!hit.empty()) {
        v.collisions.push_back(std::string(solid.name).append(" hits the ").append(hit));
        break;
      }
    }
  }
  return v;
}

} // namespace scanpick::core::grasp
