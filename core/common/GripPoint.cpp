#include "core/common/GripPoint.h"

#include "core/common/Error.h"

namespace scanpick::core {

GripPoint transformed(const GripPoint& grip, const Eigen::Isometry3d& T) {
  GripPoint out = grip;
  out.position_mm = T * grip.position_mm;
  if (grip.approach)
    out.approach = T.linear() * *grip.approach;
  if (grip.closing_axis)
    out.closing_axis = T.linear() * *grip.closing_axis;
  return out;
}

nlohmann::json gripToJson(const GripPoint& grip) {
  const auto vec = [](const Eigen::Vector3d& v) {
    return nlohmann::json::array({v.x(), v.y(), v.z()});
  };
  nlohmann::json out = {{"name", grip.name}, {"position_mm", vec(grip.position_mm)}};
  if (grip.approach)
    out["approach"] = vec(*grip.approach);
  if (grip.closing_axis)
    out["closing_axis"] = vec(*grip.closing_axis);
  return out;
}

Eigen::Vector3d unitDirection(const Eigen::Vector3d& v, const std::string& what) {
  if (!v.allFinite() || v.norm() < 1e-9)
    throw Error(what + " must be a non-zero direction");
  return v.normalized();
}

Eigen::Vector3d closingAcross(const Eigen::Vector3d& closing, const Eigen::Vector3d& approach,
                              const std::string& grip) {
  const Eigen::Vector3d c = unitDirection(closing, "the closing axis of grip '" + grip + "'");
  const Eigen::Vector3d across = c - c.dot(approach) * approach;
  if (across.norm() < 0.1)
    throw Error("the closing axis of grip '" + grip +
                "' is (nearly) along its approach: give an axis across it");
  return across.normalized();
}

GripPoint checkedGrip(GripPoint grip) {
  if (!grip.position_mm.allFinite())
    throw Error("grip '" + grip.name + "': its position is not a finite point");
  if (grip.closing_axis && !grip.approach)
    throw Error("grip '" + grip.name + "': a closing axis needs an approach");
  if (grip.approach)
    grip.approach = unitDirection(*grip.approach, "the approach of grip '" + grip.name + "'");
  if (grip.closing_axis)
    grip.closing_axis = closingAcross(*grip.closing_axis, *grip.approach, grip.name);
  return grip;
}

} // namespace scanpick::core
