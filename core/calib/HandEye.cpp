#include "core/calib/HandEye.h"

#include "core/calib/HandEyeRefine.h"
#include "core/common/Error.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace scanpick::core::calib {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

/// median + factor × 1.4826 × MAD of `values`, but at least `floor`.
double robustLimit(const std::vector<double>& values, double factor, double floor) {
  const double m = median(values);
  std::vector<double> deviations;
  for (const double v : values)
    deviations.push_back(std::abs(v - m));
  return std::max(floor, m + factor * 1.4826 * median(deviations));
}

detail::PoseData poseData(HandEyeMode mode, const HandEyeSample& sample,
                          const TargetLayout& layout) {
  detail::PoseData p;
  p.M = mode == HandEyeMode::EyeToHand ? sample.T_base_flange : sample.T_base_flange.inverse();
  p.B = sample.observation.T_camera_target;
  const auto& centres = sample.observation.centres_camera_mm;
  for (std::size_t k = 0; k < centres.size() && k < layout.sphere_centres_mm.size(); ++k)
    if (centres[k])
      p.centres.push_back({layout.sphere_centres_mm[k], *centres[k]});
  return p;
}

/// The best refined solution from OpenCV's two closed forms (Shah, Li).
detail::Solution solve(const std::vector<detail::PoseData>& poses, int max_iterations) {
  detail::Solution best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (const bool shah : {true, false}) {
    detail::Solution s;
    if (!detail::openCvSolution(poses, shah, s))
      continue;
    const double cost = detail::refineSolution(poses, s, max_iterations);
    if (cost < best_cost)
      best_cost = cost, best = s;
  }
  if (!std::isfinite(best_cost))
    throw Error("the hand-eye equations have no solution for these poses (OpenCV's "
                "calibrateRobotWorldHandEye failed): record poses rotated 15-30 degrees about at "
                "least two different axes");
  return best;
}

PoseResidual residualOf(int index, const detail::PoseData& p, const detail::Solution& s) {
  PoseResidual r;
  r.index = index;
  const Eigen::Isometry3d predicted = s.X.inverse() * p.M * s.Y;
  double sum_sq = 0;
  for (const auto& c : p.centres) {
    const double d = (predicted * c.target_mm - c.camera_mm).norm();
    sum_sq += d * d;
    r.max_mm = std::max(r.max_mm, d);
  }
  r.rms_mm = p.centres.empty() ? 0.0 : std::sqrt(sum_sq / double(p.centres.size()));
  r.rot_deg = rotationAngle_deg(predicted.linear().transpose() * p.B.linear());
  return r;
}

} // namespace

std::string modeName(HandEyeMode mode) {
  return mode == HandEyeMode::EyeToHand ? "eye-to-hand" : "eye-in-hand";
}

HandEyeMode modeFromName(const std::string& name) {
  if (name == "eye-to-hand")
    return HandEyeMode::EyeToHand;
  if (name == "eye-in-hand")
    return HandEyeMode::EyeInHand;
  throw Error(std::string("unknown calibration mode '")
                  .append(name)
                  .append("': use eye-to-hand (fixed camera, target on the flange) or eye-in-hand "
                          "(camera on the flange, fixed target)"));
}

std::string HandEyeResult::cameraName() const {
  return mode == HandEyeMode::EyeToHand ? "T_base_camera" : "T_flange_camera";
}

std::string HandEyeResult::targetName() const {
  return mode == HandEyeMode::EyeToHand ? "T_flange_target" : "T_base_target";
}

double rotationAngle_deg(const Eigen::Matrix3d& R) {
  const double c = std::clamp((R.trace() - 1) / 2, -1.0, 1.0);
  // acos loses precision near 0; the skew part's norm is 2 sin(angle).
  const Eigen::Vector3d s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(s.norm() / 2, c) * kDegPerRad;
}

void checkMotion(const std::vector<Eigen::Isometry3d>& T_base_flange, const HandEyeParams& params) {
  std::vector<Eigen::Vector3d> axes;
  double largest = 0;
  for (std::size_t i = 0; i < T_base_flange.size(); ++i)
    for (std::size_t j = i + 1; j < T_base_flange.size(); ++j) {
      const Eigen::AngleAxisd turn(T_base_flange[i].linear().transpose() *
                                   T_base_flange[j].linear());
      const double angle = rotationAngle_deg(turn.toRotationMatrix());
      largest = std::max(largest, angle);
      if (angle >= params.min_rotation_deg)
        axes.push_back(turn.axis().normalized());
    }
  if (axes.empty())
    throw Error(std::string("degenerate motion: the robot poses turn at most ")
                    .append(fixed(largest, 1))
                    .append(" degrees against one another (at least ")
                    .append(fixed(params.min_rotation_deg, 1))
                    .append(" are needed): turn the flange 15-30 degrees about at least two "
                            "different axes between the poses"));
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& a : axes)
    scatter += a * a.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d main_axis = eig.eigenvectors().col(2);
  double spread = 0;
  for (const auto& a : axes)
    spread = std::max(spread, std::acos(std::min(1.0, std::abs(a.dot(main_axis)))) * kDegPerRad);
  if (spread < params.min_axis_spread_deg)
    throw Error(std::string("degenerate motion: all rotations between the robot poses are about "
                            "(nearly) one axis (within ")
                    .append(fixed(spread, 1))
                    .append(" degrees), which leaves the calibration undetermined: add poses "
                            "turned about another axis (at least ")
                    .append(fixed(params.min_axis_spread_deg, 0))
                    .append(" degrees away), e.g. tilt about x and about y as well as turn "
                            "about z"));
}

void checkPoses(const std::vector<Eigen::Isometry3d>& T_base_flange, const HandEyeParams& params) {
  if (T_base_flange.size() < 3)
    throw Error(std::string("too few poses: ")
                    .append(std::to_string(T_base_flange.size()))
                    .append(" given; a hand-eye calibration needs at least 3 robot poses with "
                            "rotations about non-parallel axes (10 or more, turned 15-30 degrees "
                            "about different axes, give the best result)"));
  checkMotion(T_base_flange, params);
}

namespace {

/// Each sample's pose data for `mode`; throws Error for a pose with fewer than 3 sphere centres.
std::vector<detail::PoseData> checkedPoseData(HandEyeMode mode,
                                              const std::vector<HandEyeSample>& samples,
                                              const TargetLayout& layout) {
  std::vector<detail::PoseData> data;
  for (int i = 0; i < int(samples.size()); ++i) {
    data.push_back(poseData(mode, samples[std::size_t(i)], layout));
    if (data.back().centres.size() < 3)
      throw Error(std::string("pose ")
                      .append(std::to_string(i + 1))
                      .append(" has only ")
                      .append(std::to_string(data.back().centres.size()))
                      .append(" sphere centres of the target: at least 3 are needed"));
  }
  return data;
}

/// The residuals of the active poses against one solution and the worst outlier among them.
struct Outlier {
  std::vector<double> mm, deg; ///< RMS (mm) and rotation (degrees) per active pose
  double limit_mm = 0, limit_deg = 0;
  int worst = -1; ///< index into the active poses of the worst beyond a limit; -1: none
};

/// Finds the active pose furthest beyond the robust limits (median + factor × scaled MAD).
Outlier worstOutlier(const std::vector<int>& active, const std::vector<detail::PoseData>& data,
                     const detail::Solution& solution, const HandEyeParams& params) {
  Outlier o;
  for (const int i : active) {
    const PoseResidual r = residualOf(i, data[std::size_t(i)], solution);
    o.mm.push_back(r.rms_mm);
    o.deg.push_back(r.rot_deg);
  }
  o.limit_mm = robustLimit(o.mm, params.outlier_mad_factor, params.outlier_floor_mm);
  o.limit_deg = robustLimit(o.deg, params.outlier_mad_factor, params.outlier_floor_deg);
  double worst_excess = 1.0;
  for (std::size_t a = 0; a < active.size(); ++a) {
    const double excess = std::max(o.mm[a] / o.limit_mm, o.deg[a] / o.limit_deg);
    if (excess > worst_excess)
      worst_excess = excess, o.worst = int(a);
  }
  return o;
}

/// Solves over all poses, then rejects the worst outlier and solves again until none is left,
/// writing each rejected pose's reason into `residuals` (one per sample). Throws Error when more
/// than max_rejected_fraction of the poses, or all but 3, would have to go.
detail::Solution solveRejectingOutliers(const std::vector<HandEyeSample>& samples,
                                        const std::vector<detail::PoseData>& data,
                                        const HandEyeParams& params,
                                        std::vector<PoseResidual>& residuals) {
  const int n = int(samples.size());
  std::vector<int> active(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    active[std::size_t(i)] = i;
  const int max_rejected = int(std::floor(params.max_rejected_fraction * n));
  detail::Solution solution;
  for (;;) {
    std::vector<Eigen::Isometry3d> flanges;
    std::vector<detail::PoseData> used;
    for (const int i : active) {
      flanges.push_back(samples[std::size_t(i)].T_base_flange);
      used.push_back(data[std::size_t(i)]);
    }
    checkMotion(flanges, params);
    solution = solve(used, params.max_iterations);
    // The worst pose goes first: a wrong pose drags the solution and with it the others'
    // residuals, which settle once it is out.
    const Outlier o = worstOutlier(active, data, solution, params);
    if (o.worst < 0)
      break;
    const auto worst = std::size_t(o.worst);
    const int rejected_index = active[worst];
    const int rejected_count = n - int(active.size()) + 1;
    if (rejected_count > max_rejected || int(active.size()) - 1 < 3)
      throw Error(std::string("the poses disagree: after rejecting ")
                      .append(std::to_string(rejected_count - 1))
                      .append(" pose(s), pose ")
                      .append(std::to_string(rejected_index + 1))
                      .append(" still misses the others' solution by ")
                      .append(fixed(o.mm[worst], 2))
                      .append(" mm / ")
                      .append(fixed(o.deg[worst], 3))
                      .append(" degrees: check that each scan was taken at the robot pose listed "
                              "with it, in the same units, that the target is rigidly mounted, "
                              "and the mode (eye-to-hand or eye-in-hand)"));
    PoseResidual& r = residuals[std::size_t(rejected_index)];
    r.rejected = true;
    r.reason = std::string("its residual in the solve with it, ")
                   .append(fixed(o.mm[worst], 2))
                   .append(" mm / ")
                   .append(fixed(o.deg[worst], 3))
                   .append(" deg, was above the limit ")
                   .append(fixed(o.limit_mm, 2))
                   .append(" mm / ")
                   .append(fixed(o.limit_deg, 3))
                   .append(" deg (median + ")
                   .append(fixed(params.outlier_mad_factor, 1))
                   .append(" x scaled MAD of the poses' residuals): the robot pose or the scan "
                           "of this pose is wrong");
    active.erase(active.begin() + o.worst);
  }
  return solution;
}

} // namespace

HandEyeResult calibrateHandEye(HandEyeMode mode, const std::vector<HandEyeSample>& samples,
                               const TargetLayout& layout, const HandEyeParams& params) {
  const int n = int(samples.size());
  std::vector<Eigen::Isometry3d> all_flanges;
  for (const auto& s : samples)
    all_flanges.push_back(s.T_base_flange);
  checkPoses(all_flanges, params);
  const std::vector<detail::PoseData> data = checkedPoseData(mode, samples, layout);

  HandEyeResult result;
  result.mode = mode;
  result.residuals.resize(std::size_t(n));
  const detail::Solution solution = solveRejectingOutliers(samples, data, params, result.residuals);

  result.T_camera = solution.X;
  result.T_target = solution.Y;
  double sum_mm = 0, sum_deg = 0;
  std::size_t centres = 0;
  for (int i = 0; i < n; ++i) {
    PoseResidual& r = result.residuals[std::size_t(i)];
    const bool rejected = r.rejected;
    std::string reason = std::move(r.reason);
    r = residualOf(i, data[std::size_t(i)], solution);
    r.rejected = rejected;
    r.reason = std::move(reason);
    if (rejected)
      continue;
    const std::size_t k = data[std::size_t(i)].centres.size();
    sum_mm += r.rms_mm * r.rms_mm * double(k);
    centres += k;
    sum_deg += r.rot_deg * r.rot_deg;
    ++result.poses_used;
  }
  result.rms_mm = std::sqrt(sum_mm / double(centres));
  result.rms_deg = std::sqrt(sum_deg / result.poses_used);
  if (result.rms_mm > params.max_rms_mm)
    throw Error(std::string("the poses disagree: the ")
                    .append(std::to_string(result.poses_used))
                    .append(" poses kept miss the solution by ")
                    .append(fixed(result.rms_mm, 2))
                    .append(" mm RMS (at most ")
                    .append(fixed(params.max_rms_mm, 2))
                    .append(" mm allowed): check that each scan was taken at the robot pose listed "
                            "with it, in the same units, that the target is rigidly mounted, and "
                            "the mode (eye-to-hand or eye-in-hand)"));
  return result;
}

} // namespace scanpick::core::calib
