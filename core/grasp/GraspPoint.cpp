#include "core/grasp/GraspPoint.h"

#include "core/common/Error.h"

namespace scanpick::core::grasp {

std::vector<GraspPoint> graspPoints(const std::vector<GripPoint>& grips_model,
                                    const std::vector<GraspSpec>& specs) {
  std::vector<GraspPoint> out;
  if (specs.empty()) {
    for (const auto& taught : grips_model) {
      const GripPoint g = checkedGrip(taught);
      out.push_back(
          {g.name, g.position_mm, g.approach.value_or(Eigen::Vector3d::UnitZ()), g.closing_axis});
    }
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
                 unitDirection(spec.approach, "the approach of grip '" + spec.grip + "'"),
                 std::nullopt};
    if (spec.closing_axis)
      p.closing_axis = closingAcross(*spec.closing_axis, p.approach, spec.grip);
    out.push_back(std::move(p));
  }
  return out;
}

} // namespace scanpick::core::grasp
