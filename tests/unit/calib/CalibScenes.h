#pragma once
// A simulated robot cell for the hand-eye calibration tests: the calibration target as a mesh
// (plate + spheres), ground-truth hand-eye poses, robot poses that show the target to the camera
// from about 650 mm (the PhoXi M's sweet spot), tilted 10-30° about varied axes and turned about
// the view axis, and scans of each pose by the virtual scanner.
#include "core/calib/CalibTarget.h"
#include "core/calib/HandEye.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/Renderer.h"

#include <cmath>
#include <random>
#include <vector>

namespace scanpick::test {

inline constexpr double kPi = 3.14159265358979323846;

inline double rad(double deg) {
  return deg * kPi / 180;
}

/// A pose from a translation (mm) and a rotation.
inline Eigen::Isometry3d pose(const Eigen::Vector3d& t, const Eigen::Matrix3d& R) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

inline Eigen::Matrix3d rotation(double deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(rad(deg), axis.normalized()).toRotationMatrix();
}

/// The target as a closed mesh in its own frame: the plate (top face at z = 0) and the spheres
/// (fine enough that the facets lie within 0.004 mm of the true sphere).
inline core::TriangleMesh targetMesh(const core::calib::TargetLayout& t) {
  core::TriangleMesh mesh =
      core::boxMesh({-t.plate_x_mm / 2, -t.plate_y_mm / 2, -t.plate_thickness_mm},
                    {t.plate_x_mm / 2, t.plate_y_mm / 2, 0});
  std::vector<Eigen::Vector2d> profile{{0, -t.sphere_radius_mm}};
  const int rings = 64;
  for (int k = 1; k < rings; ++k) {
    const double phi = kPi * k / rings;
    profile.emplace_back(t.sphere_radius_mm * std::sin(phi), -t.sphere_radius_mm * std::cos(phi));
  }
  profile.emplace_back(0, t.sphere_radius_mm);
  const core::TriangleMesh sphere = core::revolveProfile(profile, 128);
  for (const auto& c : t.sphere_centres_mm)
    mesh.append(core::transformed(sphere, pose(c, Eigen::Matrix3d::Identity())));
  return mesh;
}

/// A robot cell with known hand-eye poses and the robot poses of a calibration run.
struct SimulatedCell {
  core::calib::HandEyeMode mode = core::calib::HandEyeMode::EyeToHand;
  Eigen::Isometry3d X; ///< true T_base_camera (eye-to-hand) or T_flange_camera (eye-in-hand)
  Eigen::Isometry3d Y; ///< true T_flange_target (eye-to-hand) or T_base_target (eye-in-hand)
  std::vector<Eigen::Isometry3d> T_base_flange;   ///< the robot poses
  std::vector<Eigen::Isometry3d> T_camera_target; ///< where the target truly is at each pose
};

/// Where the target stands in front of the camera at pose `i`: centred within ±40 mm of the
/// optical axis at 610-690 mm, facing the camera, tilted 10-30° about an axis that turns from
/// pose to pose, and turned about its normal.
inline Eigen::Isometry3d viewOfTarget(int i, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double tilt = 10 + 20 * (0.5 + 0.5 * u(rng));
  const double tilt_axis = 360.0 * i / 7.0 + 20 * u(rng); // the tilt's direction turns
  const double spin = 60 * u(rng);
  const Eigen::Matrix3d R =
      rotation(180, Eigen::Vector3d::UnitX()) * // target z towards camera
      rotation(tilt, {std::cos(rad(tilt_axis)), std::sin(rad(tilt_axis)), 0}) *
      rotation(spin, Eigen::Vector3d::UnitZ());
  return pose({40 * u(rng), 40 * u(rng), 650 + 40 * u(rng)}, R);
}

/// Eye-to-hand: the camera hangs 1.3 m above the base, looking down, slightly turned; the target
/// is mounted 45 mm off the flange, turned 33°.
inline SimulatedCell eyeToHandCell(int poses, std::uint64_t seed) {
  SimulatedCell cell;
  cell.mode = core::calib::HandEyeMode::EyeToHand;
  cell.X = pose({450, -120, 1300}, rotation(25, Eigen::Vector3d::UnitZ()) *
                                       rotation(184, Eigen::Vector3d::UnitX()) *
                                       rotation(2, Eigen::Vector3d::UnitY()));
  cell.Y = pose({12, -7, 45},
                rotation(33, Eigen::Vector3d::UnitZ()) * rotation(3, Eigen::Vector3d::UnitX()));
  std::mt19937_64 rng(seed);
  for (int i = 0; i < poses; ++i) {
    const Eigen::Isometry3d B = viewOfTarget(i, rng);
    cell.T_camera_target.push_back(B);
    cell.T_base_flange.push_back(cell.X * B * cell.Y.inverse());
  }
  return cell;
}

/// Eye-in-hand: the camera sits 95 mm off the flange, turned 90° and tilted 5°; the target lies
/// on a table in front of the robot, turned -35°.
inline SimulatedCell eyeInHandCell(int poses, std::uint64_t seed) {
  SimulatedCell cell;
  cell.mode = core::calib::HandEyeMode::EyeInHand;
  cell.X = pose({-65, 40, 95},
                rotation(90, Eigen::Vector3d::UnitZ()) * rotation(5, Eigen::Vector3d::UnitY()));
  cell.Y = pose({600, 150, 20}, rotation(-35, Eigen::Vector3d::UnitZ()));
  std::mt19937_64 rng(seed);
  for (int i = 0; i < poses; ++i) {
    const Eigen::Isometry3d B = viewOfTarget(i, rng);
    cell.T_camera_target.push_back(B);
    // B = X⁻¹ · A⁻¹ · Y, so A = Y · B⁻¹ · X⁻¹.
    cell.T_base_flange.push_back(cell.Y * B.inverse() * cell.X.inverse());
  }
  return cell;
}

/// The PhoXi M 1032 scan of pose `i` with its typical noise (or none). Eye-in-hand scenes have the
/// table under the target (its top at the plate's bottom); `with_target` false leaves the target
/// out (a scan that missed it).
inline core::PointCloud scanOf(const SimulatedCell& cell, int i, const core::TriangleMesh& target,
                               bool noisy = true, bool with_target = true) {
  const core::SensorModel sensor = core::sensorPreset("phoxi-m-1032");
  core::Scene scene;
  scene.layout = core::LayoutKind::Teach;
  core::Part part;
  part.name = "calibration-target";
  part.components = {target};
  scene.parts = {part};
  const std::size_t k = std::size_t(i);
  const bool eye_to_hand = cell.mode == core::calib::HandEyeMode::EyeToHand;
  const Eigen::Isometry3d T_base_camera =
      eye_to_hand ? cell.X : cell.T_base_flange[k] * cell.X; // world = robot base
  if (with_target) {
    core::PartInstance instance;
    instance.T_world_part =
        eye_to_hand ? cell.T_base_flange[k] * cell.Y : cell.Y; // the target in the base
    scene.instances.push_back(instance);
  }
  if (!eye_to_hand) {
    const Eigen::Vector3d top = cell.Y * Eigen::Vector3d(0, 0, -10);
    scene.environment_mm = core::boxMesh({top.x() - 1000, top.y() - 1000, top.z() - 40},
                                         {top.x() + 1000, top.y() + 1000, top.z()});
  }
  scene.T_camera_world = T_base_camera.inverse();
  const core::SensorNoise noise =
      noisy ? core::SensorNoise::typical(sensor) : core::SensorNoise::none();
  return core::renderScene(scene, sensor, noise, 1000 + std::uint64_t(i)).cloud;
}

/// Rotation angle between two poses, degrees, and the distance between their origins, mm.
inline double angleBetween_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return core::calib::rotationAngle_deg(a.linear().transpose() * b.linear());
}
inline double distanceBetween_mm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

} // namespace scanpick::test
