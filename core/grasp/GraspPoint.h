#pragma once
/// @file GraspPoint.h
/// A grip point with the direction the gripper comes from and, for fingers, the axis they close
/// along.

#include "core/cloud/PointCloud.h"
#include "core/common/GripPoint.h"

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::grasp {

/// Where and how the gripper takes the part, in the model frame (mm).
struct GraspPoint {
  std::string name;                                      ///< the grip point's name
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero(); ///< model frame
  /// Unit direction the tool moves in to reach the point (towards and into the part), model
  /// frame. Default +z: the teach camera's viewing direction, which looks at the taught side.
  Eigen::Vector3d approach = Eigen::Vector3d::UnitZ();
  /// Fingers: the unit axis they close along, model frame, perpendicular to `approach` (it is
  /// made so). Unset: any axis (suction cups); the planner picks one (toolPose()).
  std::optional<Eigen::Vector3d> closing_axis;
  bool operator==(const GraspPoint&) const = default;
};

/// A recipe's approach (and closing axis) for a grip point of the model, named.
struct GraspSpec {
  std::string grip;                                    ///< name of a model grip point
  Eigen::Vector3d approach = Eigen::Vector3d::UnitZ(); ///< model frame, any length > 0
  std::optional<Eigen::Vector3d> closing_axis;         ///< model frame, any length > 0
  bool operator==(const GraspSpec&) const = default;
};

/// The grasp points of a model: with no specs, every grip point with the approach and closing
/// axis taught with it (GripPoint; approach +z when it has none); otherwise one per spec, in the
/// specs' order, at its grip point's position, with the spec's approach and closing axis. The
/// directions are normalized (the closing axis made perpendicular to the approach). Throws Error
/// for a spec naming no grip point of the model ("grip 'x' is not a grip point of the model:
/// ..."), a zero or non-finite direction, or a closing axis along the approach.
std::vector<GraspPoint> graspPoints(const std::vector<GripPoint>& grips_model,
                                    const std::vector<GraspSpec>& specs);

/// How many scan points the default approach's plane is fitted to: enough to average a PhoXi's or
/// a Kinect's depth noise over a patch a few point spacings across.
inline constexpr std::size_t kSurfaceNeighbours = 30;

/// The approach a grip point placed at `point_mm` on `scan_mm` (a scan, camera frame: the camera at
/// the origin) gets by default: against the surface normal there, i.e. the normal of the plane
/// fitted to the kSurfaceNeighbours valid points nearest to it, turned away from the camera
/// (towards and into the part). Throws Error when the scan has fewer valid points than that or
/// they lie on a line.
Eigen::Vector3d surfaceApproach(const PointCloud& scan_mm, const Eigen::Vector3d& point_mm);

} // namespace scanpick::core::grasp
