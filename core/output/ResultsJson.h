#pragma once
/// @file ResultsJson.h
/// The results file ("scanpick-results", docs/file-formats.md). The reader is
/// core/eval/ResultsFile.h (loadResults), which the evaluator shares.
///
/// Module core/output (scanpick::core_output), what is made from a result. Contract: it reads a
/// RecognitionResult (or detections and their scan) and makes what leaves the library with it:
/// this results file, the depth overlay (DepthOverlay.h), the result picture (OverlayPicture.h)
/// and the colours that tell detections apart (DetectionColours.h). It changes nothing of the
/// result; recognition does not use it. It uses the pipeline; OpenCV, which draws and encodes the
/// picture, stays private to it.

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

/// Writes resultsToJson(result, models, scene_path) to `path` atomically. Throws Error on failure.
void saveResults(const std::filesystem::path& path, const RecognitionResult& result,
                 const std::vector<ModelSource>& models, const std::string& scene_path);

} // namespace scanpick::core
