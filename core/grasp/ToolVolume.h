#pragma once
/// @file ToolVolume.h
/// The space a gripper takes on its way to a grasp: its solids (Gripper.h) swept along the
/// straight approach, as the planner checks them, for checks against other geometry than a scan
/// (the true meshes of a simulated bin, PickJudge.h).

#include "core/grasp/Gripper.h"

#include <Eigen/Geometry>
#include <vector>

namespace scanpick::core::grasp {

/// `solid` (tool frame, mm) swept from `length` mm back along the tool's z axis to where it is,
/// grown by `clearance` mm all round: the space it takes on a straight approach.
ToolSolid sweptSolid(const ToolSolid& solid, double length, double clearance);

/// The gripper's solids (toolSolids()) swept from `approach_length_mm` back along the tool's z
/// axis to the grasp, each grown by `clearance_mm` all round; tool frame, mm. Throws Error as
/// toolSolids() does.
std::vector<ToolSolid> sweptToolSolids(const Gripper& gripper, double approach_length_mm,
                                       double clearance_mm = 0.0);

/// Whether `p_tool` (tool frame, mm) lies inside `solid` (its boundary included).
bool insideSolid(const ToolSolid& solid, const Eigen::Vector3d& p_tool);

/// Axis-aligned bounds, in the frame T_frame_tool maps into, of `solid`.
Eigen::AlignedBox3d solidBounds(const ToolSolid& solid, const Eigen::Isometry3d& T_frame_tool);

/// Points on the surface of `solid` (tool frame, mm) no farther than `spacing` mm apart: a grid on
/// each face of a box; on a cylinder, lines along its mantle and rings on its ends. Throws Error
/// for a spacing that is not positive.
std::vector<Eigen::Vector3d> solidSurfaceSamples(const ToolSolid& solid, double spacing);

} // namespace scanpick::core::grasp
