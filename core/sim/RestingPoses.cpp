// Stable resting poses of a part: convex hull faces that hold the centre of mass, merged up to the
// part's symmetries, with probabilities from seeded physics drops (PhysicsWorld.h).
#include "core/sim/RestingPoses.h"

#include "core/common/Error.h"
#include "core/sim/PhysicsWorld.h"
#include "core/sim/SensorNoise.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>
#include <LinearMath/btConvexHullComputer.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint64_t kDropStream = 0x7265737469; // the drops' own random stream

double radians(double deg) {
  return deg * kPi / 180.0;
}

/// A flat face of the hull: outward unit normal, its vertices, its area (mm²). Coordinates are
/// relative to the part's centre (Part::center_mm), which is the centre of mass.
struct HullFace {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::vector<Eigen::Vector3d> vertices;
  double area_mm2 = 0;
};

struct Hull {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<HullFace> faces;
};

/// One polygon face of btConvexHullComputer's output, its corners taken from `vertices` (the
/// hull's vertices at full precision), oriented away from `inside`.
HullFace hullFace(const btConvexHullComputer& hull, int face,
                  const std::vector<Eigen::Vector3d>& vertices, const Eigen::Vector3d& inside) {
  HullFace f;
  const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[face]];
  const btConvexHullComputer::Edge* e = start;
  do {
    f.vertices.push_back(vertices[static_cast<std::size_t>(e->getTargetVertex())]);
    e = e->getNextEdgeOfFace();
  } while (e != start && f.vertices.size() <= static_cast<std::size_t>(hull.vertices.size()));
  // Newell's normal: its length is twice the polygon's area.
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < f.vertices.size(); ++i) {
    n += f.vertices[i].cross(f.vertices[(i + 1) % f.vertices.size()]);
    centroid += f.vertices[i];
  }
  centroid /= static_cast<double>(f.vertices.size());
  f.area_mm2 = n.norm() / 2;
  f.normal = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
  if (f.normal.dot(centroid - inside) < 0)
    f.normal = -f.normal;
  return f;
}

/// The convex hull of all components' vertices, centred on Part::center_mm.
Hull convexHull(const Part& part) {
  const Eigen::Vector3d c = part.center_mm();
  std::vector<Eigen::Vector3d> points;
  for (const auto& comp : part.components)
    for (const auto& v : comp.vertices_mm)
      points.emplace_back(v - c);
  if (points.size() < 4)
    throw Error("part '" + part.name + "' has no volume: its resting sides are undefined");
  btConvexHullComputer bt;
  bt.compute(points.front().data(), static_cast<int>(sizeof(Eigen::Vector3d)),
             static_cast<int>(points.size()), 0, 0);
  Hull hull;
  Eigen::Vector3d inside = Eigen::Vector3d::Zero();
  // Bullet returns single-precision vertices: take the input points they came from.
  for (int i = 0; i < bt.vertices.size(); ++i) {
    hull.vertices.push_back(points[static_cast<std::size_t>(bt.original_vertex_index[i])]);
    inside += hull.vertices.back();
  }
  inside /= std::max<double>(1.0, static_cast<double>(hull.vertices.size()));
  for (int f = 0; f < bt.faces.size(); ++f) {
    HullFace face = hullFace(bt, f, hull.vertices, inside);
    if (face.area_mm2 > 1e-9)
      hull.faces.push_back(std::move(face));
  }
  if (hull.faces.size() < 4)
    throw Error("part '" + part.name + "' is flat (its convex hull has no volume): its resting " +
                "sides are undefined");
  return hull;
}

/// Faces whose normals differ by less than `tolerance_rad` made one (largest face first; the
/// normal is the area-weighted mean), in order of decreasing area of their largest member.
std::vector<HullFace> mergeCoplanar(std::vector<HullFace> faces, double tolerance_rad) {
  std::stable_sort(faces.begin(), faces.end(),
                   [](const HullFace& a, const HullFace& b) { return a.area_mm2 > b.area_mm2; });
  std::vector<HullFace> merged;
  std::vector<Eigen::Vector3d> first_normal, weighted;
  const double cos_tol = std::cos(tolerance_rad);
  for (const auto& f : faces) {
    std::size_t k = 0;
    while (k < merged.size() && first_normal[k].dot(f.normal) < cos_tol)
      ++k;
    if (k == merged.size()) {
      merged.push_back({f.normal, {}, 0});
      first_normal.push_back(f.normal);
      weighted.push_back(Eigen::Vector3d::Zero());
    }
    merged[k].vertices.insert(merged[k].vertices.end(), f.vertices.begin(), f.vertices.end());
    weighted[k] += f.area_mm2 * f.normal;
  }
  for (std::size_t k = 0; k < merged.size(); ++k)
    merged[k].normal = weighted[k].normalized();
  return merged;
}

/// The face's support polygon (its vertices projected onto the plane that touches the table)
/// and whether the centre of mass (the origin) stands inside it with the required tip angle.
/// Sets the face's area to the polygon's.
bool isStable(HullFace& face, double min_tip_rad) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const Eigen::Vector3d& n = face.normal;
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  double height = 0; // of the centre of mass above the table plane
  std::vector<K::Point_2> points, polygon;
  for (const auto& v : face.vertices) {
    height = std::max(height, n.dot(v));
    points.emplace_back(u.dot(v), w.dot(v));
  }
  CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(polygon)); // CCW
  if (polygon.size() < 3)
    return false;
  double area2 = 0, inner = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const K::Point_2& a = polygon[i];
    const K::Point_2& b = polygon[(i + 1) % polygon.size()];
    area2 += a.x() * b.y() - b.x() * a.y();
    // Signed distance of the projected centre of mass (2D origin) from the edge, inside > 0.
    const double ex = b.x() - a.x(), ey = b.y() - a.y(), len = std::hypot(ex, ey);
    if (len > 0)
      inner = std::min(inner, (ex * -a.y() - ey * -a.x()) / len);
  }
  face.area_mm2 = area2 / 2;
  return height > 0 && inner > 0 && std::atan2(inner, height) >= min_tip_rad;
}

/// Union-find root.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

/// Whether the direction `a` lies within `tolerance_rad` of `b`, directly or mapped by one of the
/// part's symmetries (part frame).
bool sameSide(const PartSymmetry& symmetry, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
              double tolerance_rad) {
  const double cos_tol = std::cos(tolerance_rad);
  if (a.dot(b) > cos_tol)
    return true;
  if (symmetry.continuous_axis) {
    // A turn about the axis brings a closest to b when both lie in one plane with the axis: they
    // then differ by the difference of their angles to the axis.
    const Eigen::Vector3d axis = symmetry.continuous_axis->direction.normalized();
    const double angle_a = std::acos(std::clamp(a.dot(axis), -1.0, 1.0));
    const double angle_b = std::acos(std::clamp(b.dot(axis), -1.0, 1.0));
    if (std::abs(angle_a - angle_b) < tolerance_rad)
      return true;
  }
  for (const auto& S : symmetry.discrete)
    if ((S.linear() * a).dot(b) > cos_tol || (S.linear().transpose() * a).dot(b) > cos_tol)
      return true;
  return false;
}

/// Class index of each face: faces that are the same side (sameSide, transitively) share one;
/// classes are numbered in order of their first face.
std::vector<int> symmetryClasses(const std::vector<HullFace>& faces, const PartSymmetry& symmetry,
                                 double tolerance_rad) {
  std::vector<std::size_t> parent(faces.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (std::size_t j = i + 1; j < faces.size(); ++j)
      if (sameSide(symmetry, faces[i].normal, faces[j].normal, tolerance_rad))
        parent[root(parent, j)] = root(parent, i);
  std::vector<int> cls(faces.size(), -1), class_of_root(faces.size(), -1);
  int next = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::size_t r = root(parent, i);
    if (class_of_root[r] < 0)
      class_of_root[r] = next++;
    cls[i] = class_of_root[r];
  }
  return cls;
}

/// The shortest turn after `R_table_part` that points the part-frame direction `n` down (-z).
Eigen::Matrix3d restRotation(const Eigen::Vector3d& n, const Eigen::Matrix3d& R_table_part) {
  const Eigen::Vector3d m = R_table_part * n;
  if (m.z() < -1 + 1e-12) // already down: the usual pose, exactly
    return R_table_part;
  if (m.z() > 1 - 1e-12) // pointing up: turn over about x, as teachSideTurn(1) does
    return Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix() * R_table_part;
  return Eigen::Quaterniond::FromTwoVectors(m, -Eigen::Vector3d::UnitZ()).toRotationMatrix() *
         R_table_part;
}

/// The stable faces with their symmetry classes and one pose per class (its largest face).
struct Analysis {
  std::vector<HullFace> faces; ///< stable faces only
  std::vector<int> face_class;
  std::vector<RestingPose> poses; ///< indexed by class
  std::vector<Eigen::Vector3d> hull_vertices;
};

Analysis analyse(const Part& part, const RestingPoseParams& params) {
  for (const double deg :
       {params.coplanar_tolerance_deg, params.same_side_deg, params.min_tip_angle_deg})
    if (!(deg >= 0 && deg <= 45))
      throw Error("resting poses: the coplanar tolerance, the same-side angle and the minimum tip "
                  "angle must be between 0 and 45 degrees");
  Hull hull = convexHull(part);
  Analysis a;
  a.hull_vertices = hull.vertices;
  for (auto& face : mergeCoplanar(std::move(hull.faces), radians(params.coplanar_tolerance_deg)))
    if (isStable(face, radians(params.min_tip_angle_deg)))
      a.faces.push_back(std::move(face));
  // Largest face first, so every class's first face is its largest.
  std::stable_sort(a.faces.begin(), a.faces.end(),
                   [](const HullFace& x, const HullFace& y) { return x.area_mm2 > y.area_mm2; });
  // Symmetric copies match only up to round-off, hence the floor of 1°.
  const double same_side_deg = std::max({params.coplanar_tolerance_deg, params.same_side_deg, 1.0});
  a.face_class = symmetryClasses(a.faces, part.symmetry, radians(same_side_deg));
  for (std::size_t i = 0; i < a.faces.size(); ++i) {
    const auto k = static_cast<std::size_t>(a.face_class[i]);
    if (k == a.poses.size()) {
      RestingPose p;
      p.down_normal_part = a.faces[i].normal;
      p.R_table_part = restRotation(a.faces[i].normal, part.R_table_part);
      p.face_area_mm2 = a.faces[i].area_mm2;
      p.symmetric_copies = 0;
      a.poses.push_back(p);
    }
    ++a.poses[k].symmetric_copies;
  }
  return a;
}

/// One drop: the part in a random orientation `drop_height_mm` above a table, settled; returns
/// the index of the stable face that points closest to straight down.
std::size_t dropOnce(const Part& part, const Analysis& a, const RestingPoseParams& params,
                     std::size_t index) {
  std::mt19937_64 rng(hashMix(params.seed, index, kDropStream));
  const Eigen::Matrix3d R = physics::randomRotation(rng);
  double low = 0;
  for (const auto& v : a.hull_vertices)
    low = std::min(low, (R * v).z());
  physics::World w;
  physics::addEnvironment(w, LayoutKind::Teach, BinGeometry{});
  const std::size_t first_dynamic = w.bodies.size();
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  T_world_body.linear() = R;
  T_world_body.translation() = Eigen::Vector3d(0, 0, -low + params.drop_height_mm);
  physics::addPartBody(w, physics::partShape(w, part), part, T_world_body);
  physics::simulate(w, params.settle_time_s, first_dynamic, true);
  const Eigen::Matrix3d R_end = physics::fromBt(w.bodies.back()->getWorldTransform()).linear();
  const Eigen::Vector3d down_part = R_end.transpose() * -Eigen::Vector3d::UnitZ();
  std::size_t best = 0;
  for (std::size_t i = 1; i < a.faces.size(); ++i)
    if (a.faces[i].normal.dot(down_part) > a.faces[best].normal.dot(down_part))
      best = i;
  return best;
}

/// Highest probability first, then larger face, then normal (x, y, z) for a total order.
bool morePrevalent(const RestingPose& x, const RestingPose& y) {
  if (x.probability != y.probability)
    return x.probability > y.probability;
  if (x.face_area_mm2 != y.face_area_mm2)
    return x.face_area_mm2 > y.face_area_mm2;
  const Eigen::Vector3d& p = x.down_normal_part;
  const Eigen::Vector3d& q = y.down_normal_part;
  return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
}

} // namespace

std::vector<RestingPose> stableRestingPoses(const Part& part, const RestingPoseParams& params) {
  return analyse(part, params).poses;
}

std::vector<RestingPose> restingPoses(const Part& part, const RestingPoseParams& params,
                                      const ProgressFn& progress) {
  if (params.drops < 0 || params.drops > 100000)
    throw Error("resting poses: the number of drops must be between 0 and 100000 (got " +
                std::to_string(params.drops) + ")");
  if (!(params.drop_height_mm >= 0 && params.drop_height_mm <= 10000) ||
      !(params.settle_time_s > 0 && params.settle_time_s <= 600))
    throw Error("resting poses: the drop height must be 0-10000 mm and the settle time 0-600 s");
  Analysis a = analyse(part, params);
  if (a.faces.empty() || params.drops == 0)
    return a.poses;
  // Drops are independent (each its own world and random stream), so they run in parallel in
  // batches, with progress and cancellation checked between batches on the calling thread.
  const auto drops = static_cast<std::size_t>(params.drops);
  std::vector<std::size_t> landed(drops);
  constexpr std::size_t kBatch = 16;
  for (std::size_t begin = 0; begin < drops; begin += kBatch) {
    const std::size_t end = std::min(drops, begin + kBatch);
    tbb::parallel_for(begin, end, [&](std::size_t i) { landed[i] = dropOnce(part, a, params, i); });
    reportProgress(progress, static_cast<double>(end) / static_cast<double>(drops));
  }
  std::vector<int> count(a.poses.size(), 0);
  for (const std::size_t face : landed)
    ++count[static_cast<std::size_t>(a.face_class[face])];
  for (std::size_t k = 0; k < a.poses.size(); ++k)
    a.poses[k].probability = static_cast<double>(count[k]) / params.drops;
  std::sort(a.poses.begin(), a.poses.end(), morePrevalent);
  return a.poses;
}

} // namespace scanpick::core
