#pragma once
/// @file EvalTruth.h
/// Integration-test helpers: a virtual scene's part and pose errors as `scanpick-cli eval` scores
/// them (core/eval), for tests that check detections against the scene they were made from.

#include "core/eval/GroundTruth.h"
#include "core/eval/PoseError.h"
#include "core/sim/Synth.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace scanpick::test {

/// A part of a virtual scene as eval knows it: read back from the ground truth the scene writes
/// (its design diameter, grip points and symmetries), with its symmetry group.
struct ScoredPart {
  core::eval::PartInfo info;
  std::vector<Eigen::Isometry3d> symmetries; ///< symmetryGroup of info
};

inline ScoredPart scoredPart(const core::SynthScene& scene, const std::string& name) {
  ScoredPart out;
  out.info = core::eval::parseGroundTruth(
                 nlohmann::json::parse(core::groundTruthJson(scene, "s.pcd", "s.png")), "scene")
                 .parts.at(name);
  out.symmetries = core::eval::symmetryGroup(out.info.symmetry, out.info.diameter_mm);
  return out;
}

/// Rotation of a part pose estimate from the true one, up to the part's symmetries (degrees), as
/// eval measures it.
inline double rotationErrorDeg(const Eigen::Isometry3d& T_scene_part_est,
                               const Eigen::Isometry3d& T_scene_part_true, const ScoredPart& part) {
  return core::eval::symmetricPoseError(T_scene_part_est, T_scene_part_true, part.info,
                                        part.symmetries, {})
      .rotation_deg;
}

} // namespace scanpick::test
