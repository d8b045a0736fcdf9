#include "core/calib/BaseFrame.h"

#include "core/calib/CalibJson.h"
#include "core/common/Error.h"

#include <cmath>
#include <cstdlib>

namespace scanpick::core::calib {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const Eigen::Isometry3d& T) {
  return T.matrix().allFinite();
}

/// The rotation part is a rotation: orthonormal within 1e-3, determinant +1.
bool isRotation(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-3 && R.determinant() > 0;
}

} // namespace

CameraCalibration loadCameraCalibration(const std::filesystem::path& path) {
  const HandEyeResult r = loadCalibration(path);
  const std::string source = std::string("'").append(path.string()).append("'");
  // loadCalibration snaps what it reads to a rotation; the checks here keep that promise for
  // any later change of the reader, as the base-frame poses depend on nothing else.
  if (!finite(r.T_camera))
    throw Error(source + " " + r.cameraName() + " holds a number that is not finite");
  if (!isRotation(r.T_camera.linear()))
    throw Error(source + " " + r.cameraName() + ": the rotation is not orthonormal");
  CameraCalibration c;
  c.mode = r.mode;
  c.T_camera = r.T_camera;
  c.file = path.filename().string();
  return c;
}

Eigen::Isometry3d baseFromCamera(const CameraCalibration& calibration,
                                 const std::optional<Eigen::Isometry3d>& T_base_flange) {
  if (calibration.mode == HandEyeMode::EyeToHand) {
    if (T_base_flange)
      throw Error(calibration.file +
                  " is an eye-to-hand calibration (the camera stands still): it needs no flange "
                  "pose; leave the flange pose out, or use the eye-in-hand calibration if the "
                  "camera rides on the flange");
    return calibration.T_camera;
  }
  if (!T_base_flange)
    throw Error(calibration.file +
                " is an eye-in-hand calibration (the camera rides on the flange): give the flange "
                "pose at which the scan was taken (x, y, z in mm and a rotation vector in degrees, "
                "in the robot base)");
  if (!finite(*T_base_flange) || !isRotation(T_base_flange->linear()))
    throw Error("the flange pose is not a finite rigid pose");
  return *T_base_flange * calibration.T_camera;
}

Eigen::Isometry3d poseFromRotationVector(const Eigen::Vector3d& position_mm,
                                         const Eigen::Vector3d& rotation_vector_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const double angle_deg = rotation_vector_deg.norm();
  if (angle_deg > 0)
    T.linear() = Eigen::AngleAxisd(angle_deg * kPi / 180, rotation_vector_deg / angle_deg)
                     .toRotationMatrix();
  T.translation() = position_mm;
  return T;
}

Eigen::Isometry3d flangePoseFromNumbers(const std::vector<double>& n, const std::string& what) {
  if (n.size() != 6 && n.size() != 7)
    throw Error(what +
                " must be 6 numbers x,y,z,rx,ry,rz (mm; rotation vector in degrees) or 7 "
                "numbers x,y,z,qw,qx,qy,qz (mm; unit quaternion, w first), not " +
                std::to_string(n.size()));
  for (double v : n)
    if (!std::isfinite(v))
      throw Error(what + " holds a number that is not finite");
  const Eigen::Vector3d position(n[0], n[1], n[2]);
  if (n.size() == 6)
    return poseFromRotationVector(position, Eigen::Vector3d(n[3], n[4], n[5]));
  Eigen::Quaterniond q(n[3], n[4], n[5], n[6]);
  if (std::abs(q.norm() - 1) > 1e-3)
    throw Error(what + ": the quaternion (qw, qx, qy, qz) must have length 1 (check the order: "
                       "scanpick reads w first)");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = position;
  return T;
}

Eigen::Isometry3d parseFlangePose(const std::string& text, const std::string& what) {
  std::vector<double> numbers;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    bool rest_blank = end != item.c_str();
    for (const char* c = end; rest_blank && *c != '\0'; ++c)
      rest_blank = *c == ' ';
    if (!rest_blank)
      throw Error(what + " '" + text +
                  "': expected comma-separated numbers x,y,z,rx,ry,rz (mm; rotation vector in "
                  "degrees), e.g. 400,-20,550,180,0,0");
    numbers.push_back(v);
    if (comma == std::string::npos)
      break;
    start = comma + 1;
  }
  return flangePoseFromNumbers(numbers, what);
}

nlohmann::json basePoseJson(const Eigen::Isometry3d& T) {
  nlohmann::json matrix = nlohmann::json::array();
  for (int r = 0; r < 4; ++r)
    matrix.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  Eigen::Quaterniond q(T.linear());
  if (q.w() < 0)
    q.coeffs() = -q.coeffs(); // the same rotation; w >= 0 reads more easily
  const Eigen::Vector3d t = T.translation();
  return {{"matrix", matrix},
          {"position_mm", {t.x(), t.y(), t.z()}},
          {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

} // namespace scanpick::core::calib
