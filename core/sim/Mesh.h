#pragma once
/// @file Mesh.h
/// Triangle meshes in millimetres for the virtual scanner: parts, bins and tables.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace scanpick::core {

/// An indexed triangle mesh in millimetres. Triangles are counter-clockwise seen from outside
/// (their right-hand normal points out of the solid).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_mm; ///< vertex positions, millimetres
  std::vector<Eigen::Vector3i> triangles;   ///< vertex indices, outward orientation

  [[nodiscard]] bool empty() const { return triangles.empty(); }
  /// Appends `other` (its indices shifted).
  void append(const TriangleMesh& other);
};

/// `mesh` with every vertex mapped by `T` (millimetres).
TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& T);

/// All meshes in one (no welding).
TriangleMesh merged(const std::vector<TriangleMesh>& meshes);

/// Axis-aligned bounding box of the vertices (empty box for an empty mesh).
Eigen::AlignedBox3d boundingBox(const TriangleMesh& mesh);

/// Total triangle area, mm².
double surfaceArea(const TriangleMesh& mesh);

/// Merges vertices closer than `tolerance_mm` (grid hashing; deterministic) and drops triangles
/// that become degenerate.
TriangleMesh welded(const TriangleMesh& mesh, double tolerance_mm = 1e-6);

/// Number of undirected edges not shared by exactly two triangles of opposite orientation.
/// 0 means the mesh is closed (watertight) and consistently oriented.
std::size_t openEdgeCount(const TriangleMesh& mesh);

/// Splits a mesh into its edge-connected components (each re-indexed), in order of their
/// first triangle.
std::vector<TriangleMesh> connectedComponents(const TriangleMesh& mesh);

/// Signed volume (mm³) by the divergence theorem; positive for a closed outward-oriented mesh.
double signedVolume(const TriangleMesh& mesh);

/// Squared distance from `p` to the triangle (a, b, c) (Ericson's closest-point method).
double pointTriangleDistanceSquared(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Distance (mm) from `p` to the closest triangle of `mesh` (brute force; for tests and small
/// meshes). Infinity for an empty mesh.
double pointMeshDistance(const Eigen::Vector3d& p, const TriangleMesh& mesh);

/// About `count` points spread uniformly over the surface (area-weighted, stratified so that
/// the result depends only on `seed`), with their outward unit normals.
void sampleSurface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed,
                   std::vector<Eigen::Vector3d>& points_mm, std::vector<Eigen::Vector3d>& normals);

} // namespace scanpick::core
