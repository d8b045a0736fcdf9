#pragma once
/// @file MeshBuilder.h
/// Closed (watertight) primitive solids from which the procedural parts are assembled: boxes,
/// solids of revolution, plates with round holes, and bent round bars.

#include "core/sim/Mesh.h"

#include <vector>

namespace scanpick::core {

/// Axis-aligned box between `min_mm` and `max_mm`.
TriangleMesh boxMesh(const Eigen::Vector3d& min_mm, const Eigen::Vector3d& max_mm);

/// Revolves a closed profile around the z axis. `profile_rz` is a simple polygon in the
/// (radius, z) half-plane (r >= 0; vertices with r == 0 lie on the axis), `segments` >= 3.
TriangleMesh revolveProfile(const std::vector<Eigen::Vector2d>& profile_rz, int segments);

/// One cell of a plate's outline: a closed polygon, star-shaped around `center`, optionally with a
/// round hole of `hole_radius_mm` (0 = none) centred there. Neighbouring cells must share the
/// vertices of their common sides (see rectangleCells / sectorCells).
struct PlateCell {
  std::vector<Eigen::Vector2d> boundary_mm; ///< counter-clockwise, not repeated at the end
  Eigen::Vector2d center_mm = Eigen::Vector2d::Zero();
  double hole_radius_mm = 0;
};

/// Cells tiling the rectangle [x0, x1] × [y0, y1] in `nx` × `ny` squares-ish cells, each side cut
/// in `per_side` segments; no holes (set hole_radius_mm on the cells that need one).
std::vector<PlateCell> rectangleCells(double x0, double x1, double y0, double y1, int nx, int ny,
                                      int per_side);

/// Cells tiling the annulus r_in..r_out in `sectors` equal sectors (the first starting at angle
/// `start_rad`), arcs sampled with `arc_segments` per sector; centre at mid-radius.
std::vector<PlateCell> sectorCells(double r_in_mm, double r_out_mm, int sectors, int arc_segments,
                                   double start_rad, double center_radius_mm);

/// Extrudes the union of `cells` between z0 and z1 into a closed solid; holes get round walls
/// with `hole_segments` segments.
TriangleMesh extrudeCells(const std::vector<PlateCell>& cells, double z0_mm, double z1_mm,
                          int hole_segments);

/// A round bar of radius `bar_radius_mm` bent along the arc of radius `arc_radius_mm` around
/// `center_mm` in the plane spanned by unit vectors `u` (angle 0) and `v` (angle 90°), from
/// `angle0_rad` to `angle1_rad`, with flat end caps.
TriangleMesh bentBar(const Eigen::Vector3d& center_mm, const Eigen::Vector3d& u,
                     const Eigen::Vector3d& v, double arc_radius_mm, double bar_radius_mm,
                     double angle0_rad, double angle1_rad, int arc_segments, int bar_segments);

/// Flips all triangles if the mesh's signed volume is negative, so normals point outwards.
void orientOutwards(TriangleMesh& mesh);

} // namespace scanpick::core
