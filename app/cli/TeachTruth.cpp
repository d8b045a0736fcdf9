#include "app/cli/TeachTruth.h"

#include "core/common/Error.h"
#include "core/eval/GroundTruth.h"

namespace scanpick::cli {

void teachOptionsFromTruth(const std::filesystem::path& truth_path, core::TeachOptions& options) {
  const core::eval::GroundTruth truth = core::eval::loadGroundTruth(truth_path);
  if (!truth.crop_box)
    throw core::Error(truth.source +
                      " has no crop_box: use a teach scene's .gt.json or --crop-box");
  const core::eval::TruthCropBox& box = *truth.crop_box;
  core::OrientedBox oriented;
  oriented.T_scan_box =
      (box.T_scene_box * Eigen::Translation3d(0.5 * (box.min_mm + box.max_mm))).cast<float>();
  oriented.half_extents_mm = (0.5 * (box.max_mm - box.min_mm)).cast<float>();
  options.crop_oriented = oriented;
  if (truth.instances.size() == 1)
    options.T_scan_part = truth.instances.front().T_scene_part;
  if (options.grips_scan.empty() && !truth.instances.empty())
    for (const auto& grip : truth.instances.front().grip_points_scene)
      options.grips_scan.push_back({grip.name, grip.position_mm});
}

} // namespace scanpick::cli
