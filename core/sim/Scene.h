#pragma once
/// @file Scene.h
/// A simulated scene: parts at rest in a bin or on a table, seen by a camera from above.

#include "core/cloud/Sensor.h"
#include "core/common/Progress.h"
#include "core/sim/Part.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core {

/// How instances are arranged: dropped into a bin, scattered apart on a table, or a single part
/// on a table (the scan an operator teaches a model from).
enum class LayoutKind { Bin, Scatter, Teach };

/// "bin", "scatter", "teach".
std::string layoutName(LayoutKind layout);
/// Inverse of layoutName; throws Error naming the valid layouts.
LayoutKind layoutFromName(const std::string& name);

/// One placed part. The world frame has the floor (table) at z = 0, z up, bin centred at the
/// origin.
struct PartInstance {
  int id = 0;
  std::size_t part = 0; ///< index into Scene::parts
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
};

/// The bin: inner size and wall height, mm. The walls are 10 mm thick.
struct BinGeometry {
  double inner_x_mm = 360, inner_y_mm = 280, wall_height_mm = 150, wall_thickness_mm = 10;
};

/// What buildScene should make.
struct SceneSpec {
  LayoutKind layout = LayoutKind::Bin;
  std::vector<Part> parts; ///< instance k uses parts[k % parts.size()]
  int count = 8;           ///< instances (teach: must be 1)
  std::uint64_t seed = 0;  ///< drives poses and drop positions
  BinGeometry bin;
  /// Camera height above the floor, mm; 0 = the sensor's default for the layout (PhoXi: 850 bin,
  /// 700 scatter/teach; Kinect: 1100 bin, 1000 scatter/teach), for a teach scene raised so that
  /// the part's top stays 50 mm beyond the sensor's near limit.
  double camera_height_mm = 0;
  /// Teach scenes: which side the part rests on. 0 = its usual rest pose (Part::R_table_part);
  /// 1-3 = turned over (180° about x), on its side (90° about x) or on its end (90° about y)
  /// before it is dropped, so the camera sees other sides (one taught view each).
  int teach_side = 0;
  /// Teach scenes: rest the part on its N-th most probable distinct resting pose instead
  /// (restingPoses with default RestingPoseParams, core/sim/RestingPoses.h), with a random yaw;
  /// teach_side must then be 0. Unset = teach_side decides.
  std::optional<int> resting_side;
};

/// A scene at rest.
struct Scene {
  LayoutKind layout = LayoutKind::Bin;
  std::uint64_t seed = 0;
  std::vector<Part> parts;
  std::vector<PartInstance> instances;
  TriangleMesh environment_mm; ///< floor or table and bin walls, world frame (closed boxes)
  BinGeometry bin;             ///< the bin's size (bin layouts)
  /// World in the camera (= scene) frame: the camera looks straight down at the origin.
  Eigen::Isometry3d T_camera_world = Eigen::Isometry3d::Identity();
  /// Teach scenes: the box an operator would draw around the part, world frame (axis-aligned).
  std::optional<Eigen::AlignedBox3d> crop_box_world;

  /// Pose of an instance's part frame in the scene (camera) frame.
  [[nodiscard]] Eigen::Isometry3d T_scene_part(const PartInstance& instance) const {
    return T_camera_world * instance.T_world_part;
  }
};

/// Number of teach sides (SceneSpec::teach_side is 0 .. kTeachSides - 1).
inline constexpr int kTeachSides = 4;

/// The turn applied to a part's usual rest pose before a teach scene drops it on side `side`.
Eigen::Matrix3d teachSideTurn(int side);

/// The environment of a layout, world frame (closed boxes): for a bin, its floor and walls and the
/// ground it stands on; otherwise a table top at z = 0.
TriangleMesh environmentMesh(LayoutKind layout, const BinGeometry& bin);

/// Default camera height above the floor (mm) for a sensor and layout (see SceneSpec).
double defaultCameraHeight_mm(const SensorModel& sensor, LayoutKind layout);

/// Drops the instances with rigid-body physics (Bullet) until they rest: one after the other from
/// just above the pile into the bin, spread apart onto a table, or a single part in its natural
/// pose (Part::R_table_part, random yaw; or the side SceneSpec::teach_side / resting_side
/// names). Deterministic for a given spec. Throws Error for count < 1, a teach layout with
/// count != 1, no parts, or a teach / resting side that does not exist (naming how many there
/// are). Progress covers the simulation.
Scene buildScene(const SceneSpec& spec, const SensorModel& sensor, const ProgressFn& progress = {});

/// Deepest interpenetration (mm): how far dense surface samples (about 1 per mm², plus the
/// vertices) of each instance lie inside the convex hulls of other instances' components or of the
/// environment's boxes. The hulls contain the meshes, so the meshes overlap at most this much.
/// 0 when nothing overlaps.
double maxInterpenetration_mm(const Scene& scene);

} // namespace scanpick::core
