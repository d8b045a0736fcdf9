#pragma once
/// @file SelfOcclusion.h
/// Which points of a model seen from every side its own body hides from the camera at a pose: a
/// bracket's inner face behind its other leg, a flange's seat under its hub. A scan cannot show
/// them whatever else lies in the bin, so verification does not expect them.

#include <Eigen/Geometry>
#include <vector>

namespace scanpick::core {

/// For each of `points_model` (model frame, mm; samples of the part's surface about `spacing_mm`
/// apart) at pose `T_scene_model`, with the camera at the scene origin: 1 when another of the
/// points lies more than `margin_mm` nearer the camera on its line of sight, within a cone of
/// 1.5 x `spacing_mm` across at the part's distance (so that the samples of a surface leave no
/// gaps between them); else 0. All 0 when `spacing_mm` is not positive, when a point lies behind
/// the camera, or when the part spans more than 4 million such cones.
std::vector<char> selfHidden(const std::vector<Eigen::Vector3f>& points_model,
                             const Eigen::Isometry3f& T_scene_model, double spacing_mm,
                             float margin_mm);

} // namespace scanpick::core
