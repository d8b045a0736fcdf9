// The Bullet world shared by every simulated drop (see PhysicsWorld.h).
#include "core/sim/PhysicsWorld.h"

#include <algorithm>
#include <cmath>

namespace scanpick::core::physics {

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

World::World() {
  world.setGravity(btVector3(0, 0, static_cast<btScalar>(-kGravity_mm_s2 / kMmPerUnit)));
}

World::~World() {
  for (auto& b : bodies)
    world.removeRigidBody(b.get());
}

btRigidBody* World::addBody(btCollisionShape* shape, double mass, const btTransform& pose) {
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

void World::addStaticBox(const Eigen::Vector3d& lo_mm, const Eigen::Vector3d& hi_mm) {
  shapes.push_back(std::make_unique<btBoxShape>(toBt(Eigen::Vector3d((hi_mm - lo_mm) / 2))));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = (lo_mm + hi_mm) / 2;
  addBody(shapes.back().get(), 0, toBt(T));
}

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

namespace {

double partVolume_mm3(const Part& part) {
  double v = 0;
  for (const auto& c : part.components)
    v += std::abs(signedVolume(c));
  return v;
}

bool allResting(const World& w, std::size_t first_dynamic) {
  for (std::size_t i = first_dynamic; i < w.bodies.size(); ++i) {
    const btRigidBody& b = *w.bodies[i];
    if (b.getLinearVelocity().length() * kMmPerUnit > 2.0 || b.getAngularVelocity().length() > 0.05)
      return false;
  }
  return true;
}

} // namespace

Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  // Uniform on SO(3): a normalized 4D Gaussian quaternion.
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

double pileTop_mm(const World& w, std::size_t first_dynamic) {
  double top = 0;
  for (std::size_t i = first_dynamic; i < w.bodies.size(); ++i) {
    btVector3 lo, hi;
    w.bodies[i]->getAabb(lo, hi);
    top = std::max(top, static_cast<double>(hi.z()) * kMmPerUnit);
  }
  return top;
}

void simulate(World& w, double seconds, std::size_t first_dynamic, bool stop_when_resting) {
  const int steps = static_cast<int>(seconds / kStep_s);
  for (int s = 0; s < steps; ++s) {
    w.world.stepSimulation(static_cast<btScalar>(kStep_s), 1, static_cast<btScalar>(kStep_s));
    if (stop_when_resting && s % 30 == 29 && allResting(w, first_dynamic))
      return;
  }
}

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

void addPartBody(World& w, btCollisionShape* shape, const Part& part,
                 const Eigen::Isometry3d& T_world_body) {
  const double mass = partVolume_mm3(part) * 1e-3; // grams at 1 g/cm³
  btRigidBody* body = w.addBody(shape, mass, toBt(T_world_body));
  body->setCcdMotionThreshold(static_cast<btScalar>(2.0 / kMmPerUnit));
  body->setCcdSweptSphereRadius(static_cast<btScalar>(1.5 / kMmPerUnit));
  body->setSleepingThresholds(0.05f, 0.05f);
}

} // namespace scanpick::core::physics
