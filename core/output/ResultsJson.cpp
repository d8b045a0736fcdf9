#include "core/output/ResultsJson.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"

namespace scanpick::core {
namespace {
using nlohmann::json;

json matrix(const Eigen::Isometry3d& T) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r)
    rows.push_back(json::array({T(r, 0), T(r, 1), T(r, 2), T(r, 3)}));
  return rows;
}
json vec(const Eigen::Vector3d& v) {
  return json::array({v.x(), v.y(), v.z()});
}
} // namespace

json resultsToJson(const RecognitionResult& result, const std::vector<ModelSource>& models,
                   const std::string& scene_path) {
  if (models.empty() || !models.front().model)
    throw Error("results need at least one model");
  json model_docs = json::array();
  for (const auto& m : models)
    model_docs.push_back({{"path", m.path},
                          {"name", m.model->name},
                          {"teach_scan", m.model->teach_scan},
                          {"T_teach_model", matrix(m.model->T_teach_model)}});
  json detections = json::array();
  for (std::size_t i = 0; i < result.detections.size(); ++i) {
    const Detection& d = result.detections[i];
    const Eigen::Quaterniond q(d.T_scene_model.linear());
    json grips = json::array();
    for (const auto& g : d.grip_points_scene)
      grips.push_back(gripToJson(g));
    json pairs = json::array();
    for (const auto& [m, s] : d.matched_features)
      pairs.push_back(json::array({m, s}));
    detections.push_back({{"id", i},
                          {"score", d.score},
                          {"feature_score", d.feature_score},
                          {"coverage", d.coverage},
                          {"refined", d.refined},
                          {"cluster", d.cluster},
                          {"model", d.model_index},
                          {"T_scene_model", matrix(d.T_scene_model)},
                          {"position_mm", vec(d.T_scene_model.translation())},
                          {"quaternion_wxyz", json::array({q.w(), q.x(), q.y(), q.z()})},
                          {"grip_points", grips},
                          {"matched_features", pairs}});
    const auto axisJson = [&](const std::optional<FreeTurnAxis>& axis) -> json {
      if (!axis)
        return nullptr;
      return {{"point_mm", vec(axis->point_mm)}, {"direction", vec(axis->direction)}};
    };
    if (d.free_turn_axis)
      detections.back()["free_turn_axis"] = axisJson(d.free_turn_axis);
    if (!d.alternative_poses.empty()) {
      json alternatives = json::array();
      for (const auto& T : d.alternative_poses)
        alternatives.push_back(matrix(T));
      detections.back()["alternative_poses"] = alternatives;
    }
    if (!d.alternative_free_turn_axes.empty()) {
      json axes = json::array();
      for (const auto& axis : d.alternative_free_turn_axes)
        axes.push_back(axisJson(axis));
      detections.back()["alternative_free_turn_axes"] = axes;
    }
  }
  const StageTimings& t = result.timings;
  return {{"format", "scanpick-results"},
          {"version", kResultsFormatVersion},
          {"units", "mm"},
          {"scene", scene_path},
          {"model", model_docs.front()},
          {"models", model_docs},
          {"detections", detections},
          {"timings_ms",
           {{"preprocess", t.preprocess_ms},
            {"clustering", t.clustering_ms},
            {"keypoints", t.keypoints_ms},
            {"features", t.features_ms},
            {"matching", t.matching_ms},
            {"refine", t.refine_ms},
            {"total", t.total_ms}}}};
}

void saveResults(const std::filesystem::path& path, const RecognitionResult& result,
                 const std::vector<ModelSource>& models, const std::string& scene_path) {
  writeFileAtomic(path, dumpJsonText(resultsToJson(result, models, scene_path), 2) + "\n");
}

} // namespace scanpick::core
