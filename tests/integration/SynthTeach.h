#pragma once
// Helpers of the integration tests: load a bundled preset, teach a built-in part from a virtual
// teach scan, find a taught view's near symmetries, and tell which simulated instance a detection
// lies on.
#include "core/ambiguity/NearSymmetry.h"
#include "core/common/Detection.h"
#include "core/model/TaughtModel.h"
#include "core/params/ParamsJson.h"
#include "core/preprocess/FloorRemoval.h"
#include "core/refine/RefineModel.h"
#include "core/sim/Synth.h"
#include "core/verification/PoseVerification.h"

#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace scanpick::test {

/// The parameters of the bundled preset `name` (resources/presets/NAME.json).
inline core::RecognitionParams bundledPreset(const std::string& name) {
  return core::loadPreset(std::filesystem::path(SCANPICK_SOURCE_DIR) / "resources/presets" /
                          (name + ".json"))
      .params;
}

/// A model taught from one part on a table (resting on side `teach_side`, see
/// core::teachSideTurn), cropped with the box an operator would draw, and the part's pose in that
/// teach scan.
struct SynthTeach {
  std::shared_ptr<core::TaughtModel> model;
  Eigen::Isometry3d T_teach_part = Eigen::Isometry3d::Identity();
  /// The model frame → the part frame.
  Eigen::Isometry3d T_part_model() const { return T_teach_part.inverse() * model->T_teach_model; }
};

/// A virtual teach scan: one `part` alone on a table, resting on side `teach_side`.
inline core::SynthScene teachScan(const std::string& part, std::uint64_t seed, int teach_side) {
  core::SynthRequest request;
  request.parts = {part};
  request.layout = core::LayoutKind::Teach;
  request.count = 1;
  request.seed = seed;
  request.teach_side = teach_side;
  return core::synthesize(request);
}

/// How the only part of a virtual scan is taught: cropped to the box of its ground truth, the
/// floor removed, its pose known.
inline core::TeachOptions teachOptionsFor(const core::SynthScene& scan, const std::string& name) {
  core::TeachOptions options;
  options.name = name;
  options.sensor = scan.sensor;
  options.remove_floor = true;
  const Eigen::AlignedBox3d box = scan.scene.crop_box_world.value();
  core::OrientedBox crop;
  crop.T_scan_box = (scan.scene.T_camera_world * Eigen::Translation3d(box.center())).cast<float>();
  crop.half_extents_mm = (0.5 * box.sizes()).cast<float>();
  options.crop_oriented = crop;
  // The part's pose in the scan, as `teach --crop-from-truth` reads it: views can be joined.
  options.T_scan_part = scan.scene.T_scene_part(scan.scene.instances.at(0));
  return options;
}

/// A model taught from the only part of a virtual scan (teachOptionsFor).
inline SynthTeach teachFromScan(const core::SynthScene& scan, const std::string& name,
                                const core::RecognitionParams& params) {
  SynthTeach out;
  out.model = std::make_shared<core::TaughtModel>(
      core::teach(scan.render.cloud, teachOptionsFor(scan, name), params));
  out.T_teach_part = scan.scene.T_scene_part(scan.scene.instances.at(0));
  return out;
}

inline SynthTeach teachFromSynth(const std::string& part, std::uint64_t seed,
                                 const core::RecognitionParams& params, int teach_side = 0) {
  return teachFromScan(teachScan(part, seed, teach_side), part, params);
}

/// A view taught from one teach scan and verified against another scan of the part resting the
/// same way: the true pose of the view in it, and what verification needs of that scan.
struct VerifyCase {
  SynthTeach taught;
  core::SynthScene scan;
  Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity(); ///< scene ← model
  core::FloorRemovalResult floor;
  std::shared_ptr<const core::VerifyModel> view;
  std::shared_ptr<const core::SceneIndex> index; ///< of the scan less its floor
};

inline VerifyCase verifyCase(const std::string& part, const core::RecognitionParams& params,
                             std::uint64_t teach_seed, std::uint64_t scan_seed, int side) {
  VerifyCase c;
  c.taught = teachFromSynth(part, teach_seed, params, side);
  c.scan = teachScan(part, scan_seed, side);
  c.T_true = c.scan.scene.T_scene_part(c.scan.scene.instances.at(0)) * c.taught.T_part_model();
  c.floor = core::removeFloor(c.scan.render.cloud, params.floor, params.seed);
  c.view = core::makeVerifyModel(*c.taught.model, params.refine.model_points,
                                 params.keypoints.normal_radius_mm);
  c.index = std::make_shared<const core::SceneIndex>(c.floor.remaining);
  return c;
}

/// The instance nearest a detection's part origin (as scanpick-cli eval places it).
struct NearestInstance {
  int id = -1;
  std::string part;
  double distance_mm = std::numeric_limits<double>::max();
};

inline NearestInstance nearestInstance(const core::Detection& d, const SynthTeach& taught,
                                       const core::Scene& scene) {
  const Eigen::Isometry3d T_scene_part = d.T_scene_model * taught.T_part_model().inverse();
  NearestInstance out;
  for (const auto& instance : scene.instances) {
    const double dist =
        (scene.T_scene_part(instance).translation() - T_scene_part.translation()).norm();
    if (dist < out.distance_mm)
      out = {instance.id, scene.parts.at(instance.part).name, dist};
  }
  return out;
}

/// A taught view's verification points and its near symmetries, as the recognizer finds them.
struct ViewSymmetries {
  std::shared_ptr<const core::VerifyModel> view;
  std::vector<core::NearSymmetry> found;
};

inline ViewSymmetries symmetriesOf(const core::TaughtModel& model,
                                   const core::RecognitionParams& params) {
  ViewSymmetries out;
  out.view =
      core::makeVerifyModel(model, params.refine.model_points, params.keypoints.normal_radius_mm);
  const core::RefineModel refine(model.cloud_mm, params.refine.model_points,
                                 Eigen::Vector3d(model.T_teach_model.inverse().translation()));
  out.found = core::findNearSymmetries(model, *out.view, refine, params.refine,
                                       params.matching.verify_tolerance_mm,
                                       params.matching.symmetry_overlap);
  return out;
}

} // namespace scanpick::test
