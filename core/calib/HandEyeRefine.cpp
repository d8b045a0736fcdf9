#include "core/calib/HandEyeRefine.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace scanpick::core::calib::detail {
namespace {

cv::Mat rotationMat(const Eigen::Isometry3d& T) {
  cv::Mat R(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      R.at<double>(r, c) = T.linear()(r, c);
  return R;
}

cv::Mat translationMat(const Eigen::Isometry3d& T) {
  cv::Mat t(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r)
    t.at<double>(r, 0) = T.translation()[r];
  return t;
}

/// The rigid transform of OpenCV's rotation and translation; false when they are not finite or
/// the rotation is not one (OpenCV returns the nearest rotation, so only a failure trips this).
bool toIsometry(const cv::Mat& R, const cv::Mat& t, Eigen::Isometry3d& T) {
  if (R.rows != 3 || R.cols != 3 || t.total() != 3)
    return false;
  cv::Mat R64, t64;
  R.convertTo(R64, CV_64F);
  t.convertTo(t64, CV_64F);
  Eigen::Matrix3d M;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      M(r, c) = R64.at<double>(r, c);
  if (!M.allFinite())
    return false;
  // Snap to the nearest rotation: the refinement assumes an exact one.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  if (rotation.determinant() < 0 || (rotation - M).norm() > 0.1)
    return false;
  T = Eigen::Isometry3d::Identity();
  T.linear() = rotation;
  T.translation() = Eigen::Vector3d(t64.at<double>(0), t64.at<double>(1), t64.at<double>(2));
  return T.translation().allFinite();
}

/// `T` turned by the rotation vector `w` (radians) and shifted by `v` (mm), both in its own frame.
Eigen::Isometry3d applied(const Eigen::Isometry3d& T, const Eigen::Vector3d& w,
                          const Eigen::Vector3d& v) {
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  const double angle = w.norm();
  if (angle > 0)
    D.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  D.translation() = v;
  return T * D;
}

Solution applied(const Solution& s, const Eigen::Matrix<double, 12, 1>& delta) {
  return {applied(s.X, delta.segment<3>(0), delta.segment<3>(3)),
          applied(s.Y, delta.segment<3>(6), delta.segment<3>(9))};
}

Eigen::VectorXd residuals(const std::vector<PoseData>& poses, const Solution& s) {
  std::size_t n = 0;
  for (const auto& p : poses)
    n += p.centres.size();
  Eigen::VectorXd r(Eigen::Index(3 * n));
  const Eigen::Isometry3d X_inv = s.X.inverse();
  Eigen::Index row = 0;
  for (const auto& p : poses) {
    const Eigen::Isometry3d B = X_inv * p.M * s.Y;
    for (const auto& c : p.centres) {
      r.segment<3>(row) = B * c.target_mm - c.camera_mm;
      row += 3;
    }
  }
  return r;
}

} // namespace

bool openCvSolution(const std::vector<PoseData>& poses, bool shah, Solution& solution) {
  std::vector<cv::Mat> R_world2cam, t_world2cam, R_base2gripper, t_base2gripper;
  for (const auto& p : poses) {
    // OpenCV's form: ^cT_w · ^wT_b = ^cT_g · ^gT_b, i.e. B_i · Y⁻¹ = X⁻¹ · M_i.
    R_world2cam.push_back(rotationMat(p.B));
    t_world2cam.push_back(translationMat(p.B));
    R_base2gripper.push_back(rotationMat(p.M));
    t_base2gripper.push_back(translationMat(p.M));
  }
  cv::Mat R_base2world, t_base2world, R_gripper2cam, t_gripper2cam;
  try {
    cv::calibrateRobotWorldHandEye(R_world2cam, t_world2cam, R_base2gripper, t_base2gripper,
                                   R_base2world, t_base2world, R_gripper2cam, t_gripper2cam,
                                   shah ? cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH
                                        : cv::CALIB_ROBOT_WORLD_HAND_EYE_LI);
  } catch (const cv::Exception&) {
    return false;
  }
  Eigen::Isometry3d Y_inv, X_inv;
  if (!toIsometry(R_base2world, t_base2world, Y_inv) ||
      !toIsometry(R_gripper2cam, t_gripper2cam, X_inv))
    return false;
  solution.X = X_inv.inverse();
  solution.Y = Y_inv.inverse();
  return true;
}

double refineSolution(const std::vector<PoseData>& poses, Solution& solution, int max_iterations) {
  using Vector12d = Eigen::Matrix<double, 12, 1>;
  Eigen::VectorXd r = residuals(poses, solution);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  // Central differences: the residuals are smooth and 12 unknowns make this cheap; a step of
  // 1e-6 (rad or mm) keeps truncation and rounding errors far below the sensor noise.
  constexpr double kStep = 1e-6;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Eigen::MatrixXd J(r.size(), 12);
    for (int j = 0; j < 12; ++j) {
      Vector12d d = Vector12d::Zero();
      d[j] = kStep;
      J.col(j) =
          (residuals(poses, applied(solution, d)) - residuals(poses, applied(solution, -d))) /
          (2 * kStep);
    }
    const Eigen::Matrix<double, 12, 12> H = J.transpose() * J;
    const Vector12d g = J.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Eigen::Matrix<double, 12, 12> A = H;
      A.diagonal() += lambda * H.diagonal().cwiseMax(1e-12);
      const Vector12d delta = A.ldlt().solve(-g);
      if (!delta.allFinite())
        break;
      const Solution trial = applied(solution, delta);
      const Eigen::VectorXd r_trial = residuals(poses, trial);
      const double trial_cost = r_trial.squaredNorm();
      if (trial_cost < cost) {
        const double gain = cost - trial_cost;
        solution = trial;
        r = r_trial;
        cost = trial_cost;
        lambda = std::max(lambda / 10, 1e-12);
        improved = true;
        if (delta.norm() < 1e-10 || gain < 1e-14 * (1 + cost))
          return cost;
      } else {
        lambda *= 10;
      }
    }
    if (!improved)
      break; // at the minimum within rounding
  }
  return cost;
}

} // namespace scanpick::core::calib::detail
