#pragma once
// Ground truth and results built in code for the evaluator's tests.
#include "core/eval/GroundTruth.h"
#include "core/eval/ResultsFile.h"

#include <Eigen/Geometry>
#include <numbers>
#include <string>

namespace scanpick::test {

inline double degToRad(double deg) {
  return deg * std::numbers::pi / 180.0;
}

/// Pose from a translation (mm) and a rotation of `angle_deg` about `axis`.
inline Eigen::Isometry3d pose(const Eigen::Vector3d& t_mm, double angle_deg = 0.0,
                              const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(degToRad(angle_deg), axis.normalized()).toRotationMatrix();
  T.translation() = t_mm;
  return T;
}

/// A part of `diameter_mm` with one grip point 20 mm above its origin and no symmetry.
inline core::eval::PartInfo makePart(const std::string& name, double diameter_mm) {
  core::eval::PartInfo part;
  part.name = name;
  part.diameter_mm = diameter_mm;
  part.grip_points_part.push_back({"top", Eigen::Vector3d(0, 0, 20)});
  return part;
}

/// The teach scene: one instance of `part` at a fixed, non-trivial pose.
inline core::eval::GroundTruth makeTeachTruth(const core::eval::PartInfo& part) {
  core::eval::GroundTruth teach;
  teach.source = "teach (test)";
  teach.kind = "teach";
  teach.parts[part.name] = part;
  teach.instances.push_back(
      {0, part.name, pose({5, -3, 700}, 30, Eigen::Vector3d(1, 2, 3)), 1.0, 5000});
  return teach;
}

/// The model frame the "recognizer" chose inside the teach scan (arbitrary, like a centroid).
inline Eigen::Isometry3d testTeachModel() {
  return pose({2, 4, 690}, -15, Eigen::Vector3d(0, 1, 1));
}

/// The T_scene_model a perfect recognizer reports for a part at `T_scene_part`: the inverse of
/// T_scene_part = T_scene_model · T_teach_model⁻¹ · T_teach_part.
inline Eigen::Isometry3d modelPoseFor(const Eigen::Isometry3d& T_scene_part,
                                      const core::eval::GroundTruth& teach) {
  return T_scene_part * teach.instances.front().T_scene_part.inverse() * testTeachModel();
}

inline core::eval::ResultsFile makeResults() {
  core::eval::ResultsFile results;
  results.source = "results (test)";
  results.T_teach_model = testTeachModel();
  return results;
}

inline void addDetection(core::eval::ResultsFile& results, double score,
                         const Eigen::Isometry3d& T_scene_part,
                         const core::eval::GroundTruth& teach) {
  core::eval::ResultDetection d;
  d.id = static_cast<int>(results.detections.size());
  d.score = score;
  d.T_scene_model = modelPoseFor(T_scene_part, teach);
  results.detections.push_back(d);
}

} // namespace scanpick::test
