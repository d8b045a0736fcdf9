#include "core/model/AllAround.h"

#include "core/cloud/PointKdTree.h"
#include "core/refine/SceneIndex.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>
#include <boost/graph/prim_minimum_spanning_tree.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace scanpick::core {
namespace {

/// Neighbours each point links to in the graph its normals' signs spread over.
constexpr std::size_t kGraphNeighbours = 10;
/// Lines of sight that pass two surfaces this many point spacings apart see through the part.
constexpr double kLayerGapSpacings = 4.0;

using NormalGraph =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                          boost::property<boost::edge_weight_t, float>>;

/// How well `n_j` (at `p_j`) agrees in sign with `n_i` (at `p_i`), in [−1, 1]: the cosine between
/// n_j and n_i mirrored in the plane half way between the points, which is n_j's direction if a
/// circular arc joins them. Near 1 on a smooth surface (n_i ≈ n_j) and across a sharp edge (a
/// box's faces).
float signAgreement(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i,
                    const Eigen::Vector3f& p_j, const Eigen::Vector3f& n_j) {
  const Eigen::Vector3f d = (p_j - p_i).normalized();
  return std::clamp(n_i.dot(n_j) - 2.0f * n_i.dot(d) * n_j.dot(d), -1.0f, 1.0f);
}

/// How far signAgreement can be trusted, in [0, 1]: not where the points lie along both normals
/// (the two faces of a thin wall, whose normals are opposite, and two faces of a step, whose
/// normals are alike, look the same), fully where they lie along both tangent planes.
float signConfidence(const Eigen::Vector3f& p_i, const Eigen::Vector3f& n_i,
                     const Eigen::Vector3f& p_j, const Eigen::Vector3f& n_j) {
  const Eigen::Vector3f d = (p_j - p_i).normalized();
  return std::abs(signAgreement(p_i, n_i, p_j, n_j)) *
         (1.0f - std::abs(n_i.dot(d)) * std::abs(n_j.dot(d)));
}

/// Each point with a normal linked to its nearest neighbours; an edge costs 1 − signConfidence,
/// so that the signs spread first where they are clear.
NormalGraph neighbourGraph(const std::vector<Eigen::Vector3f>& points,
                           const std::vector<Eigen::Vector3f>& normals) {
  NormalGraph graph(points.size());
  PointVectorSource source{&points};
  PointKdTree tree(3, source);
  tree.buildIndex();
  std::vector<std::uint32_t> index(kGraphNeighbours + 1);
  std::vector<float> distance_sq(kGraphNeighbours + 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!normals[i].allFinite())
      continue;
    const std::size_t found =
        tree.knnSearch(points[i].data(), index.size(), index.data(), distance_sq.data());
    for (std::size_t k = 0; k < found; ++k) {
      const std::uint32_t j = index[k];
      if (j != i && normals[j].allFinite() && points[j] != points[i])
        boost::add_edge(i, j, 1.0f - signConfidence(points[i], normals[i], points[j], normals[j]),
                        graph);
    }
  }
  return graph;
}

/// Turns the normals of one connected piece (`members`) outward: its point farthest from the
/// piece's centroid faces away from it, and each other normal agrees in sign with its parent's in
/// the minimum spanning tree grown from there.
void orientPiece(const NormalGraph& graph, const std::vector<Eigen::Vector3f>& points,
                 const std::vector<std::size_t>& members, std::vector<Eigen::Vector3f>& normals) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const std::size_t i : members)
    centroid += points[i].cast<double>();
  centroid /= static_cast<double>(members.size());
  const auto reach = [&](std::size_t i) { return (points[i].cast<double>() - centroid).norm(); };
  const std::size_t root =
      *std::max_element(members.begin(), members.end(),
                        [&](std::size_t a, std::size_t b) { return reach(a) < reach(b); });
  if (normals[root].cast<double>().dot(points[root].cast<double>() - centroid) < 0)
    normals[root] = -normals[root];
  if (members.size() < 2)
    return;
  std::vector<std::size_t> parent(boost::num_vertices(graph));
  boost::prim_minimum_spanning_tree(graph, parent.data(), boost::root_vertex(root));
  std::vector<std::vector<std::size_t>> children(parent.size());
  for (const std::size_t i : members)
    if (parent[i] != i)
      children[parent[i]].push_back(i);
  std::vector<std::size_t> stack{root};
  while (!stack.empty()) {
    const std::size_t at = stack.back();
    stack.pop_back();
    for (const std::size_t child : children[at]) {
      if (signAgreement(points[at], normals[at], points[child], normals[child]) < 0)
        normals[child] = -normals[child];
      stack.push_back(child);
    }
  }
}

} // namespace

bool seenFromOneCamera(const PointCloud& cloud_mm, const Eigen::Vector3d& camera_mm,
                       double spacing_mm) {
  std::vector<Eigen::Vector3d> sight; // from the camera to each valid point
  Eigen::AlignedBox3d box;
  for (const auto& p : cloud_mm.points_mm)
    if (isValid(p)) {
      sight.push_back(p.cast<double>() - camera_mm);
      box.extend(p.cast<double>());
    }
  if (sight.size() < 3 || !(spacing_mm > 0))
    return true;
  if (box.contains(camera_mm))
    return false;
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  for (const auto& d : sight)
    axis += d;
  axis.normalize();
  std::vector<double> range;
  for (const auto& d : sight) {
    if (!(d.dot(axis) > 0))
      return false; // the cloud wraps around the camera
    range.push_back(d.norm());
  }
  std::nth_element(range.begin(), range.begin() + std::ptrdiff_t(range.size() / 2), range.end());
  const double cell = 2.0 * spacing_mm / range[range.size() / 2]; // in tangent units
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  struct Depths {
    double near = std::numeric_limits<double>::infinity();
    double far = -std::numeric_limits<double>::infinity();
    std::size_t points = 0;
  };
  std::unordered_map<std::uint64_t, Depths> cells;
  for (const auto& d : sight) {
    const double along = d.dot(axis);
    const auto iu = static_cast<std::int32_t>(std::floor(d.dot(u) / along / cell));
    const auto iv = static_cast<std::int32_t>(std::floor(d.dot(v) / along / cell));
    Depths& depths = cells[(std::uint64_t(std::uint32_t(iu)) << 32) | std::uint32_t(iv)];
    const double r = d.norm();
    depths.near = std::min(depths.near, r);
    depths.far = std::max(depths.far, r);
    ++depths.points;
  }
  std::size_t crossed = 0, layered = 0;
  for (const auto& [key, depths] : cells) {
    if (depths.points < 2)
      continue;
    ++crossed;
    layered += depths.far - depths.near > kLayerGapSpacings * spacing_mm ? 1 : 0;
  }
  return 2 * layered < crossed;
}

std::vector<Eigen::Vector3f> outwardNormals(const PointCloud& cloud_mm, double radius_mm) {
  SceneIndexOptions options;
  options.normal_radius_mm = radius_mm;
  options.orient_cloud_normals = false;
  const SceneIndex index(cloud_mm, options);
  const std::vector<Eigen::Vector3f>& points = index.points();
  std::vector<Eigen::Vector3f> normals = index.normals();
  const NormalGraph graph = neighbourGraph(points, normals);
  std::vector<int> piece(points.size());
  const int pieces = boost::connected_components(graph, piece.data());
  std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(pieces));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (normals[i].allFinite())
      members[static_cast<std::size_t>(piece[i])].push_back(i);
  for (const auto& m : members)
    if (!m.empty())
      orientPiece(graph, points, m, normals);
  // Back to one normal per input point.
  std::vector<Eigen::Vector3f> out(cloud_mm.size(), invalidPoint());
  std::size_t next = 0;
  for (std::size_t i = 0; i < cloud_mm.size(); ++i)
    if (isValid(cloud_mm.points_mm[i]))
      out[i] = normals[next++];
  return out;
}

} // namespace scanpick::core
