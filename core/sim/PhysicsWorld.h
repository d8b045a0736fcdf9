#pragma once
/// @file PhysicsWorld.h
/// Internal to scanpick_core_sim (it includes Bullet, a private dependency): the Bullet world in
/// which parts are dropped and settle, shared by buildScene / settleScene (SceneBuilder.cpp) and
/// restingPoses (RestingPoses.cpp) so that every simulated drop uses the same physics.

#include "core/sim/Scene.h"

#include <btBulletDynamicsCommon.h>
#include <memory>
#include <random>
#include <vector>

namespace scanpick::core::physics {

/// Bullet is tuned for bodies of about 0.1-10 units: one unit is 10 mm, so parts are ~8 units.
inline constexpr double kMmPerUnit = 10.0;
inline constexpr double kGravity_mm_s2 = 9810.0;
inline constexpr double kStep_s = 1.0 / 300.0;
/// Collision margin outside the hulls (0.4 mm): parts rest slightly apart.
inline constexpr float kMargin_units = 0.04f;

btVector3 toBt(const Eigen::Vector3d& p_mm);
btTransform toBt(const Eigen::Isometry3d& T);
/// A Bullet transform in mm, its rotation re-orthonormalized (Bullet keeps single precision).
Eigen::Isometry3d fromBt(const btTransform& t);

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

  World();
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// A body of `mass` (0 = static) with the friction, restitution and damping of every body.
  btRigidBody* addBody(btCollisionShape* shape, double mass, const btTransform& pose);
  /// A static axis-aligned box between the two corners (mm).
  void addStaticBox(const Eigen::Vector3d& lo_mm, const Eigen::Vector3d& hi_mm);
};

/// A part's compound of convex hulls (one per component), in a body frame centred on the part's
/// bounding box (Part::center_mm, which is also the body's centre of mass); owned by `w`.
btCollisionShape* partShape(World& w, const Part& part, float margin = kMargin_units);

/// Uniformly distributed rotation (a normalized 4D Gaussian quaternion).
Eigen::Matrix3d randomRotation(std::mt19937_64& rng);

/// Highest point of the dynamic bodies (mm), or 0 on an empty floor.
double pileTop_mm(const World& w, std::size_t first_dynamic);

/// Steps the world for `seconds` of simulated time; with `stop_when_resting`, stops as soon as
/// every dynamic body (index >= first_dynamic) rests.
void simulate(World& w, double seconds, std::size_t first_dynamic, bool stop_when_resting);

/// The static bodies of a layout: the bin's floor and walls, or a table top at z = 0.
void addEnvironment(World& w, LayoutKind layout, const BinGeometry& bin);

/// Adds a part as a dynamic body (1 g/cm³) whose frame is centred on the part's bounding box, at
/// T_world_body, with the damping and CCD settings of every dropped part.
void addPartBody(World& w, btCollisionShape* shape, const Part& part,
                 const Eigen::Isometry3d& T_world_body);

} // namespace scanpick::core::physics
