#include "core/sim/Mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <tuple>

namespace scanpick::core {

void TriangleMesh::append(const TriangleMesh& other) {
  const int offset = static_cast<int>(vertices_mm.size());
  vertices_mm.insert(vertices_mm.end(), other.vertices_mm.begin(), other.vertices_mm.end());
  for (const auto& t : other.triangles)
    triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& T) {
  TriangleMesh out = mesh;
  for (auto& v : out.vertices_mm)
    v = T * v;
  return out;
}

TriangleMesh merged(const std::vector<TriangleMesh>& meshes) {
  TriangleMesh out;
  for (const auto& m : meshes)
    out.append(m);
  return out;
}

Eigen::AlignedBox3d boundingBox(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices_mm)
    box.extend(v);
  return box;
}

double surfaceArea(const TriangleMesh& mesh) {
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.vertices_mm[t[0]];
    area += 0.5 * (mesh.vertices_mm[t[1]] - a).cross(mesh.vertices_mm[t[2]] - a).norm();
  }
  return area;
}

TriangleMesh welded(const TriangleMesh& mesh, double tolerance_mm) {
  // Quantize to a grid of the tolerance; neighbouring cells are probed so two points on either
  // side of a cell border still merge.
  using Key = std::tuple<long long, long long, long long>;
  std::map<Key, int> grid;
  TriangleMesh out;
  std::vector<int> remap(mesh.vertices_mm.size());
  for (std::size_t i = 0; i < mesh.vertices_mm.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices_mm[i];
    const Key key{std::llround(v.x() / tolerance_mm), std::llround(v.y() / tolerance_mm),
                  std::llround(v.z() / tolerance_mm)};
    int found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it =
              grid.find({std::get<0>(key) + dx, std::get<1>(key) + dy, std::get<2>(key) + dz});
          if (it != grid.end() && (out.vertices_mm[it->second] - v).norm() <= tolerance_mm)
            found = it->second;
        }
    if (found < 0) {
      found = static_cast<int>(out.vertices_mm.size());
      out.vertices_mm.push_back(v);
      grid.emplace(key, found);
    }
    remap[i] = found;
  }
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3i r(remap[t[0]], remap[t[1]], remap[t[2]]);
    if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2])
      out.triangles.push_back(r);
  }
  return out;
}

std::size_t openEdgeCount(const TriangleMesh& mesh) {
  // For each undirected edge: count of a->b (a<b) minus count of b->a must be 0 and each 1.
  std::map<std::pair<int, int>, std::pair<int, int>> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      auto& e = edges[{std::min(a, b), std::max(a, b)}];
      (a < b ? e.first : e.second) += 1;
    }
  std::size_t open = 0;
  for (const auto& [key, count] : edges)
    if (count.first != 1 || count.second != 1)
      ++open;
  return open;
}

std::vector<TriangleMesh> connectedComponents(const TriangleMesh& mesh) {
  // Union-find over vertices joined by triangles.
  std::vector<int> parent(mesh.vertices_mm.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) {
      const int a = find(t[0]), b = find(t[k]);
      if (a != b)
        parent[std::max(a, b)] = std::min(a, b);
    }
  std::map<int, std::size_t> component_of_root;
  std::vector<TriangleMesh> out;
  std::vector<std::map<int, int>> local(0);
  for (const auto& t : mesh.triangles) {
    const int root = find(t[0]);
    auto [it, inserted] = component_of_root.emplace(root, out.size());
    if (inserted) {
      out.emplace_back();
      local.emplace_back();
    }
    TriangleMesh& c = out[it->second];
    auto& index = local[it->second];
    Eigen::Vector3i r;
    for (int k = 0; k < 3; ++k) {
      auto [vit, added] = index.emplace(t[k], static_cast<int>(c.vertices_mm.size()));
      if (added)
        c.vertices_mm.push_back(mesh.vertices_mm[t[k]]);
      r[k] = vit->second;
    }
    c.triangles.push_back(r);
  }
  return out;
}

double signedVolume(const TriangleMesh& mesh) {
  double v = 0;
  for (const auto& t : mesh.triangles)
    v += mesh.vertices_mm[t[0]].dot(mesh.vertices_mm[t[1]].cross(mesh.vertices_mm[t[2]]));
  return v / 6.0;
}

double pointTriangleDistanceSquared(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Real-Time Collision Detection, 5.1.5: classify p against the triangle's Voronoi regions.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return ap.squaredNorm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}

double pointMeshDistance(const Eigen::Vector3d& p, const TriangleMesh& mesh) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles)
    best = std::min(best,
                    pointTriangleDistanceSquared(p, mesh.vertices_mm[t[0]], mesh.vertices_mm[t[1]],
                                                 mesh.vertices_mm[t[2]]));
  return std::sqrt(best);
}

void sampleSurface(const TriangleMesh& mesh, std::size_t count, std::uint64_t seed,
                   std::vector<Eigen::Vector3d>& points_mm, std::vector<Eigen::Vector3d>& normals) {
  points_mm.clear();
  normals.clear();
  if (mesh.empty() || count == 0)
    return;
  std::vector<double> cumulative(mesh.triangles.size());
  double total = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const auto& a = mesh.vertices_mm[t[0]];
    total += 0.5 * (mesh.vertices_mm[t[1]] - a).cross(mesh.vertices_mm[t[2]] - a).norm();
    cumulative[i] = total;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  points_mm.reserve(count);
  normals.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    // Stratified over the cumulative area so the samples cover all triangles evenly.
    const double target = (static_cast<double>(k) + unit(rng)) / static_cast<double>(count) * total;
    const std::size_t i = std::min<std::size_t>(
        static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), target) -
                                 cumulative.begin()),
        mesh.triangles.size() - 1);
    const auto& t = mesh.triangles[i];
    const auto& a = mesh.vertices_mm[t[0]];
    const auto& b = mesh.vertices_mm[t[1]];
    const auto& c = mesh.vertices_mm[t[2]];
    double u = unit(rng), v = unit(rng);
    if (u + v > 1) {
      u = 1 - u;
      v = 1 - v;
    }
    points_mm.push_back(a + u * (b - a) + v * (c - a));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    normals.push_back(n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ());
  }
}

} // namespace scanpick::core
