#pragma once
// What the studies that start at the true pose share (study_icp_from_truth, study_render_pin): the
// part's views joined and prepared as recognize prepares them, the suite's scenes, the view the
// scan covers best at a true pose, and ICP from that pose.
#include "core/ambiguity/ModelPrep.h"
#include "core/common/Error.h"
#include "core/eval/GroundTruth.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "core/params/ViewParams.h"
#include "core/refine/PoseRefinement.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace scanpick::study {

using namespace scanpick::core;

inline double median(std::vector<double> values) {
  if (values.empty())
    return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// A part's views, joined, each prepared with `params` and its own view parameters.
struct PreparedViews {
  std::vector<std::shared_ptr<const TaughtModel>> views;
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps;
};

/// Loads the model files, joins them and prepares each. Throws Error for a view that does not know
/// its place in the part.
inline PreparedViews prepareViews(const std::vector<std::string>& model_files,
                                  const RecognitionParams& params) {
  PreparedViews out;
  for (const auto& file : model_files)
    out.views.push_back(std::make_shared<const TaughtModel>(loadModel(file)));
  requireOnePart(out.views);
  out.views = joinViews(out.views);
  std::vector<std::shared_ptr<const detail::ModelPrep>> cache;
  for (const auto& view : out.views) {
    if (!view->T_part_model)
      throw Error(view->teach_scan + " does not know its place in the part (teach it with "
                                     "--crop-from-truth or --part-pose)");
    out.preps.push_back(
        detail::prepareModel(cache, view, withViewParams(params, view->view_params)));
  }
  return out;
}

/// The suite's scans (SUITE_DIR/*.pcd), sorted.
inline std::vector<std::filesystem::path> sceneFiles(const std::filesystem::path& suite) {
  std::vector<std::filesystem::path> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(suite))
    if (entry.path().extension() == ".pcd")
      scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

/// The ground truth beside a scan (scene-000.pcd → scene-000.gt.json).
inline eval::GroundTruth truthOf(std::filesystem::path scene) {
  scene.replace_extension(".gt.json");
  return eval::loadGroundTruth(scene);
}

/// The scan indexed as recognize indexes it for ICP.
inline SceneIndex sceneIndexFor(const PointCloud& cloud, const eval::GroundTruth& truth,
                                const RecognitionParams& params) {
  SceneIndexOptions options;
  options.normal_radius_mm = params.keypoints.normal_radius_mm;
  options.sensor = sensorPreset(truth.sensor_preset.empty() ? "phoxi-m-1032" : truth.sensor_preset);
  return SceneIndex(cloud, options);
}

/// The view whose own points the scan covers best with the part at T_scene_part: the one
/// recognition would find the instance with.
inline std::size_t bestView(const PreparedViews& v, const SceneIndex& index,
                            const Eigen::Isometry3d& T_scene_part,
                            const RecognitionParams& params) {
  std::size_t best = 0;
  double best_coverage = -1.0;
  for (std::size_t k = 0; k < v.views.size(); ++k) {
    const double coverage =
        coverageScore(*v.preps[k]->refine, index, T_scene_part * *v.views[k]->T_part_model,
                      params.matching.verify_tolerance_mm);
    if (coverage > best_coverage) {
      best_coverage = coverage;
      best = k;
    }
  }
  return best;
}

/// ICP of view `view` from the pose T_scene_model_true, as recognize refines (views joined).
inline RefinementResult refineFrom(const PreparedViews& v, std::size_t view,
                                   const SceneIndex& index,
                                   const Eigen::Isometry3d& T_scene_model_true,
                                   const RecognitionParams& params) {
  const detail::ModelPrep& prep = *v.preps[view];
  return refinePose(prep.joined_refine ? *prep.joined_refine : *prep.refine, index,
                    T_scene_model_true, params.refine);
}

/// A study's main(): `run`, with an exception reported as "NAME: what it says" and exit code 1.
inline int studyMain(const char* name, int (*run)(int, char**), int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

} // namespace scanpick::study
