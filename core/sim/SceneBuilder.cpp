// Rigid-body drop of parts into a bin or onto a table with Bullet.
#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/Scene.h"
#include "core/sim/Settle.h"

#include <LinearMath/btConvexHullComputer.h>
#include <algorithm>
#include <btBulletCollisionCommon.h>
#include <btBulletDynamicsCommon.h>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

namespace scanpick::core {
namespace {

/// Bullet is tuned for bodies of about 0.1-10 units: one unit is 10 mm, so parts are ~8 units.
constexpr double kMmPerUnit = 10.0;
constexpr double kGravity_mm_s2 = 9810.0;
constexpr double kStep_s = 1.0 / 300.0;
constexpr float kMargin_units = 0.04f; // 0.4 mm, outside the hulls: parts rest slightly apart

btVector3 toBt(const Eigen::Vector3d& p_mm) {
  return {static_cast<btScalar>(p_mm.x() / kMmPerUnit),
          static_cast<btScalar>(p_mm.y() / kMmPerUnit),
          static_cast<btScalar>(p_mm.z() / kMmPerUnit)};
}

Eigen::Isometry3d fromBt(const btTransform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const btMatrix3x3& b = t.getBasis();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      T.linear()(r, c) = b[r][c];
  // Bullet keeps single-precision matrices: re-orthonormalize so poses are exact rotations.
  T.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  T.translation() =
      Eigen::Vector3d(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z()) * kMmPerUnit;
  return T;
}

btTransform toBt(const Eigen::Isometry3d& T) {
  btMatrix3x3 b;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      b[r][c] = static_cast<btScalar>(T.linear()(r, c));
  return btTransform(b, toBt(Eigen::Vector3d(T.translation())));
}

/// The dynamics world with every object it owns.
struct World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;

  World() {
    world.setGravity(btVector3(0, 0, static_cast<btScalar>(-kGravity_mm_s2 / kMmPerUnit)));
  }
  ~World() {
    for (auto& b : bodies)
      world.removeRigidBody(b.get());
  }
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  btRigidBody* addBody(btCollisionShape* shape, double mass, const btTransform& pose) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0)
      shape->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
    states.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), states.back().get(),
                                                  shape, inertia);
    info.m_friction = 0.6f;
    info.m_restitution = 0.05f;
    info.m_linearDamping = 0.05f;
    info.m_angularDamping = 0.2f;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(bodies.back().get());
    return bodies.back().get();
  }

  void addStaticBox(const Eigen::Vector3d& lo_mm, const Eigen::Vector3d& hi_mm) {
    shapes.push_back(std::make_unique<btBoxShape>(toBt(Eigen::Vector3d((hi_mm - lo_mm) / 2))));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = (lo_mm + hi_mm) / 2;
    addBody(shapes.back().get(), 0, toBt(T));
  }
};

/// A part's compound of convex hulls, in a body frame centred on the part's bounding box.
btCollisionShape* partShape(World& w, const Part& part, float margin) {
  const Eigen::Vector3d c = part.center_mm();
  auto compound = std::make_unique<btCompoundShape>();
  for (const auto& comp : part.components) {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const auto& v : comp.vertices_mm)
      hull->addPoint(toBt(Eigen::Vector3d(v - c)), false);
    hull->recalcLocalAabb();
    hull->optimizeConvexHull();
    hull->setMargin(margin);
    compound->addChildShape(btTransform::getIdentity(), hull.get());
    w.shapes.push_back(std::move(hull));
  }
  w.shapes.push_back(std::move(compound));
  return w.shapes.back().get();
}

double partVolume_mm3(const Part& part) {
  double v = 0;
  for (const auto& c : part.components)
    v += std::abs(signedVolume(c));
  return v;
}

Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  // Uniform on SO(3): a normalized 4D Gaussian quaternion.
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// Highest point of the dynamic bodies (mm), or 0 on an empty floor.
double pileTop_mm(const World& w, std::size_t first_dynamic) {
  double top = 0;
  for (std::size_t i = first_dynamic; i < w.bodies.size(); ++i) {
    btVector3 lo, hi;
    w.bodies[i]->getAabb(lo, hi);
    top = std::max(top, static_cast<double>(hi.z()) * kMmPerUnit);
  }
  return top;
}

bool allResting(const World& w, std::size_t first_dynamic) {
  for (std::size_t i = first_dynamic; i < w.bodies.size(); ++i) {
    const btRigidBody& b = *w.bodies[i];
    if (b.getLinearVelocity().length() * kMmPerUnit > 2.0 || b.getAngularVelocity().length() > 0.05)
      return false;
  }
  return true;
}

void simulate(World& w, double seconds, std::size_t first_dynamic, bool stop_when_resting) {
  const int steps = static_cast<int>(seconds / kStep_s);
  for (int s = 0; s < steps; ++s) {
    w.world.stepSimulation(static_cast<btScalar>(kStep_s), 1, static_cast<btScalar>(kStep_s));
    if (stop_when_resting && s % 30 == 29 && allResting(w, first_dynamic))
      return;
  }
}

/// The static bodies of a layout: the bin's floor and walls, or a table.
void addEnvironment(World& w, LayoutKind layout, const BinGeometry& b) {
  if (layout == LayoutKind::Bin) {
    // Walls go well above the rendered rim so that nothing bounces out of the bin.
    const double hx = b.inner_x_mm / 2, hy = b.inner_y_mm / 2, t = b.wall_thickness_mm, h = 2000;
    w.addStaticBox({-hx - t, -hy - t, -t}, {hx + t, hy + t, 0});
    w.addStaticBox({-hx - t, -hy - t, 0}, {-hx, hy + t, h});
    w.addStaticBox({hx, -hy - t, 0}, {hx + t, hy + t, h});
    w.addStaticBox({-hx, -hy - t, 0}, {hx, -hy, h});
    w.addStaticBox({-hx, hy, 0}, {hx, hy + t, h});
  } else {
    w.addStaticBox({-600, -600, -20}, {600, 600, 0});
  }
}

/// Adds a part as a dynamic body whose frame is centred on the part's bounding box, at
/// T_world_body, with the damping and CCD settings of every dropped part.
void addPartBody(World& w, btCollisionShape* shape, const Part& part,
                 const Eigen::Isometry3d& T_world_body) {
  const double mass = partVolume_mm3(part) * 1e-3; // grams at 1 g/cm³
  btRigidBody* body = w.addBody(shape, mass, toBt(T_world_body));
  body->setCcdMotionThreshold(static_cast<btScalar>(2.0 / kMmPerUnit));
  body->setCcdSweptSphereRadius(static_cast<btScalar>(1.5 / kMmPerUnit));
  body->setSleepingThresholds(0.05f, 0.05f);
}

} // namespace

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

Scene buildScene(const SceneSpec& spec, const SensorModel& sensor, const ProgressFn& progress) {
  if (spec.parts.empty())
    throw Error("no part to place: give a built-in part name or a mesh file");
  if (spec.count < 1)
    throw Error("the scene needs at least one instance (count is " + std::to_string(spec.count) +
                ")");
  if (spec.teach_side < 0 || spec.teach_side > kTeachSides - 1)
    throw Error("teach side " + std::to_string(spec.teach_side) + " does not exist: use 0 to " +
                std::to_string(kTeachSides - 1));
  if (spec.layout == LayoutKind::Teach && spec.count != 1)
    throw Error("a teach scene holds exactly one part (count is " + std::to_string(spec.count) +
                ")");
  if (spec.count > 200)
    throw Error("at most 200 instances per scene (count is " + std::to_string(spec.count) + ")");

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
  const std::size_t first_dynamic = w.bodies.size();
  std::vector<btCollisionShape*> shapes;
  for (const auto& p : scene.parts)
    shapes.push_back(partShape(w, p, kMargin_units));

  auto spawn = [&](int id, const Eigen::Matrix3d& R, const Eigen::Vector3d& center_world_mm) {
    const Part& part = scene.parts[static_cast<std::size_t>(id) % scene.parts.size()];
    Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
    T_world_body.linear() = R;
    T_world_body.translation() = center_world_mm;
    addPartBody(w, shapes[static_cast<std::size_t>(id) % shapes.size()], part, T_world_body);
  };
  const int n = spec.count;
  if (spec.layout == LayoutKind::Bin) {
    // One at a time, from just above the pile, so no two start overlapping.
    for (int id = 0; id < n; ++id) {
      const Part& part = scene.parts[static_cast<std::size_t>(id) % scene.parts.size()];
      const double r = part.diameter_mm() / 2;
      const double mx = std::max(0.0, spec.bin.inner_x_mm / 2 - r),
                   my = std::max(0.0, spec.bin.inner_y_mm / 2 - r);
      const Eigen::Matrix3d R = randomRotation(rng);
      const double x = (2 * unit(rng) - 1) * mx, y = (2 * unit(rng) - 1) * my;
      spawn(id, R, {x, y, pileTop_mm(w, first_dynamic) + r + 5});
      simulate(w, 0.35, first_dynamic, false);
      reportProgress(progress, 0.8 * (id + 1) / n);
    }
    simulate(w, 3.0, first_dynamic, true);
  } else if (spec.layout == LayoutKind::Scatter) {
    // Grid cells larger than the biggest part, shuffled, so instances start apart.
    double d = 0;
    for (const auto& p : scene.parts)
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
      spawn(id, R, {gx + (unit(rng) - 0.5) * 10, gy + (unit(rng) - 0.5) * 10, d / 2 + 3});
    }
    simulate(w, 3.0, first_dynamic, true);
  } else {
    const Part& part = scene.parts.front();
    const double yaw = unit(rng) * 2 * 3.14159265358979323846;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                              teachSideTurn(spec.teach_side) * part.R_table_part;
    // Lowest point of the part in this orientation, relative to its centre.
    double low = 0;
    for (const auto& c : part.components)
      for (const auto& v : c.vertices_mm)
        low = std::min(low, (R * (v - part.center_mm())).z());
    spawn(0, R, {(unit(rng) - 0.5) * 40, (unit(rng) - 0.5) * 40, -low + 1.0});
    simulate(w, 2.0, first_dynamic, true);
  }
  reportProgress(progress, 1.0);

  for (int id = 0; id < n; ++id) {
    const btRigidBody& body = *w.bodies[first_dynamic + static_cast<std::size_t>(id)];
    PartInstance inst;
    inst.id = id;
    inst.part = static_cast<std::size_t>(id) % scene.parts.size();
    Eigen::Isometry3d T_body_part = Eigen::Isometry3d::Identity();
    T_body_part.translation() = -scene.parts[inst.part].center_mm();
    inst.T_world_part = fromBt(body.getWorldTransform()) * T_body_part;
    scene.instances.push_back(inst);
  }

  // Camera straight above the origin: camera x = world x, camera y = -world y, z down.
  const double height = spec.camera_height_mm > 0 ? spec.camera_height_mm
                                                  : defaultCameraHeight_mm(sensor, spec.layout);
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  T_world_camera.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  T_world_camera.translation() = Eigen::Vector3d(0, 0, height);
  scene.T_camera_world = T_world_camera.inverse();

  if (spec.layout == LayoutKind::Teach) {
    // The operator's box: the part's extent plus 10 mm around, starting 1 mm above the table so the
    // table itself stays out.
    const auto& inst = scene.instances.front();
    Eigen::AlignedBox3d box =
        boundingBox(transformed(scene.parts[inst.part].mesh(), inst.T_world_part));
    box.min() -= Eigen::Vector3d(10, 10, 0);
    box.max() += Eigen::Vector3d(10, 10, 10);
    box.min().z() = 1.0;
    scene.crop_box_world = box;
  }
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
