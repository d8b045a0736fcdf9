#include "core/eval/PoseError.h"

#include "core/common/Error.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace scanpick::core::eval {
namespace {

constexpr std::size_t kMaxGroupSize = 256;

bool sameTransform(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double diameter_mm) {
  return rotationAngleDeg(a.linear().transpose() * b.linear()) < 1e-4 &&
         (a.translation() - b.translation()).norm() < 1e-6 * std::max(1.0, diameter_mm);
}

/// Rotation by `angle_rad` about the line through `point` along unit `direction`.
Eigen::Isometry3d rotationAboutLine(const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                                    double angle_rad) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(angle_rad, direction).toRotationMatrix();
  t.translation() = point - t.linear() * point;
  return t;
}

/// Twist angle of `rotation` about unit `axis` (swing-twist decomposition: rotation =
/// swing · twist with the swing axis perpendicular to `axis`).
double twistAngle(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& axis) {
  const Eigen::Quaterniond q(rotation);
  const double along = q.vec().dot(axis);
  return 2.0 * std::atan2(along, q.w());
}

} // namespace

double rotationAngleDeg(const Eigen::Matrix3d& rotation) {
  const Eigen::Quaterniond q(rotation);
  // 2·atan2(|v|, |w|) is accurate for small and large angles alike (acos of the trace is not).
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())) * 180.0 / std::numbers::pi;
}

std::vector<Eigen::Isometry3d> symmetryGroup(const PartSymmetry& symmetry, double diameter_mm) {
  std::vector<Eigen::Isometry3d> group{Eigen::Isometry3d::Identity()};
  const auto contains = [&](const Eigen::Isometry3d& t) {
    for (const auto& g : group)
      if (sameTransform(g, t, diameter_mm))
        return true;
    return false;
  };
  for (const auto& s : symmetry.discrete)
    if (!contains(s))
      group.push_back(s);
  // Close under composition: the file may list generators only (e.g. 90° without 180°, 270°).
  for (std::size_t i = 0; i < group.size(); ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      for (const auto& product : {group[i] * group[j], group[j] * group[i]}) {
        if (!contains(product)) {
          if (group.size() >= kMaxGroupSize)
            throw Error("the part's discrete symmetries do not form a finite group (more than " +
                        std::to_string(kMaxGroupSize) +
                        " compositions): list exact symmetry transforms in the ground truth");
          group.push_back(product);
        }
      }
    }
  }
  return group;
}

PoseError symmetricPoseError(const Eigen::Isometry3d& T_scene_part_est,
                             const Eigen::Isometry3d& T_scene_part_true, const PartInfo& part,
                             const std::vector<Eigen::Isometry3d>& group,
                             const Tolerances& tolerances) {
  const double max_translation_mm = tolerances.translation_fraction * part.diameter_mm;
  const double radius_mm = part.diameter_mm / 2.0;
  PoseError best;
  bool have_best = false;
  double best_cost = std::numeric_limits<double>::infinity();
  for (const auto& s : group) {
    Eigen::Isometry3d candidate = T_scene_part_true * s;
    if (part.symmetry.continuous_axis) {
      // Turn the candidate about the axis so it differs from the estimate by a pure swing:
      // the remaining rotation is then the angle between the two axis directions.
      const auto& axis = *part.symmetry.continuous_axis;
      const Eigen::Matrix3d relative = candidate.linear().transpose() * T_scene_part_est.linear();
      candidate = candidate * rotationAboutLine(axis.point_mm, axis.direction,
                                                twistAngle(relative, axis.direction));
    }
    PoseError e;
    e.T_scene_part_equivalent = candidate;
    e.translation_mm = (T_scene_part_est.translation() - candidate.translation()).norm();
    e.rotation_deg = rotationAngleDeg(candidate.linear().transpose() * T_scene_part_est.linear());
    e.within_tolerance =
        e.translation_mm <= max_translation_mm && e.rotation_deg <= tolerances.rotation_deg;
    const double cost = e.translation_mm + e.rotation_deg * std::numbers::pi / 180.0 * radius_mm;
    const bool better = !have_best || (e.within_tolerance && !best.within_tolerance) ||
                        (e.within_tolerance == best.within_tolerance && cost < best_cost);
    if (better) {
      best = std::move(e);
      best_cost = cost;
      have_best = true;
    }
  }
  for (const auto& grip : part.grip_points_part)
    best.grip_mm.push_back(
        (T_scene_part_est * grip.position_mm - best.T_scene_part_equivalent * grip.position_mm)
            .norm());
  return best;
}

} // namespace scanpick::core::eval
