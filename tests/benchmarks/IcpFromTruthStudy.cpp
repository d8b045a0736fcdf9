// Where ICP settles when it starts at the true pose: the floor the scans and the part's shape set
// for refinement, whatever pose the matching hands it (docs/design-notes-refinement.md).
//
//   study_icp_from_truth SUITE_DIR PART PRESET.json MODEL.spmodel [MODEL.spmodel ...]
//
// For every instance of PART at least 50 % visible in SUITE_DIR/scene-*.gt.json, the view whose
// own points the scan covers best at the true pose is refined from that pose, as recognize does
// with `--preset PRESET --set refine.enabled=true` (views that know their place in the part are
// joined, and ICP fits all of them). Prints each instance's error at the model origin and the
// medians. Not a test: run it by hand and write the figures in the docs.
#include "FromTruthStudy.h"
#include "core/cloud/CloudIo.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace scanpick::core;
using namespace scanpick::study;

namespace {

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
  const PreparedViews views = prepareViews({argv + 4, argv + argc}, params);

  std::vector<double> origin_mm, rotation_deg;
  for (const auto& scene : sceneFiles(suite)) {
    const auto truth = truthOf(scene);
    const PointCloud cloud = loadCloud(scene, LengthUnit::Millimetres).cloud;
    const SceneIndex index = sceneIndexFor(cloud, truth, params);
    for (const auto& instance : truth.instances) {
      if (instance.part != part || instance.visible_fraction < 0.5)
        continue;
      const std::size_t best = bestView(views, index, instance.T_scene_part, params);
      const Eigen::Isometry3d T_true = instance.T_scene_part * *views.views[best]->T_part_model;
      const RefinementResult r = refineFrom(views, best, index, T_true, params);
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
  return scanpick::study::studyMain("study_icp_from_truth", run, argc, argv);
}
