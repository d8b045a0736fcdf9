#include "core/grasp/Gripper.h"

#include "core/common/Error.h"

#include <cmath>

namespace scanpick::core::grasp {
namespace {

void requirePositive(double value, const char* name, bool allow_zero = false) {
  if (!std::isfinite(value) || value < 0.0 || (!allow_zero && value == 0.0))
    throw Error(std::string("gripper ") + name + " must be " +
                (allow_zero ? "zero or more" : "more than zero") + " (mm), not " +
                std::to_string(value));
}

ToolSolid box(std::string name, const Eigen::Vector3d& min_mm, const Eigen::Vector3d& max_mm,
              bool checks_part) {
  ToolSolid s;
  s.name = std::move(name);
  s.shape = SolidShape::Box;
  s.centre_mm = 0.5 * (min_mm + max_mm);
  s.half_extents_mm = 0.5 * (max_mm - min_mm);
  s.checks_part = checks_part;
  return s;
}

ToolSolid cylinder(std::string name, double radius_mm, double z_min_mm, double z_max_mm) {
  ToolSolid s;
  s.name = std::move(name);
  s.shape = SolidShape::Cylinder;
  s.centre_mm = Eigen::Vector3d(0.0, 0.0, 0.5 * (z_min_mm + z_max_mm));
  s.half_extents_mm = Eigen::Vector3d(radius_mm, radius_mm, 0.5 * (z_max_mm - z_min_mm));
  return s;
}

} // namespace

std::vector<ToolSolid> toolSolids(const Gripper& g) {
  std::vector<ToolSolid> solids;
  double body_start_z = 0.0; // where the body begins (its front face), tool z
  if (g.kind == GripperKind::Suction) {
    requirePositive(g.suction.diameter_mm, "suction.diameter_mm");
    requirePositive(g.suction.stroke_mm, "suction.stroke_mm");
    solids.push_back(cylinder("cup", 0.5 * g.suction.diameter_mm, -g.suction.stroke_mm, 0.0));
    body_start_z = -g.suction.stroke_mm;
  } else {
    const ParallelGripper& f = g.fingers;
    requirePositive(f.finger_thickness_mm, "fingers.finger_thickness_mm");
    requirePositive(f.finger_width_mm, "fingers.finger_width_mm");
    requirePositive(f.finger_length_mm, "fingers.finger_length_mm");
    requirePositive(f.opening_mm, "fingers.opening_mm");
    requirePositive(f.grip_depth_mm, "fingers.grip_depth_mm", true);
    const double tip = f.grip_depth_mm, root = f.grip_depth_mm - f.finger_length_mm;
    const double inner = 0.5 * f.opening_mm, outer = inner + f.finger_thickness_mm;
    const double half_w = 0.5 * f.finger_width_mm;
    solids.push_back(box("finger +x", {inner, -half_w, root}, {outer, half_w, tip}, true));
    solids.push_back(box("finger -x", {-outer, -half_w, root}, {-inner, half_w, tip}, true));
    // Whatever else lies between the open fingers would be closed on together with the part.
    solids.push_back(box("closing region", {-inner, -half_w, root}, {inner, half_w, tip}, false));
    body_start_z = root;
  }
  requirePositive(g.body.length_mm, "body.length_mm", true);
  if (g.body.length_mm > 0.0) {
    requirePositive(g.body.diameter_mm, "body.diameter_mm");
    if (g.body.shape == SolidShape::Cylinder) {
      solids.push_back(cylinder("body", 0.5 * g.body.diameter_mm, body_start_z - g.body.length_mm,
                                body_start_z));
    } else {
      requirePositive(g.body.depth_mm, "body.depth_mm");
      const Eigen::Vector3d half(0.5 * g.body.diameter_mm, 0.5 * g.body.depth_mm, 0.0);
      solids.push_back(box("body", {-half.x(), -half.y(), body_start_z - g.body.length_mm},
                           {half.x(), half.y(), body_start_z}, false));
    }
  }
  return solids;
}

const char* toString(GripperKind kind) {
  return kind == GripperKind::Suction ? "suction" : "fingers";
}

GripperKind parseGripperKind(const std::string& name) {
  if (name == "suction")
    return GripperKind::Suction;
  if (name == "fingers")
    return GripperKind::Fingers;
  throw Error("unknown gripper kind '" + name + "': use \"suction\" or \"fingers\"");
}

} // namespace scanpick::core::grasp
