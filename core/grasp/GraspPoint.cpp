#include "core/grasp/GraspPoint.h"

#include "core/common/Error.h"

namespace scanpick::core::grasp {
namespace {

Eigen::Vector3d unit(const Eigen::Vector3d& v, const std::string& what) {
  if (!v.allFinite() || v.norm() < 1e-9)
    throw Error(what + " must be a non-zero direction");
  return v.normalized();
}

} // namespace

std::vector<GraspPoint> graspPoints(const std::vector<GripPoint>& grips_model,
                                    const std::vector<GraspSpec>& specs) {
  std::vector<GraspPoint> out;
  if (specs.empty()) {
    for (const auto& g : grips_model)
      out.push_back({g.name, g.position_mm, Eigen::Vector3d::UnitZ(), std::nullopt});
    return out;
  }
  for (const auto& spec : specs) {
    const GripPoint* grip = nullptr;
    for (const auto& g : grips_model)
      if (g.name == spec.grip)
        grip = &g;
    if (grip == nullptr) {
      std::string names;
      for (const auto& g : grips_model)
        names += (names.empty() ? "" : ", ") + g.name;
      throw Error("grip '" + spec.grip + "' is not a grip point of the model: use one of [" +
                  names + "] or teach it with --grip");
    }
    GraspPoint p{grip->name, grip->position_mm,
                 unit(spec.approach, "the approach of grip '" + spec.grip + "'"), std::nullopt};
    if (spec.closing_axis) {
      const Eigen::Vector3d c = unit(*spec.closing_axis, "the closing axis of '" + spec.grip + "'");
      const Eigen::Vector3d across = c - c.dot(p.approach) * p.approach;
      if (across.norm() < 0.1)
        throw Error("the closing axis of grip '" + spec.grip +
                    "' is (nearly) along its approach: give an axis across it");
      p.closing_axis = across.normalized();
    }
    out.push_back(std::move(p));
  }
  return out;
}

} // namespace scanpick::core::grasp
