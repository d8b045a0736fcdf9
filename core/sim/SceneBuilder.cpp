// Rigid-body drop of parts into a bin or onto a table with Bullet.
#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/PhysicsWorld.h"
#include "core/sim/RestingPoses.h"
#include "core/sim/Scene.h"
#include "core/sim/Settle.h"

#include <LinearMath/btConvexHullComputer.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

namespace scanpick::core {

using namespace physics;

TriangleMesh environmentMesh(LayoutKind layout, const BinGeometry& bin) {
  TriangleMesh env;
  if (layout != LayoutKind::Bin) {
    env.append(boxMesh({-600, -600, -20}, {600, 600, 0}));
    return env;
  }
  const double hx = bin.inner_x_mm / 2, hy = bin.inner_y_mm / 2, t = bin.wall_thickness_mm;
  const double h = bin.wall_height_mm;
  env.append(boxMesh({-hx - t, -hy - t, -t}, {hx + t, hy + t, 0}));
  // The ground the bin stands on, so the scan has a background as a real one does.
  env.append(boxMesh({-900, -900, -t - 20}, {900, 900, -t}));
  env.append(boxMesh({-hx - t, -hy - t, 0}, {-hx, hy + t, h}));
  env.append(boxMesh({hx, -hy - t, 0}, {hx + t, hy + t, h}));
  env.append(boxMesh({-hx, -hy - t, 0}, {hx, -hy, h}));
  env.append(boxMesh({-hx, hy, 0}, {hx, hy + t, h}));
  return env;
}

std::string layoutName(LayoutKind layout) {
  switch (layout) {
  case LayoutKind::Bin:
    return "bin";
  case LayoutKind::Scatter:
    return "scatter";
  case LayoutKind::Teach:
    return "teach";
  }
  return "bin";
}

LayoutKind layoutFromName(const std::string& name) {
  if (name == "bin")
    return LayoutKind::Bin;
  if (name == "scatter")
    return LayoutKind::Scatter;
  if (name == "teach")
    return LayoutKind::Teach;
  throw Error("unknown layout '" + name + "': use bin, scatter or teach");
}

Eigen::Matrix3d teachSideTurn(int side) {
  constexpr double kHalfPi = 1.57079632679489661923;
  switch (side) {
  case 1:
    return Eigen::AngleAxisd(2 * kHalfPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  case 2:
    return Eigen::AngleAxisd(kHalfPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  case 3:
    return Eigen::AngleAxisd(kHalfPi, Eigen::Vector3d::UnitY()).toRotationMatrix();
  default:
    return Eigen::Matrix3d::Identity();
  }
}

double defaultCameraHeight_mm(const SensorModel& sensor, LayoutKind layout) {
  const bool kinect = sensor.nominal_distance_mm >= 1000;
  if (layout == LayoutKind::Bin)
    return kinect ? 1100.0 : 850.0;
  return kinect ? 1000.0 : 700.0;
}

namespace {

/// The turn of a teach scene's part before its random yaw: the teach side's, or the resting pose's
/// that spec.resting_side names (its drops take the first 90 % of `progress`).
Eigen::Matrix3d teachRotation(const SceneSpec& spec, const Part& part, const ProgressFn& progress) {
  if (!spec.resting_side)
    return teachSideTurn(spec.teach_side) * part.R_table_part;
  const int side = *spec.resting_side;
  const auto poses = restingPoses(part, RestingPoseParams{}, subProgress(progress, 0.0, 0.9));
  if (side < 0 || static_cast<std::size_t>(side) >= poses.size())
    throw Error(
        "resting side " + std::to_string(side) + " does not exist: part '" + part.name + "' has " +
        std::to_string(poses.size()) + " distinct resting side" + (poses.size() == 1 ? "" : "s") +
        (poses.empty() ? std::string() : " (0 to " + std::to_string(poses.size() - 1) + ")"));
  return poses[static_cast<std::size_t>(side)].R_table_part;
}

/// Throws Error for a spec that names no part, an instance count out of range, or a teach or
/// resting side that does not exist or does not apply.
void checkSceneSpec(const SceneSpec& spec) {
  if (spec.parts.empty())
    throw Error("no part to place: give a built-in part name or a mesh file");
  if (spec.count < 1)
    throw Error("the scene needs at least one instance (count is " + std::to_string(spec.count) +
                ")");
  if (spec.teach_side < 0 || spec.teach_side > kTeachSides - 1)
    throw Error("teach side " + std::to_string(spec.teach_side) + " does not exist: use 0 to " +
                std::to_string(kTeachSides - 1));
  if (spec.resting_side && spec.layout != LayoutKind::Teach)
    throw Error("a resting side applies to a teach scene only (layout is " +
                layoutName(spec.layout) + ")");
  if (spec.resting_side && spec.teach_side != 0)
    throw Error("give either a teach side or a resting side, not both");
  if (spec.resting_side && *spec.resting_side < 0)
    throw Error("resting side " + std::to_string(*spec.resting_side) +
                " does not exist: sides are numbered from 0 (most probable first)");
  if (spec.layout == LayoutKind::Teach && spec.count != 1)
    throw Error("a teach scene holds exactly one part (count is " + std::to_string(spec.count) +
                ")");
  if (spec.count > 200)
    throw Error("at most 200 instances per scene (count is " + std::to_string(spec.count) + ")");
}

/// The physics world of a scene being built: its parts' shapes, and the instances' bodies from
/// `first_dynamic` on (instance k uses part k % parts).
struct DropWorld {
  World& w;
  const std::vector<Part>& parts;
  std::vector<btCollisionShape*> shapes;
  std::size_t first_dynamic = 0;

  /// Adds instance `id`'s body, turned by `R`, its part's centre at `center_world_mm`.
  void spawn(int id, const Eigen::Matrix3d& R, const Eigen::Vector3d& center_world_mm) {
    const Part& part = parts[static_cast<std::size_t>(id) % parts.size()];
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.linear() = R;
    T_world_body.translation() = center_world_mm;
    addPartBody(w, shapes[static_cast<std::size_t>(id) % shapes.size()], part, T_world_body);
  }
};

/// Drops the instances into the bin one at a time, from just above the pile, so no two start
/// overlapping; the drops take the first 80 % of `progress`.
void dropIntoBin(DropWorld& drop, const SceneSpec& spec, std::mt19937_64& rng,
                 std::uniform_real_distribution<double>& unit, const ProgressFn& progress) {
  const int n = spec.count;
  for (int id = 0; id < n; ++id) {
    const Part& part = drop.parts[static_cast<std::size_t>(id) % drop.parts.size()];
    const double r = part.diameter_mm() / 2;
    const double mx = std::max(0.0, spec.bin.inner_x_mm / 2 - r),
                 my = std::max(0.0, spec.bin.inner_y_mm / 2 - r);
    const Eigen::Matrix3d R = randomRotation(rng);
    const double x = (2 * unit(rng) - 1) * mx, y = (2 * unit(rng) - 1) * my;
    drop.spawn(id, R, {x, y, pileTop_mm(drop.w, drop.first_dynamic) + r + 5});
    simulate(drop.w, 0.35, drop.first_dynamic, false);
    reportProgress(progress, 0.8 * (id + 1) / n);
  }
  simulate(drop.w, 3.0, drop.first_dynamic, true);
}

/// Drops the instances onto the table from grid cells larger than the biggest part, shuffled, so
/// instances start apart.
void scatterOnTable(DropWorld& drop, const SceneSpec& spec, std::mt19937_64& rng,
                    std::uniform_real_distribution<double>& unit) {
  const int n = spec.count;
  double d = 0;
  for (const auto& p : drop.parts)
    d = std::max(d, p.diameter_mm());
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::vector<int> cells(static_cast<std::size_t>(side * side));
  for (std::size_t i = 0; i < cells.size(); ++i)
    cells[i] = static_cast<int>(i);
  std::shuffle(cells.begin(), cells.end(), rng);
  const double pitch = d + 15;
  for (int id = 0; id < n; ++id) {
    const double gx = (cells[static_cast<std::size_t>(id)] % side - (side - 1) / 2.0) * pitch;
    const double gy = (cells[static_cast<std::size_t>(id)] / side - (side - 1) / 2.0) * pitch;
    const Eigen::Matrix3d R = randomRotation(rng);
    drop.spawn(id, R, {gx + (unit(rng) - 0.5) * 10, gy + (unit(rng) - 0.5) * 10, d / 2 + 3});
  }
  simulate(drop.w, 3.0, drop.first_dynamic, true);
}

/// Sets the teach scene's one part down on the table, turned per the spec and by a random yaw.
void placeForTeach(DropWorld& drop, const SceneSpec& spec, std::mt19937_64& rng,
                   std::uniform_real_distribution<double>& unit, const ProgressFn& progress) {
  const Part& part = drop.parts.front();
  const double yaw = unit(rng) * 2 * 3.14159265358979323846;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                            teachRotation(spec, part, progress);
  // Lowest point of the part in this orientation, relative to its centre.
  double low = 0;
  for (const auto& c : part.components)
    for (const auto& v : c.vertices_mm)
      low = std::min(low, (R * (v - part.center_mm())).z());
  drop.spawn(0, R, {(unit(rng) - 0.5) * 40, (unit(rng) - 0.5) * 40, -low + 1.0});
  simulate(drop.w, 2.0, drop.first_dynamic, true);
}

/// How far a teach scene's part stays beyond the sensor's near limit, mm.
constexpr double kTeachNearMargin_mm = 50.0;

/// The operator's box of a teach scene: the part's extent plus 10 mm around, starting 1 mm above
/// the table so the table itself stays out (world frame).
Eigen::AlignedBox3d teachCropBox(const Scene& scene) {
  const auto& inst = scene.instances.front();
  Eigen::AlignedBox3d box =
      boundingBox(transformed(scene.parts[inst.part].mesh(), inst.T_world_part));
  box.min() -= Eigen::Vector3d(10, 10, 0);
  box.max() += Eigen::Vector3d(10, 10, 10);
  box.min().z() = 1.0;
  return box;
}

} // namespace

Scene buildScene(const SceneSpec& spec, const SensorModel& sensor, const ProgressFn& progress) {
  checkSceneSpec(spec);

  Scene scene;
  scene.layout = spec.layout;
  scene.seed = spec.seed;
  scene.parts = spec.parts;
  scene.environment_mm = environmentMesh(spec.layout, spec.bin);
  scene.bin = spec.bin;
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  World w;
  addEnvironment(w, spec.layout, spec.bin);
  DropWorld drop{w, scene.parts, {}, w.bodies.size()};
  for (const auto& p : scene.parts)
    drop.shapes.push_back(partShape(w, p, kMargin_units));
  if (spec.layout == LayoutKind::Bin)
    dropIntoBin(drop, spec, rng, unit, progress);
  else if (spec.layout == LayoutKind::Scatter)
    scatterOnTable(drop, spec, rng, unit);
  else
    placeForTeach(drop, spec, rng, unit, progress);
  reportProgress(progress, 1.0);

  for (int id = 0; id < spec.count; ++id) {
    const btRigidBody& body = *w.bodies[drop.first_dynamic + static_cast<std::size_t>(id)];
    PartInstance inst;
    inst.id = id;
    inst.part = static_cast<std::size_t>(id) % scene.parts.size();
    Eigen::Isometry3d T_body_part = Eigen::Isometry3d::Identity();
    T_body_part.translation() = -scene.parts[inst.part].center_mm();
    inst.T_world_part = fromBt(body.getWorldTransform()) * T_body_part;
    scene.instances.push_back(inst);
  }

  // Camera straight above the origin: camera x = world x, camera y = -world y, z down.
  double height = spec.camera_height_mm;
  if (height <= 0) {
    height = defaultCameraHeight_mm(sensor, spec.layout);
    // A part too tall for the teach height would reach inside the sensor's near limit and lose
    // its top: an operator raises the camera until it is whole, with a margin.
    if (spec.layout == LayoutKind::Teach)
      height = std::max(height,
                        teachCropBox(scene).max().z() + sensor.min_range_mm + kTeachNearMargin_mm);
  }
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  T_world_camera.translation() = Eigen::Vector3d(0, 0, height);
  scene.T_camera_world = T_world_camera.inverse();

  if (spec.layout == LayoutKind::Teach)
    scene.crop_box_world = teachCropBox(scene);
  return scene;
}

Scene settleScene(const Scene& scene, const std::vector<int>& removed_ids, double max_seconds) {
  Scene out = scene;
  out.instances.clear();
  World w;
  addEnvironment(w, scene.layout, scene.bin);
  const std::size_t first_dynamic = w.bodies.size();
  std::vector<btCollisionShape*> shapes;
  for (const auto& p : scene.parts)
    shapes.push_back(partShape(w, p, kMargin_units));
  for (const auto& inst : scene.instances) {
    if (std::find(removed_ids.begin(), removed_ids.end(), inst.id) != removed_ids.end())
      continue;
    const Part& part = scene.parts[inst.part];
    addPartBody(w, shapes[inst.part], part,
                inst.T_world_part * Eigen::Translation3d(part.center_mm()));
    PartInstance kept = inst;
    kept.id = static_cast<int>(out.instances.size());
    out.instances.push_back(kept);
  }
  simulate(w, max_seconds, first_dynamic, true);
  for (auto& inst : out.instances) {
    const btRigidBody& body = *w.bodies[first_dynamic + static_cast<std::size_t>(inst.id)];
    inst.T_world_part = fromBt(body.getWorldTransform()) *
                        Eigen::Translation3d(-scene.parts[inst.part].center_mm());
  }
  return out;
}

namespace {

/// Outward face planes (unit normal n, offset d: inside where n·p <= d) of a point set's hull.
std::vector<Eigen::Vector4d> hullPlanes(const std::vector<Eigen::Vector3d>& points) {
  btConvexHullComputer hull;
  hull.compute(points.front().data(), static_cast<int>(sizeof(Eigen::Vector3d)),
               static_cast<int>(points.size()), 0, 0);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i = 0; i < hull.vertices.size(); ++i)
    centroid += Eigen::Vector3d(hull.vertices[i].x(), hull.vertices[i].y(), hull.vertices[i].z());
  centroid /= std::max(1, hull.vertices.size());
  std::vector<Eigen::Vector4d> planes;
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* e = &hull.edges[hull.faces[f]];
    auto vertex = [&](int k) {
      const btVector3& v = hull.vertices[k];
      return Eigen::Vector3d(v.x(), v.y(), v.z());
    };
    const Eigen::Vector3d a = vertex(e->getSourceVertex()), b = vertex(e->getTargetVertex());
    const Eigen::Vector3d c = vertex(e->getNextEdgeOfFace()->getTargetVertex());
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-12)
      continue;
    n.normalize();
    if (n.dot(a - centroid) < 0)
      n = -n;
    planes.emplace_back(n.x(), n.y(), n.z(), n.dot(a));
  }
  return planes;
}

/// How deep `p` lies inside the convex region (0 outside).
double depthInside(const std::vector<Eigen::Vector4d>& planes, const Eigen::Vector3d& p) {
  double depth = std::numeric_limits<double>::infinity();
  for (const auto& pl : planes) {
    depth = std::min(depth, pl[3] - pl.head<3>().dot(p));
    if (depth <= 0)
      return 0;
  }
  return planes.empty() ? 0 : depth;
}

struct ConvexPiece {
  std::vector<Eigen::Vector4d> planes; ///< in the owner's frame
  Eigen::AlignedBox3d box;             ///< in the owner's frame
};

} // namespace

double maxInterpenetration_mm(const Scene& scene) {
  // Dense samples of every instance's surface are tested against the convex hulls of every other
  // instance's components and of the environment's boxes. The hulls contain the meshes, so this
  // over- rather than under-estimates how deep two meshes overlap.
  std::vector<std::vector<ConvexPiece>> part_pieces(scene.parts.size());
  for (std::size_t k = 0; k < scene.parts.size(); ++k)
    for (const auto& comp : scene.parts[k].components)
      part_pieces[k].push_back({hullPlanes(comp.vertices_mm), boundingBox(comp)});
  std::vector<ConvexPiece> env_pieces;
  for (const auto& box : connectedComponents(scene.environment_mm))
    env_pieces.push_back({hullPlanes(box.vertices_mm), boundingBox(box)});

  std::vector<std::vector<Eigen::Vector3d>> samples_world(scene.instances.size());
  std::vector<Eigen::AlignedBox3d> boxes_world(scene.instances.size());
  for (const auto& inst : scene.instances) {
    const TriangleMesh mesh = transformed(scene.parts[inst.part].mesh(), inst.T_world_part);
    std::vector<Eigen::Vector3d> normals;
    const auto n = static_cast<std::size_t>(std::min(40000.0, surfaceArea(mesh))); // ~1 per mm²
    auto& pts = samples_world[static_cast<std::size_t>(inst.id)];
    sampleSurface(mesh, n, 1, pts, normals);
    pts.insert(pts.end(), mesh.vertices_mm.begin(), mesh.vertices_mm.end());
    boxes_world[static_cast<std::size_t>(inst.id)] = boundingBox(mesh);
  }
  double deepest = 0;
  for (const auto& a : scene.instances) {
    const auto ia = static_cast<std::size_t>(a.id);
    for (const auto& p : samples_world[ia])
      for (const auto& piece : env_pieces)
        if (piece.box.exteriorDistance(p) == 0)
          deepest = std::max(deepest, depthInside(piece.planes, p));
    for (const auto& b : scene.instances) {
      const auto ib = static_cast<std::size_t>(b.id);
      if (ia == ib || !boxes_world[ia].intersects(boxes_world[ib]))
        continue;
      const Eigen::Isometry3d T_b_world = b.T_world_part.inverse();
      for (const auto& p_world : samples_world[ia]) {
        if (boxes_world[ib].exteriorDistance(p_world) > 0)
          continue;
        const Eigen::Vector3d p = T_b_world * p_world;
        for (const auto& piece : part_pieces[b.part])
          if (piece.box.exteriorDistance(p) == 0)
            deepest = std::max(deepest, depthInside(piece.planes, p));
      }
    }
  }
  return deepest;
}

} // namespace scanpick::core
