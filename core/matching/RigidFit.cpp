#include "core/matching/RigidFit.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace scanpick::core {

Eigen::Matrix3d rotationBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d a = from.normalized(), b = to.normalized();
  const Eigen::Vector3d axis = a.cross(b);
  const double s = axis.norm(), c = std::clamp(a.dot(b), -1.0, 1.0);
  if (s < 1e-12) {
    if (c > 0.0)
      return Eigen::Matrix3d::Identity();
    // Antiparallel: any perpendicular axis; pick a fixed one so the result is deterministic.
    Eigen::Vector3d perp = a.cross(Eigen::Vector3d::UnitX());
    if (perp.norm() < 1e-6)
      perp = a.cross(Eigen::Vector3d::UnitY());
    return Eigen::AngleAxisd(M_PI, perp.normalized()).toRotationMatrix();
  }
  return Eigen::AngleAxisd(std::atan2(s, c), axis / s).toRotationMatrix();
}

double axisAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, c));
}

namespace {

/// A model feature and its scene partner as three point pairs each side: the centre and the two
/// ends of an arm along the direction (a circle's radius, half a line's length, at least 1 mm; the
/// same arm on both sides, as the scene feature's size may differ by up to Δl). The scene's
/// direction is flipped to agree with the model's turned by `R_scene_model`.
struct FeaturePair {
  Eigen::Vector3d model_centre, scene_centre, model_arm, scene_arm;
  Eigen::Vector3d scene_direction; ///< unit
};

FeaturePair featurePair(const Feature& m, const Feature& t, const Eigen::Matrix3d& R_scene_model) {
  const Eigen::Vector3d md = m.direction.cast<double>().normalized();
  Eigen::Vector3d td = t.direction.cast<double>().normalized();
  if ((R_scene_model * md).dot(td) < 0.0)
    td = -td;
  const double arm =
      std::max(1.0, m.type == FeatureType::Circle ? double(m.size_mm) : 0.5 * m.size_mm);
  return {m.centre_mm.cast<double>(), t.centre_mm.cast<double>(), arm * md, arm * td, td};
}

} // namespace

Eigen::Isometry3d fitFeaturePairs(const FeatureList& model, const FeatureList& scene,
                                  const std::vector<std::pair<int, int>>& pairs,
                                  const Eigen::Isometry3d& T_guess) {
  if (pairs.empty())
    return T_guess;
  Eigen::Matrix3Xd src(3, 3 * pairs.size()), dst(3, 3 * pairs.size());
  Eigen::Index col = 0;
  for (const auto& [mi, si] : pairs) {
    const FeaturePair f = featurePair(model[static_cast<std::size_t>(mi)],
                                      scene[static_cast<std::size_t>(si)], T_guess.linear());
    for (const double side : {0.0, 1.0, -1.0}) {
      src.col(col) = f.model_centre + side * f.model_arm;
      dst.col(col++) = f.scene_centre + side * f.scene_arm;
    }
  }
  const Eigen::Matrix4d T = Eigen::umeyama(src, dst, false);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = T.topLeftCorner<3, 3>();
  out.translation() = T.topRightCorner<3, 1>();
  return out;
}

Eigen::Isometry3d refineOnFeatureGeometry(const FeatureList& model, const FeatureList& scene,
                                          const std::vector<std::pair<int, int>>& pairs,
                                          const Eigen::Isometry3d& T_init, int iterations) {
  if (pairs.size() < 2)
    return T_init;
  // Along a line only its direction and its perpendicular position are trusted: the line's
  // extent (and so its centre) moves with occlusion. That direction keeps a small weight so that
  // all-parallel-lines poses stay defined.
  constexpr double kAlongWeight = 0.05;
  Eigen::Isometry3d T = T_init;
  for (int it = 0; it < iterations; ++it) {
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    // Residual r(p) = W (T p − q) for a moved model point p and its scene target q, with a
    // small-angle update T ← exp([ω]×, v) T: ∂(Tp)/∂(ω, v) = [−[Tp]×, I].
    const auto add = [&](const Eigen::Vector3d& p_model, const Eigen::Vector3d& q,
                         const Eigen::Matrix3d& W) {
      const Eigen::Vector3d p = T * p_model;
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() << 0, p.z(), -p.y(), -p.z(), 0, p.x(), p.y(), -p.x(), 0;
      J.rightCols<3>() = Eigen::Matrix3d::Identity();
      const Eigen::Matrix<double, 3, 6> WJ = W * J;
      const Eigen::Vector3d r = W * (p - q);
      H += WJ.transpose() * WJ;
      g += WJ.transpose() * r;
    };
    for (const auto& [mi, si] : pairs) {
      const Feature& m = model[static_cast<std::size_t>(mi)];
      const FeaturePair f = featurePair(m, scene[static_cast<std::size_t>(si)], T.linear());
      const Eigen::Vector3d& td = f.scene_direction;
      const Eigen::Matrix3d W = m.type == FeatureType::Line
                                    ? Eigen::Matrix3d(Eigen::Matrix3d::Identity() -
                                                      (1.0 - kAlongWeight) * td * td.transpose())
                                    : Eigen::Matrix3d::Identity();
      for (const double side : {0.0, 1.0, -1.0})
        add(f.model_centre + side * f.model_arm, f.scene_centre + side * f.scene_arm, W);
    }
    const Eigen::Matrix<double, 6, 1> delta = H.ldlt().solve(-g);
    if (!delta.allFinite())
      return T;
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d w = delta.head<3>();
    if (w.norm() > 1e-15)
      step.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    step.translation() = delta.tail<3>();
    T = step * T;
    if (delta.norm() < 1e-9)
      break;
  }
  // Re-orthonormalize against rounding.
  const Eigen::Quaterniond q(T.linear());
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

} // namespace scanpick::core
