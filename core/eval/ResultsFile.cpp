#include "core/eval/ResultsFile.h"

#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/eval/JsonFields.h"

#include <cmath>

namespace scanpick::core::eval {
namespace {

/// An axis {"point_mm": [x, y, z], "direction": [x, y, z]} (direction made unit).
ContinuousAxis readAxis(const nlohmann::json& axis, const std::string& at) {
  const Eigen::Vector3d point = readVector3(requireField(axis, "point_mm", at), at + ".point_mm");
  const Eigen::Vector3d direction =
      readVector3(requireField(axis, "direction", at), at + ".direction");
  if (direction.norm() < 1e-6)
    throw Error(at + ".direction is zero: it must be a unit vector");
  return ContinuousAxis{point, direction.normalized()};
}

/// One entry of "models" (or the single "model"): its name, teach scan and T_teach_model.
ResultModel readModel(const nlohmann::json& model, const std::string& at) {
  ResultModel m;
  if (model.contains("name") && model["name"].is_string())
    m.name = model["name"].get<std::string>();
  if (model.contains("teach_scan") && model["teach_scan"].is_string())
    m.teach_scan = model["teach_scan"].get<std::string>();
  m.T_teach_model =
      readRigidTransform(requireField(model, "T_teach_model", at), at + ".T_teach_model");
  return m;
}

/// A detection's optional "alternative_poses" and their "alternative_free_turn_axes" (one axis
/// or null per pose).
void readAlternatives(const nlohmann::json& value, const std::string& at, ResultDetection& d) {
  if (value.contains("alternative_poses")) {
    const auto& alternatives = value["alternative_poses"];
    if (!alternatives.is_array())
      throw Error(at + ".alternative_poses must be an array of 4x4 rigid transforms");
    for (std::size_t k = 0; k < alternatives.size(); ++k)
      d.alternative_poses.push_back(readRigidTransform(
          alternatives[k], at + ".alternative_poses[" + std::to_string(k) + "]"));
  }
  if (value.contains("alternative_free_turn_axes")) {
    const auto& axes = value["alternative_free_turn_axes"];
    if (!axes.is_array() || axes.size() != d.alternative_poses.size())
      throw Error(at + ".alternative_free_turn_axes must be an array with one entry (an axis or "
                       "null) per alternative pose");
    for (std::size_t k = 0; k < axes.size(); ++k)
      d.alternative_free_turn_axes.push_back(
          axes[k].is_null() ? std::nullopt
                            : std::optional(readAxis(axes[k], at + ".alternative_free_turn_axes[" +
                                                                  std::to_string(k) + "]")));
  }
}

/// Entry `index` of "detections" (`at` names it); `model_count` entries of "models" exist.
ResultDetection readDetection(const nlohmann::json& value, const std::string& at, std::size_t index,
                              std::size_t model_count) {
  ResultDetection d;
  d.id = value.contains("id") ? static_cast<int>(readNumber(value["id"], at + ".id"))
                              : static_cast<int>(index);
  d.score = readNumber(requireField(value, "score", at), at + ".score");
  if (d.score < 0.0 || d.score > 1.0)
    throw Error(at + ".score = " + std::to_string(d.score) + " is outside [0, 1]");
  d.T_scene_model =
      readRigidTransform(requireField(value, "T_scene_model", at), at + ".T_scene_model");
  if (value.contains("model")) {
    const double m = readNumber(value["model"], at + ".model");
    if (m < 0 || m >= double(model_count) || m != std::floor(m))
      throw Error(at + ".model = " + jsonExcerpt(value["model"]) + " names no entry of 'models'");
    d.model = static_cast<std::size_t>(m);
  }
  if (value.contains("grip_points") && value["grip_points"].is_array()) {
    const auto& grips = value["grip_points"];
    for (std::size_t g = 0; g < grips.size(); ++g) {
      const std::string gat = at + ".grip_points[" + std::to_string(g) + "]";
      NamedPoint p;
      p.name = grips[g].value("name", "");
      p.position_mm = readVector3(requireField(grips[g], "position_mm", gat), gat + ".position_mm");
      d.grip_points_scene.push_back(std::move(p));
    }
  }
  if (value.contains("free_turn_axis"))
    d.free_turn_axis = readAxis(value["free_turn_axis"], at + ".free_turn_axis");
  readAlternatives(value, at, d);
  return d;
}

ResultsFile parseResultsFields(const nlohmann::json& doc, const std::string& source) {
  checkFormatAndVersion(doc, "scanpick-results", kResultsVersion, source);
  if (doc.contains("units") && doc["units"] != "mm")
    throw Error(source + ": units " + jsonExcerpt(doc["units"]) +
                " are not supported (expected \"mm\")");
  ResultsFile results;
  results.source = source;
  if (doc.contains("scene") && doc["scene"].is_string())
    results.scene = doc["scene"].get<std::string>();

  if (doc.contains("models")) {
    if (!doc["models"].is_array() || doc["models"].empty())
      throw Error(source + ": 'models' must be a non-empty array");
    for (std::size_t m = 0; m < doc["models"].size(); ++m)
      results.models.push_back(
          readModel(doc["models"][m], source + ": models[" + std::to_string(m) + "]"));
  } else {
    results.models.push_back(readModel(requireField(doc, "model", source), source + ": model"));
  }
  results.model_name = results.models.front().name;
  results.T_teach_model = results.models.front().T_teach_model;

  const auto& detections = requireField(doc, "detections", source);
  if (!detections.is_array())
    throw Error(source + ": 'detections' must be an array");
  for (std::size_t i = 0; i < detections.size(); ++i)
    results.detections.push_back(readDetection(detections[i],
                                               source + ": detections[" + std::to_string(i) + "]",
                                               i, results.models.size()));

  if (doc.contains("timings_ms") && doc["timings_ms"].is_object() &&
      doc["timings_ms"].contains("total"))
    results.total_ms = readNumber(doc["timings_ms"]["total"], source + ": timings_ms.total");
  return results;
}

} // namespace

ResultsFile parseResults(const nlohmann::json& doc, const std::string& source) {
  return withJsonErrors(source, [&] { return parseResultsFields(doc, source); });
}

ResultsFile loadResults(const std::filesystem::path& path) {
  const nlohmann::json doc = readVersionedJson(path, "scanpick-results", kResultsVersion);
  return parseResults(doc, quoted(path));
}

} // namespace scanpick::core::eval
