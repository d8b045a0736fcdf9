#pragma once
/// @file ModelViews.h
/// Loading the --model options of recognize and bench: one model, or several views of one part.

#include "core/common/Error.h"
#include "core/model/ModelFile.h"
#include "core/output/ResultsJson.h"

#include <memory>
#include <string>
#include <vector>

namespace scanpick::cli {

/// Every model given (views of one part), with what the results and pictures need of them.
struct ModelViews {
  std::vector<std::shared_ptr<const core::TaughtModel>> models;
  std::vector<core::ModelSource> sources;
  std::vector<const core::PointCloud*> clouds;
};

/// Loads `paths` (at least one) and joins the views that know their place in the part
/// (core::joinViews). Throws core::Error for a file that does not load, or for models of
/// different parts (several --model must be views of one part).
inline ModelViews loadModelViews(const std::vector<std::string>& paths) {
  if (paths.empty())
    throw core::Error("--model is required");
  ModelViews out;
  for (const auto& path : paths)
    out.models.push_back(std::make_shared<const core::TaughtModel>(core::loadModel(path)));
  core::requireOnePart(out.models);
  out.models = core::joinViews(out.models);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    out.sources.push_back({out.models[i].get(), paths[i]});
    out.clouds.push_back(&out.models[i]->cloud_mm);
  }
  return out;
}

/// The sensor preset for the run: `given`, else the (first) model's, else PhoXi M 1032.
inline std::string sensorNameFor(const std::string& given, const core::TaughtModel& model) {
  if (!given.empty())
    return given;
  return model.sensor.preset.empty() || model.sensor.preset == "custom" ? "phoxi-m-1032"
                                                                        : model.sensor.preset;
}

} // namespace scanpick::cli
