// Where ICP settles when it starts at the true pose: the floor the scans and the part's shape set
// for refinement, whatever pose the matching hands it (docs/accuracy.md, "ICP").
//
//   study_icp_from_truth SUITE_DIR PART PRESET.json MODEL.spmodel [MODEL.spmodel ...]
//
// For every instance of PART at least 50 % visible in SUITE_DIR/scene-*.gt.json, the view whose
// own points the scan covers best at the true pose is refined from that pose, as recognize does
// with `--preset PRESET --set refine.enabled=true` (views that know their place in the part are
// joined, and ICP fits all of them). Prints each instance's error at the model origin and the
// medians. Not a test: run it by hand and write the figures in the docs.
#include "core/cloud/CloudIo.h"
#include "core/common/Error.h"
#include "core/eval/GroundTruth.h"
#include "core/model/ModelFile.h"
#include "core/params/ParamsJson.h"
#include "core/params/ViewParams.h"
#include "core/pipeline/ModelPrep.h"
#include "core/refine/PoseRefinement.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace scanpick::core;

namespace {

double median(std::vector<double> values) {
  if (values.empty())
    return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

int run(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s SUITE_DIR PART PRESET.json MODEL.spmodel [MODEL.spmodel ...]\n",
                 argv[0]);
    return 2;
  }
  const fs::path suite = argv[1];
  const std::string part = argv[2];
  RecognitionParams params = loadPreset(argv[3]).params;
  params.refine.enabled = true;
  std::vector<std::shared_ptr<const TaughtModel>> views;
  for (int a = 4; a < argc; ++a)
    views.push_back(std::make_shared<const TaughtModel>(loadModel(argv[a])));
  requireOnePart(views);
  views = joinViews(views);
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps, cache;
  for (const auto& view : views) {
    if (!view->T_part_model)
      throw Error(view->teach_scan + " does not know its place in the part (teach it with "
                                     "--crop-from-truth or --part-pose)");
    preps.push_back(detail::prepareModel(cache, view, withViewParams(params, view->view_params)));
  }

  std::vector<double> origin_mm, rotation_deg;
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(suite))
    if (entry.path().extension() == ".pcd")
      scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  for (const auto& scene : scenes) {
    fs::path truth_path = scene;
    truth_path.replace_extension(".gt.json");
    const auto truth = eval::loadGroundTruth(truth_path);
    const PointCloud cloud = loadCloud(scene, LengthUnit::Millimetres).cloud;
    SceneIndexOptions options;
    options.normal_radius_mm = params.keypoints.normal_radius_mm;
    options.sensor =
        sensorPreset(truth.sensor_preset.empty() ? "phoxi-m-1032" : truth.sensor_preset);
    const SceneIndex index(cloud, options);
    for (const auto& instance : truth.instances) {
      if (instance.part != part || instance.visible_fraction < 0.5)
        continue;
      // The view the scan covers best at the true pose: the one recognition would find it with.
      std::size_t best = 0;
      double best_coverage = -1.0;
      for (std::size_t v = 0; v < views.size(); ++v) {
        const double coverage =
            coverageScore(*preps[v]->refine, index, instance.T_scene_part * *views[v]->T_part_model,
                          params.matching.verify_tolerance_mm);
        if (coverage > best_coverage) {
          best_coverage = coverage;
          best = v;
        }
      }
      const detail::ModelPrep& prep = *preps[best];
      const Eigen::Isometry3d T_true = instance.T_scene_part * *views[best]->T_part_model;
      const RefinementResult r = refinePose(prep.joined_refine ? *prep.joined_refine : *prep.refine,
                                            index, T_true, params.refine);
      const Eigen::Isometry3d error = T_true.inverse() * r.T_scene_model;
      origin_mm.push_back(error.translation().norm());
      rotation_deg.push_back(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / std::numbers::pi);
      std::printf("%s instance %d (visible %.2f, view %zu): %.3f mm, %.3f deg, %d iterations\n",
                  scene.stem().c_str(), instance.id, instance.visible_fraction, best,
                  origin_mm.back(), rotation_deg.back(), r.iterations);
    }
  }
  std::printf("%s: %zu instances, median %.3f mm, %.3f deg from the true pose\n", part.c_str(),
              origin_mm.size(), median(origin_mm), median(rotation_deg));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "study_icp_from_truth: %s\n", e.what());
    return 1;
  }
}
