#pragma once
/// @file TaughtPoseError.h
/// Integration-test helper: how far a pose found in the very scan a model was taught from lies
/// from the pose it was taught in (TaughtModel::T_teach_model, a pure translation to the
/// centroid), for tests on real scans whose only ground truth is the teach scan itself.

#include "core/model/TaughtModel.h"

#include <Eigen/Geometry>
#include <cmath>

namespace scanpick::test {

/// Translation (mm) and rotation (degrees) of a found pose off the taught one.
struct TaughtPoseError {
  double translation_mm = 0.0;
  double rotation_deg = 0.0;
};

/// The error of `T_scene_model`, found in `model`'s own teach scan, against the pose it was
/// taught in: the distance between the origins, and the angle of its rotation (the taught pose
/// has none).
inline TaughtPoseError taughtPoseError(const Eigen::Isometry3d& T_scene_model,
                                       const core::TaughtModel& model) {
  TaughtPoseError error;
  error.translation_mm = (T_scene_model.translation() - model.T_teach_model.translation()).norm();
  error.rotation_deg = Eigen::AngleAxisd(T_scene_model.linear()).angle() * 180.0 / M_PI;
  return error;
}

} // namespace scanpick::test
