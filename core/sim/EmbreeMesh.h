#pragma once
/// @file EmbreeMesh.h
/// A triangle mesh handed to Embree (the ray tracer the simulator renders with), for the renderer
/// and for studies that render a model themselves.

#include "core/sim/Mesh.h"

#include <embree3/rtcore.h>

namespace scanpick::core {

/// Copies `mesh_mm` (vertices and triangles as they are, in the scene's frame) into a new triangle
/// geometry of `device`, commits it and attaches it to `scene`. Returns the geometry's id in
/// `scene`; the scene itself is not committed.
unsigned attachTriangleMesh(RTCDevice device, RTCScene scene, const TriangleMesh& mesh_mm);

} // namespace scanpick::core
