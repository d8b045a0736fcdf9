#include "core/cloud/Sensor.h"

#include "core/common/Error.h"

#include <cmath>

namespace scanpick::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// PhoXi 3D Scanner M (thesis table 4.2): range 458-1118 mm, sweet spot about 650 mm, point size
/// 0.66 mm at 0.8 Mpx and 0.33 mm at 3.2 Mpx, z-noise <= 0.1 mm. The camera-projector baseline
/// (about 0.3 m) is an approximation of the M model's body.
SensorModel phoxiM(int width, int height) {
  SensorModel s;
  s.preset = width > 1500 ? "phoxi-m-2064" : "phoxi-m-1032";
  s.width = width;
  s.height = height;
  const double point_size_mm = width > 1500 ? 0.33 : 0.66;
  s.nominal_distance_mm = 650.0;
  s.fx = s.fy = s.nominal_distance_mm / point_size_mm;
  s.cx = (width - 1) / 2.0;
  s.cy = (height - 1) / 2.0;
  s.T_camera_projector = Eigen::Isometry3d::Identity();
  // The projector looks at the same working volume: it sits 300 mm along +x and is toed in.
  s.T_camera_projector.translation() = Eigen::Vector3d(300.0, 0.0, 0.0);
  s.T_camera_projector.linear() =
      Eigen::AngleAxisd(-std::atan2(300.0, s.nominal_distance_mm), Eigen::Vector3d::UnitY())
          .toRotationMatrix();
  s.min_range_mm = 458.0;
  s.max_range_mm = 1118.0;
  s.noise_sigma_mm = 0.1;
  return s;
}

/// Kinect v1 (thesis table 4.3): 640x480 depth, 58° x 45° field of view, range 0.8-3.5 m,
/// IR projector 75 mm from the IR camera, parallel axes.
SensorModel kinectV1() {
  SensorModel s;
  s.preset = "kinect-v1";
  s.width = 640;
  s.height = 480;
  s.fx = (s.width / 2.0) / std::tan(58.0 / 2.0 * kPi / 180.0);
  s.fy = (s.height / 2.0) / std::tan(45.0 / 2.0 * kPi / 180.0);
  s.cx = 319.5;
  s.cy = 239.5;
  s.T_camera_projector = Eigen::Isometry3d::Identity();
  s.T_camera_projector.translation() = Eigen::Vector3d(75.0, 0.0, 0.0);
  s.min_range_mm = 800.0;
  s.max_range_mm = 3500.0;
  s.nominal_distance_mm = 1200.0;
  s.noise_sigma_mm = 0.0;
  return s;
}

} // namespace

SensorModel sensorPreset(const std::string& name) {
  if (name == "phoxi-m-1032")
    return phoxiM(1032, 772);
  if (name == "phoxi-m-2064")
    return phoxiM(2064, 1544);
  if (name == "kinect-v1")
    return kinectV1();
  std::string known;
  for (const auto& n : sensorPresetNames())
    known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown sensor '" + name + "': use one of " + known);
}

std::vector<std::string> sensorPresetNames() {
  return {"phoxi-m-1032", "phoxi-m-2064", "kinect-v1"};
}

} // namespace scanpick::core
