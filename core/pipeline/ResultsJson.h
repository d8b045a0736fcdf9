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

/// The results document of one recognition. `scene_path` and `model_path` are stored as given.
nlohmann::json resultsToJson(const RecognitionResult& result, const TaughtModel& model,
                             const std::string& scene_path, const std::string& model_path);

/// Writes resultsToJson(...) to `path` atomically (pretty-printed). Throws Error on failure.
void saveResults(const std::filesystem::path& path, const RecognitionResult& result,
                 const TaughtModel& model, const std::string& scene_path,
                 const std::string& model_path);

} // namespace scanpick::core
