#pragma once
/// @file ResultsJson.h
/// The results file ("scanpick-results", docs/file-formats.md). The reader is
/// core/eval/ResultsFile.h (loadResults), which the evaluator shares.

#include "core/model/TaughtModel.h"
#include "core/pipeline/Recognizer.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace scanpick::core {

/// Version of the results format written here.
inline constexpr int kResultsFormatVersion = 1;

/// A model searched, with the file it was loaded from (stored as given).
struct ModelSource {
  const TaughtModel* model = nullptr;
  std::string path;
};

/// The results document of one recognition of one or more models (views of one part;
/// Detection::model_index refers to `models`). `scene_path` is stored as given. The first model
/// is also written as "model", for readers of single-model files.
nlohmann::json resultsToJson(const RecognitionResult& result,
                             const std::vector<ModelSource>& models, const std::string& scene_path);

/// The results document of one recognition of one model.
nlohmann::json resultsToJson(const RecognitionResult& result, const TaughtModel& model,
                             const std::string& scene_path, const std::string& model_path);

/// Writes resultsToJson(result, models, scene_path) to `path` atomically. Throws Error on failure.
void saveResults(const std::filesystem::path& path, const RecognitionResult& result,
                 const std::vector<ModelSource>& models, const std::string& scene_path);

/// Writes resultsToJson(...) to `path` atomically (pretty-printed). Throws Error on failure.
void saveResults(const std::filesystem::path& path, const RecognitionResult& result,
                 const TaughtModel& model, const std::string& scene_path,
                 const std::string& model_path);

} // namespace scanpick::core
