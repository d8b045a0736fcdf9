#include "core/calib/CalibJson.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"

#include <cmath>

namespace scanpick::core::calib {
namespace {

using json = nlohmann::json;

bool isNumberArray(const json& j, std::size_t size) {
  if (!j.is_array() || j.size() != size)
    return false;
  for (const auto& v : j)
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      return false;
  return true;
}

/// An array of `size` numbers, some of which may be too large for a double (1e999 reads as inf).
bool isAnyNumberArray(const json& j, std::size_t size) {
  if (!j.is_array() || j.size() != size)
    return false;
  for (const auto& v : j)
    if (!v.is_number())
      return false;
  return true;
}

Eigen::Vector3d vec3(const json& j, const std::string& what) {
  if (!isNumberArray(j, 3))
    throw Error(std::string(what).append(" must be three numbers [x, y, z]"));
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

Eigen::Isometry3d fromMatrix(const json& j, double mm_per_unit, const std::string& what) {
  const std::string shape = std::string(what).append(
      " must be a 4 x 4 matrix (four rows of four numbers, the last row 0 0 0 1) or "
      "{\"x\", \"y\", \"z\", \"qw\", \"qx\", \"qy\", \"qz\"}");
  if (!j.is_array() || j.size() != 4)
    throw Error(shape);
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r) {
    if (!isAnyNumberArray(j[std::size_t(r)], 4))
      throw Error(shape);
    if (!isNumberArray(j[std::size_t(r)], 4))
      throw Error(std::string(what)
                      .append(": row ")
                      .append(std::to_string(r + 1))
                      .append(" holds a number that is not finite"));
    for (int c = 0; c < 4; ++c)
      M(r, c) = j[std::size_t(r)][std::size_t(c)].get<double>();
  }
  if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    throw Error(shape);
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3 || R.determinant() < 0)
    throw Error(std::string(what).append(
        ": the upper left 3 x 3 block is not a rotation matrix (give it with at least 4 decimals, "
        "rows as rows)"));
  // Snap to the nearest rotation: a pose printed with 6 decimals is off by ~1e-6.
  const Eigen::Quaterniond q(R);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = M.topRightCorner<3, 1>() * mm_per_unit;
  return T;
}

Eigen::Isometry3d fromPositionQuaternion(const json& j, double mm_per_unit,
                                         const std::string& what) {
  double v[7];
  const char* keys[7] = {"x", "y", "z", "qw", "qx", "qy", "qz"};
  for (int i = 0; i < 7; ++i) {
    if (!j.contains(keys[i]) || !j[keys[i]].is_number())
      throw Error(
          std::string(what)
              .append(" needs the number \"")
              .append(keys[i])
              .append(
                  "\" (position x, y, z and unit quaternion qw, qx, qy, qz), or a 4 x 4 matrix"));
    v[i] = j[keys[i]].get<double>();
    if (!std::isfinite(v[i]))
      throw Error(std::string(what).append(": \"").append(keys[i]).append("\" is not finite"));
  }
  Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (std::abs(q.norm() - 1) > 1e-3)
    throw Error(std::string(what).append(": the quaternion (qw, qx, qy, qz) must have length 1 "
                                         "(check the order: scanpick reads w first)"));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]) * mm_per_unit;
  return T;
}

} // namespace

Eigen::Isometry3d poseFromJson(const json& j, double mm_per_unit, const std::string& what) {
  if (j.is_object() && j.contains("matrix"))
    return fromMatrix(j["matrix"], mm_per_unit, what);
  if (j.is_object())
    return fromPositionQuaternion(j, mm_per_unit, what);
  return fromMatrix(j, mm_per_unit, what);
}

json poseToJson(const Eigen::Isometry3d& T) {
  json matrix = json::array();
  for (int r = 0; r < 4; ++r)
    matrix.push_back({T.matrix()(r, 0), T.matrix()(r, 1), T.matrix()(r, 2), T.matrix()(r, 3)});
  Eigen::Quaterniond q(T.linear());
  if (q.w() < 0)
    q.coeffs() = -q.coeffs(); // the same rotation; w >= 0 reads more easily
  const Eigen::Vector3d t = T.translation();
  return {{"matrix", matrix}, {"x", t.x()},  {"y", t.y()},  {"z", t.z()},
          {"qw", q.w()},      {"qx", q.x()}, {"qy", q.y()}, {"qz", q.z()}};
}

TargetLayout targetFromJson(const json& j, const std::string& source, double min_gap_mm) {
  return withJsonErrors(source, [&] {
    if (!j.is_object())
      throw Error(source + ": a calibration target is a JSON object with \"sphere_radius_mm\" "
                           "and \"spheres_mm\"");
    for (const auto& [key, value] : j.items())
      if (key != "name" && key != "sphere_radius_mm" && key != "spheres_mm" && key != "plate_mm")
        throw Error(source + ": unknown key \"" + key +
                    "\" (a target has name, sphere_radius_mm, spheres_mm, plate_mm)");
    TargetLayout t;
    t.sphere_centres_mm.clear();
    if (j.contains("name"))
      t.name = j.at("name").get<std::string>();
    if (!j.contains("sphere_radius_mm") || !j["sphere_radius_mm"].is_number())
      throw Error(source + ": \"sphere_radius_mm\" (the spheres' radius in mm) is missing");
    t.sphere_radius_mm = j["sphere_radius_mm"].get<double>();
    if (!j.contains("spheres_mm") || !j["spheres_mm"].is_array())
      throw Error(source + ": \"spheres_mm\" (a list of sphere centres [x, y, z] in mm, target "
                           "frame) is missing");
    for (std::size_t i = 0; i < j["spheres_mm"].size(); ++i)
      t.sphere_centres_mm.push_back(
          vec3(j["spheres_mm"][i], source + ": sphere " + std::to_string(i + 1)));
    if (j.contains("plate_mm")) {
      const Eigen::Vector3d plate = vec3(j["plate_mm"], source + ": \"plate_mm\"");
      t.plate_x_mm = plate.x(), t.plate_y_mm = plate.y(), t.plate_thickness_mm = plate.z();
    }
    try {
      validateTarget(t, min_gap_mm);
    } catch (const Error& e) {
      throw Error(source + ": " + e.what());
    }
    return t;
  });
}

json toJson(const TargetLayout& layout) {
  json spheres = json::array();
  for (const auto& c : layout.sphere_centres_mm)
    spheres.push_back({c.x(), c.y(), c.z()});
  return {{"name", layout.name},
          {"sphere_radius_mm", layout.sphere_radius_mm},
          {"spheres_mm", spheres},
          {"plate_mm", {layout.plate_x_mm, layout.plate_y_mm, layout.plate_thickness_mm}}};
}

TargetLayout loadTarget(const std::filesystem::path& path, double min_gap_mm) {
  const std::string source = std::string("'").append(path.string()).append("'");
  return targetFromJson(
      parseJsonText(readFile(path), source, " (a calibration target file, docs/calibration.md)"),
      source, min_gap_mm);
}

std::vector<PoseEntry> loadPoseList(const std::filesystem::path& path, double mm_per_unit) {
  const std::string source = std::string("'").append(path.string()).append("'");
  const json doc =
      parseJsonText(readFile(path), source, " (a calibration poses file, docs/calibration.md)");
  return withJsonErrors(source, [&] {
    const json& list = doc.is_object() && doc.contains("poses") ? doc["poses"] : doc;
    if (!list.is_array())
      throw Error(source + " must hold a list of poses [{\"scan\": PATH, \"T_base_flange\": "
                           "pose}, ...] (or {\"poses\": [...]})");
    std::vector<PoseEntry> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string what = source + " pose " + std::to_string(i + 1);
      const json& e = list[i];
      if (!e.is_object() || !e.contains("scan") || !e["scan"].is_string() ||
          !e.contains("T_base_flange"))
        throw Error(what + " must be {\"scan\": PATH, \"T_base_flange\": pose}");
      PoseEntry entry;
      entry.scan = e["scan"].get<std::string>();
      if (entry.scan.is_relative())
        entry.scan = path.parent_path() / entry.scan;
      entry.T_base_flange = poseFromJson(e["T_base_flange"], mm_per_unit, what + " T_base_flange");
      out.push_back(std::move(entry));
    }
    return out;
  });
}

json toJson(const HandEyeResult& result, const TargetLayout& layout) {
  json residuals = json::array(), rejected = json::array();
  for (const auto& r : result.residuals) {
    json e = {{"pose", r.index + 1},
              {"rms_mm", r.rms_mm},
              {"max_mm", r.max_mm},
              {"rot_deg", r.rot_deg},
              {"rejected", r.rejected}};
    if (r.rejected) {
      e["reason"] = r.reason;
      rejected.push_back({{"pose", r.index + 1}, {"reason", r.reason}});
    }
    residuals.push_back(e);
  }
  return {{"format", "scanpick-handeye"},
          {"version", kCalibrationFileVersion},
          {"mode", modeName(result.mode)},
          {"units", "mm"},
          {result.cameraName(), poseToJson(result.T_camera)},
          {result.targetName(), poseToJson(result.T_target)},
          {"rms_mm", result.rms_mm},
          {"rms_deg", result.rms_deg},
          {"poses_used", result.poses_used},
          {"poses_rejected", rejected},
          {"residuals", residuals},
          {"target", toJson(layout)}};
}

void saveCalibration(const std::filesystem::path& path, const HandEyeResult& result,
                     const TargetLayout& layout) {
  writeFileAtomic(path, dumpJsonText(toJson(result, layout), 2) + "\n");
}

HandEyeResult loadCalibration(const std::filesystem::path& path) {
  const std::string source = std::string("'").append(path.string()).append("'");
  const json doc = parseJsonText(
      readFile(path), source, " (a hand-eye calibration file written by scanpick-cli calibrate)");
  return withJsonErrors(source, [&] {
    if (!doc.is_object() || doc.value("format", "") != "scanpick-handeye")
      throw Error(source + " is not a hand-eye calibration (\"format\": \"scanpick-handeye\")");
    if (doc.at("version").get<int>() > kCalibrationFileVersion)
      throw Error(source + " was written by a newer scanpick (version " +
                  std::to_string(doc.at("version").get<int>()) + "): update scanpick");
    HandEyeResult r;
    if (!doc.contains("mode") || !doc["mode"].is_string())
      throw Error(source + ": \"mode\" (eye-to-hand or eye-in-hand) is missing");
    try {
      r.mode = modeFromName(doc["mode"].get<std::string>());
    } catch (const Error& e) {
      throw Error(source + ": " + e.what());
    }
    for (const std::string& key : {r.cameraName(), r.targetName()})
      if (!doc.contains(key))
        throw Error(source + ": \"" + key + "\" is missing");
    r.T_camera = poseFromJson(doc[r.cameraName()], 1.0, source + " " + r.cameraName());
    r.T_target = poseFromJson(doc[r.targetName()], 1.0, source + " " + r.targetName());
    r.rms_mm = doc.value("rms_mm", 0.0);
    r.rms_deg = doc.value("rms_deg", 0.0);
    r.poses_used = doc.value("poses_used", 0);
    return r;
  });
}

} // namespace scanpick::core::calib
