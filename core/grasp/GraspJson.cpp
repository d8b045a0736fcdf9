#include "core/grasp/GraspJson.h"

#include "core/common/Error.h"

#include <set>

namespace scanpick::core::grasp {
namespace {
using nlohmann::json;

void requireObject(const json& j, const std::string& what, const std::set<std::string>& keys) {
  if (!j.is_object())
    throw Error(what + " must be a JSON object");
  for (const auto& item : j.items())
    if (!keys.contains(item.key())) {
      std::string known;
      for (const auto& k : keys)
        known += (known.empty() ? "" : ", ") + k;
      throw Error(what + ": unknown key '" + item.key() + "' (known: " + known + ")");
    }
}

void readNumber(const json& j, const std::string& key, double& out, const std::string& what) {
  if (!j.contains(key))
    return;
  if (!j[key].is_number())
    throw Error(what + "." + key + " must be a number");
  out = j[key].get<double>();
}

void readInt(const json& j, const std::string& key, int& out, const std::string& what) {
  if (!j.contains(key))
    return;
  if (!j[key].is_number_integer())
    throw Error(what + "." + key + " must be an integer");
  const auto v = j[key].get<long long>();
  if (v < -1000000000LL || v > 1000000000LL)
    throw Error(what + "." + key + " is out of range");
  out = int(v);
}

void readBool(const json& j, const std::string& key, bool& out, const std::string& what) {
  if (!j.contains(key))
    return;
  if (!j[key].is_boolean())
    throw Error(what + "." + key + " must be true or false");
  out = j[key].get<bool>();
}

void readString(const json& j, const std::string& key, std::string& out, const std::string& what) {
  if (!j.contains(key))
    return;
  if (!j[key].is_string())
    throw Error(what + "." + key + " must be a string");
  out = j[key].get<std::string>();
}

Eigen::Vector3d vec3(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw Error(what + " must be three numbers [x, y, z]");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

json pose(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  return {{"position_mm", {t.x(), t.y(), t.z()}},
          {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

} // namespace

Gripper gripperFromJson(const json& j) {
  requireObject(j, "gripper", {"kind", "suction", "fingers", "body"});
  Gripper g;
  std::string kind = toString(g.kind);
  readString(j, "kind", kind, "gripper");
  g.kind = parseGripperKind(kind);
  if (j.contains("suction")) {
    const json& s = j["suction"];
    requireObject(s, "gripper.suction", {"diameter_mm", "stroke_mm"});
    readNumber(s, "diameter_mm", g.suction.diameter_mm, "gripper.suction");
    readNumber(s, "stroke_mm", g.suction.stroke_mm, "gripper.suction");
  }
  if (j.contains("fingers")) {
    const json& f = j["fingers"];
    requireObject(f, "gripper.fingers",
                  {"finger_thickness_mm", "finger_width_mm", "finger_length_mm", "opening_mm",
                   "grip_depth_mm"});
    readNumber(f, "finger_thickness_mm", g.fingers.finger_thickness_mm, "gripper.fingers");
    readNumber(f, "finger_width_mm", g.fingers.finger_width_mm, "gripper.fingers");
    readNumber(f, "finger_length_mm", g.fingers.finger_length_mm, "gripper.fingers");
    readNumber(f, "opening_mm", g.fingers.opening_mm, "gripper.fingers");
    readNumber(f, "grip_depth_mm", g.fingers.grip_depth_mm, "gripper.fingers");
  }
  if (j.contains("body")) {
    const json& b = j["body"];
    requireObject(b, "gripper.body", {"shape", "diameter_mm", "depth_mm", "length_mm"});
    std::string shape = "cylinder";
    readString(b, "shape", shape, "gripper.body");
    if (shape != "cylinder" && shape != "box")
      throw Error("gripper.body.shape must be \"cylinder\" or \"box\", not '" + shape + "'");
    g.body.shape = shape == "box" ? SolidShape::Box : SolidShape::Cylinder;
    readNumber(b, "diameter_mm", g.body.diameter_mm, "gripper.body");
    readNumber(b, "depth_mm", g.body.depth_mm, "gripper.body");
    readNumber(b, "length_mm", g.body.length_mm, "gripper.body");
  }
  (void)toolSolids(g); // the dimensions' checks
  return g;
}

json toJson(const Gripper& g) {
  return {{"kind", toString(g.kind)},
          {"suction", {{"diameter_mm", g.suction.diameter_mm}, {"stroke_mm", g.suction.stroke_mm}}},
          {"fingers",
           {{"finger_thickness_mm", g.fingers.finger_thickness_mm},
            {"finger_width_mm", g.fingers.finger_width_mm},
            {"finger_length_mm", g.fingers.finger_length_mm},
            {"opening_mm", g.fingers.opening_mm},
            {"grip_depth_mm", g.fingers.grip_depth_mm}}},
          {"body",
           {{"shape", g.body.shape == SolidShape::Box ? "box" : "cylinder"},
            {"diameter_mm", g.body.diameter_mm},
            {"depth_mm", g.body.depth_mm},
            {"length_mm", g.body.length_mm}}}};
}

std::vector<GraspSpec> graspSpecsFromJson(const json& j) {
  if (!j.is_array())
    throw Error("grasps must be a JSON array of {\"grip\", \"approach\", \"closing_axis\"}");
  std::vector<GraspSpec> out;
  for (const auto& item : j) {
    requireObject(item, "grasps[]", {"grip", "approach", "closing_axis"});
    GraspSpec s;
    readString(item, "grip", s.grip, "grasps[]");
    if (s.grip.empty())
      throw Error("grasps[]: each grasp needs \"grip\", the name of a model grip point");
    if (item.contains("approach"))
      s.approach = vec3(item["approach"], "grasps[].approach");
    if (item.contains("closing_axis"))
      s.closing_axis = vec3(item["closing_axis"], "grasps[].closing_axis");
    out.push_back(std::move(s));
  }
  return out;
}

GraspPlanParams planParamsFromJson(const json& j, const GraspPlanParams& base) {
  requireObject(j, "planning",
                {"approach_length_mm", "max_tilt_deg", "up", "part_tolerance_mm", "clearance_mm",
                 "max_collision_points", "min_score", "order", "one_per_part", "reject_ambiguous",
                 "grid_cell_mm", "bin_sample_mm", "occlusion_radius_mm", "max_occlusion_samples"});
  GraspPlanParams p = base;
  const std::string w = "planning";
  readNumber(j, "approach_length_mm", p.approach_length_mm, w);
  readNumber(j, "max_tilt_deg", p.max_tilt_deg, w);
  if (j.contains("up"))
    p.up = vec3(j["up"], "planning.up").normalized();
  readNumber(j, "part_tolerance_mm", p.part_tolerance_mm, w);
  readNumber(j, "clearance_mm", p.clearance_mm, w);
  readInt(j, "max_collision_points", p.max_collision_points, w);
  readNumber(j, "min_score", p.min_score, w);
  std::string order = toString(p.order);
  readString(j, "order", order, w);
  p.order = parsePickOrder(order);
  readBool(j, "one_per_part", p.one_per_part, w);
  readBool(j, "reject_ambiguous", p.reject_ambiguous, w);
  readNumber(j, "grid_cell_mm", p.grid_cell_mm, w);
  readNumber(j, "bin_sample_mm", p.bin_sample_mm, w);
  readNumber(j, "occlusion_radius_mm", p.occlusion_radius_mm, w);
  readInt(j, "max_occlusion_samples", p.max_occlusion_samples, w);
  return p;
}

json toJson(const GraspPlanParams& p) {
  return {{"approach_length_mm", p.approach_length_mm},
          {"max_tilt_deg", p.max_tilt_deg},
          {"up", {p.up.x(), p.up.y(), p.up.z()}},
          {"part_tolerance_mm", p.part_tolerance_mm},
          {"clearance_mm", p.clearance_mm},
          {"max_collision_points", p.max_collision_points},
          {"min_score", p.min_score},
          {"order", toString(p.order)},
          {"one_per_part", p.one_per_part},
          {"reject_ambiguous", p.reject_ambiguous},
          {"grid_cell_mm", p.grid_cell_mm},
          {"bin_sample_mm", p.bin_sample_mm},
          {"occlusion_radius_mm", p.occlusion_radius_mm},
          {"max_occlusion_samples", p.max_occlusion_samples}};
}

BinEstimateParams binParamsFromJson(const json& j, const BinEstimateParams& base) {
  requireObject(j, "bin",
                {"up", "distance_mm", "angle_tol_deg", "min_plane_share", "max_planes",
                 "iterations", "max_samples", "seed", "estimate"});
  BinEstimateParams p = base;
  const std::string w = "bin";
  if (j.contains("up"))
    p.up = vec3(j["up"], "bin.up").normalized();
  readNumber(j, "distance_mm", p.distance_mm, w);
  readNumber(j, "angle_tol_deg", p.angle_tol_deg, w);
  readNumber(j, "min_plane_share", p.min_plane_share, w);
  readInt(j, "max_planes", p.max_planes, w);
  readInt(j, "iterations", p.iterations, w);
  int samples = int(p.max_samples), seed = int(p.seed);
  readInt(j, "max_samples", samples, w);
  readInt(j, "seed", seed, w);
  if (samples < 3 || seed < 0)
    throw Error("bin.max_samples must be at least 3 and bin.seed not negative");
  p.max_samples = std::size_t(samples);
  p.seed = std::uint64_t(seed);
  return p;
}

json toJson(const GraspCandidate& c) {
  json j = {{"detection", c.detection},
            {"grasp", c.grasp},
            {"grip", c.grip},
            {"tool", pose(c.T_scene_tool)},
            {"pregrasp", pose(c.T_scene_pregrasp)},
            {"tilt_deg", c.tilt_deg},
            {"height_mm", c.height_mm},
            {"occlusion", c.occlusion},
            {"score", c.score}};
  if (!c.rejections.empty()) {
    json reasons = json::array();
    for (const auto& r : c.rejections)
      reasons.push_back({{"kind", toString(r.kind)}, {"detail", r.detail}});
    j["rejected"] = reasons;
  }
  return j;
}

json toJson(const PickList& list) {
  json picks = json::array(), rejected = json::array();
  for (const auto& c : list.picks)
    picks.push_back(toJson(c));
  for (const auto& c : list.rejected)
    rejected.push_back(toJson(c));
  return {{"picks", picks}, {"rejected", rejected}};
}

} // namespace scanpick::core::grasp
