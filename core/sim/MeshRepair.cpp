#include "core/sim/MeshRepair.h"

#include "core/common/Error.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <algorithm>
#include <map>
#include <string>

namespace scanpick::core {
namespace {

/// Each directed edge (a, b) of a triangle running a → b, with that triangle's third vertex.
using EdgeThirds = std::map<std::pair<int, int>, int>;

EdgeThirds edgeThirds(const TriangleMesh& mesh) {
  EdgeThirds thirds;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (!thirds.emplace(std::pair{t[k], t[(k + 1) % 3]}, t[(k + 2) % 3]).second)
        throw Error("the mesh has a non-manifold edge (vertices " + std::to_string(t[k]) + " and " +
                    std::to_string(t[(k + 1) % 3]) + "): its holes cannot be closed automatically");
  return thirds;
}

/// The boundary loops in the order a cap must run through them (each boundary edge a → b of a
/// triangle is b → a in the cap), starting at their smallest vertex.
std::vector<std::vector<int>> boundaryLoops(const EdgeThirds& edges) {
  std::map<int, int> cap_next; // vertex → next vertex along its cap
  for (const auto& [edge, third] : edges) {
    if (edges.count({edge.second, edge.first}))
      continue;
    if (!cap_next.emplace(edge.second, edge.first).second)
      throw Error("vertex " + std::to_string(edge.second) +
                  " lies on more than one hole: its holes cannot be closed automatically");
  }
  std::vector<std::vector<int>> loops;
  std::map<int, bool> used;
  for (const auto& [start, next] : cap_next) {
    if (used[start])
      continue;
    std::vector<int> loop;
    int v = start;
    for (; !used[v]; v = cap_next.at(v)) {
      used[v] = true;
      loop.push_back(v);
      if (!cap_next.count(cap_next.at(v)))
        throw Error("a hole's border does not close on itself");
    }
    if (v != start)
      throw Error("two holes share a vertex: they cannot be closed automatically");
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// Triangles over `loop` (vertex indices of `mesh`) by CGAL's hole filling (Liepa: the
/// triangulation of least area and dihedral angles, in 3D), each running through the loop in its
/// order, as the triangles around the hole need.
std::vector<Eigen::Vector3i> capTriangles(const TriangleMesh& mesh, const std::vector<int>& loop,
                                          const EdgeThirds& third_vertex) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::vector<Point> points, third_points;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices_mm[loop[i]];
    points.emplace_back(p.x(), p.y(), p.z());
    // The cap runs loop[i] → loop[i + 1]; the triangle beside it runs the other way.
    const Eigen::Vector3d& q =
        mesh.vertices_mm[third_vertex.at({loop[(i + 1) % loop.size()], loop[i]})];
    third_points.emplace_back(q.x(), q.y(), q.z());
  }
  std::vector<CGAL::Triple<int, int, int>> patch;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(points, third_points,
                                                           std::back_inserter(patch));
  if (patch.size() != loop.size() - 2)
    throw Error("a hole of " + std::to_string(loop.size()) +
                " vertices could not be capped (it folds over itself): close it in a mesh editor");
  std::vector<Eigen::Vector3i> caps;
  bool reversed = false; // the cap beside the loop's first edge must run loop[0] → loop[1]
  for (const auto& t : patch) {
    caps.emplace_back(loop[t.first], loop[t.second], loop[t.third]);
    for (int k = 0; k < 3; ++k)
      reversed |= caps.back()[k] == loop[1] && caps.back()[(k + 1) % 3] == loop[0];
  }
  if (reversed)
    for (auto& c : caps)
      std::swap(c[1], c[2]);
  return caps;
}

} // namespace

HoleFilling closeHoles(TriangleMesh& mesh) {
  HoleFilling report;
  std::vector<Eigen::Vector3i> caps;
  const EdgeThirds edges = edgeThirds(mesh);
  for (const auto& loop : boundaryLoops(edges)) {
    if (loop.size() < 3)
      throw Error("a hole of " + std::to_string(loop.size()) + " vertices cannot be capped");
    const auto loop_caps = capTriangles(mesh, loop, edges);
    caps.insert(caps.end(), loop_caps.begin(), loop_caps.end());
    Eigen::AlignedBox3d box;
    for (int v : loop)
      box.extend(mesh.vertices_mm[v]);
    report.largest_hole_mm = std::max(report.largest_hole_mm, box.diagonal().norm());
    ++report.holes;
  }
  mesh.triangles.insert(mesh.triangles.end(), caps.begin(), caps.end());
  report.triangles = caps.size();
  return report;
}

} // namespace scanpick::core
