#pragma once
/// @file PartCatalog.h
/// Built-in procedural parts modelled on the thesis objects, and parts loaded from mesh files.

#include "core/sim/Part.h"

#include <filesystem>
#include <string>
#include <vector>

namespace scanpick::core {

/// Names of the built-in parts: "support", "cup", "pump-connector", "coat-rack".
std::vector<std::string> builtInPartNames();

/// A built-in part:
/// - `support`: an L-shaped square bracket, two 80 × 80 × 5 mm legs with two Ø12 mm holes each
///   and a triangular gusset; one 180° symmetry swapping the legs.
/// - `cup`: Ø80 × 95 mm cup (3 mm wall) with a handle; no symmetry.
/// - `pump-connector`: a 100 mm pipe (Ø40 outside, Ø24 bore) with two equal Ø90 × 8 mm flanges
///   with four Ø10 mm bolt holes; 90° symmetry about its axis and the end-to-end flip (7
///   transforms).
/// - `coat-rack`: a 60 × 30 × 4 mm plate with two Ø10 mm holes, an L hook and a suction cup.
/// - `random-<seed>`: the generated part of that seed (randomPart, core/sim/RandomPart.h).
/// Throws Error listing the names for an unknown one.
Part builtInPart(const std::string& name);

/// A part from a mesh file in millimetres (see loadMesh): no grip points except the bounding-box
/// centre ("center"), no known symmetry. With `close_holes`, the holes of a scanned mesh (an open
/// base) are capped first (closeHoles). Throws Error if the mesh is not closed (it names the
/// number of open edges) or empty, or if loading or closing fails.
Part partFromMeshFile(const std::filesystem::path& path, bool close_holes = false);

} // namespace scanpick::core
