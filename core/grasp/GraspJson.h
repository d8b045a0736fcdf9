#pragma once
/// @file GraspJson.h
/// The grasp planning part of a recipe in JSON (gripper, grasps, planning, bin) and the pick list
/// as JSON. docs/grasping.md documents the keys.

#include "core/grasp/BinBox.h"
#include "core/grasp/GraspPlanner.h"
#include "core/grasp/Gripper.h"

#include <nlohmann/json.hpp>
#include <vector>

namespace scanpick::core::grasp {

/// Reads a gripper: {"kind": "suction"|"fingers", "suction": {...}, "fingers": {...}, "body":
/// {"shape": "cylinder"|"box", ...}}; missing keys keep their defaults. Throws Error naming the
/// key for a wrong type, an unknown name or an unknown key (a typo would silently keep a
/// default), and for bad dimensions (toolSolids()).
Gripper gripperFromJson(const nlohmann::json& j);
nlohmann::json toJson(const Gripper& gripper);

/// Reads grasp specs: [{"grip": NAME, "approach": [x, y, z], "closing_axis": [x, y, z]}, ...]
/// (approach default [0, 0, 1], closing axis optional). Throws Error as gripperFromJson.
std::vector<GraspSpec> graspSpecsFromJson(const nlohmann::json& j);

/// Reads planning parameters over `base` (keys as GraspPlanParams' members; "order" by name,
/// "up" as [x, y, z]). Throws Error as gripperFromJson.
GraspPlanParams planParamsFromJson(const nlohmann::json& j, const GraspPlanParams& base = {});
nlohmann::json toJson(const GraspPlanParams& params);

/// Reads bin estimation parameters over `base` ("up", "distance_mm", ...).
BinEstimateParams binParamsFromJson(const nlohmann::json& j, const BinEstimateParams& base = {});

/// A candidate: detection, grip, tool and pre-grasp poses (position mm, quaternion w x y z),
/// tilt, height, occlusion, score, and for a rejected one its reasons [{"kind", "detail"}].
nlohmann::json toJson(const GraspCandidate& candidate);
/// {"picks": [...], "rejected": [...]}
nlohmann::json toJson(const PickList& list);

} // namespace scanpick::core::grasp
