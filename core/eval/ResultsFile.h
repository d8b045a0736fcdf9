#pragma once
/// @file ResultsFile.h
/// What the evaluator needs from a results file (`result.json`, written by `scanpick-cli
/// recognize` and the GUI; format in docs/file-formats.md).

#include "core/eval/GroundTruth.h"

#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::eval {

/// Highest results version this reader understands.
inline constexpr int kResultsVersion = 1;

/// One reported detection.
struct ResultDetection {
  int id = 0;
  double score = 0.0;
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
  std::vector<NamedPoint> grip_points_scene; ///< as reported (informative only)
  std::size_t model = 0;                     ///< index into ResultsFile::models
  /// The axis (scene frame) about which the detection's turn was not seen, when reported.
  std::optional<ContinuousAxis> free_turn_axis;
  /// Other poses (model frame → scene frame) the detection reports it cannot tell apart.
  std::vector<Eigen::Isometry3d> alternative_poses;
  /// Empty, or per alternative pose the axis (scene frame) about which its turn was not seen.
  std::vector<std::optional<ContinuousAxis>> alternative_free_turn_axes;
};

/// One taught model (view) the results were produced with.
struct ResultModel {
  std::string name;       ///< taught model's name ("" when absent)
  std::string teach_scan; ///< file name of the scan it was taught from ("" when unknown)
  /// The model frame in the frame of the scan the model was taught from.
  Eigen::Isometry3d T_teach_model = Eigen::Isometry3d::Identity();
};

/// A results file's content.
struct ResultsFile {
  std::string source;     ///< file it came from (for messages)
  std::string scene;      ///< scan the results belong to
  std::string model_name; ///< taught model's name ("" when absent)
  /// The model frame in the frame of the scan the model was taught from.
  Eigen::Isometry3d T_teach_model = Eigen::Isometry3d::Identity();
  /// Every model searched (several views of one part); `models[0]` is `model_name` and
  /// `T_teach_model` above. A file without "models" gives one entry from "model".
  std::vector<ResultModel> models;
  std::vector<ResultDetection> detections;
  std::optional<double> total_ms; ///< timings_ms.total, when present
};

/// Validates and converts a parsed results document. Required: format, version,
/// model.T_teach_model, detections (each with score and T_scene_model). Throws Error for missing
/// fields, non-finite numbers, non-rigid matrices, a score outside [0, 1] or a future version.
ResultsFile parseResults(const nlohmann::json& doc, const std::string& source);

/// Reads `path` (see parseResults; also throws Error for a missing or malformed file).
ResultsFile loadResults(const std::filesystem::path& path);

} // namespace scanpick::core::eval
