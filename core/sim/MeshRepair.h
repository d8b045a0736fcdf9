#pragma once
/// @file MeshRepair.h
/// Closing the holes of scanned meshes (an open base, a cut) so that they can stand as solids.

#include "core/sim/Mesh.h"

#include <cstddef>

namespace scanpick::core {

/// What closeHoles did.
struct HoleFilling {
  std::size_t holes = 0;      ///< boundary loops closed
  std::size_t triangles = 0;  ///< triangles added
  double largest_hole_mm = 0; ///< the largest closed loop's extent across, mm
};

/// Closes every boundary loop of `mesh` (edges used by one triangle only) with a cap: the loop is
/// triangulated in 3D by CGAL's hole filling (triangulate_hole_polyline: least area and dihedral
/// angles), with the caps oriented like the triangles around them. No vertices are added. Throws
/// Error, leaving `mesh` unchanged, when a boundary is not a set of simple loops (a vertex on
/// several holes, a non-manifold edge) or a loop cannot be capped (it folds over itself).
HoleFilling closeHoles(TriangleMesh& mesh);

} // namespace scanpick::core
