#include "core/ambiguity/NearSymmetry.h"

#include "core/common/Log.h"
#include "core/matching/PointPairVoting.h"
#include "core/refine/PoseRefinement.h"
#include "core/refine/SceneIndex.h"
#include "core/refine/SurfaceEnds.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

/// cos 60°: rotated and original normals closer than this agree.
constexpr float kMinNormalAgreement = 0.5f;

/// Rotations smaller than this (rad, 30°) are the view itself, not a symmetry.
constexpr double kMinRotationRad = M_PI / 6.0;

/// Candidate rotations: the most voted poses of the view against itself (the identity among them).
constexpr int kCandidates = 12;

/// The view is sampled for its self-voting with voxels of this share of its diameter.
constexpr double kSamplingShare = 0.055;
/// Rotations closer than this share of the view's diameter are one (and the identity is left
/// out).
constexpr double kClusterShare = 0.14;

/// Squared distance from view point k moved by `S` to the nearest point of the view's surface
/// closer than sqrt(max_distance_sq), or infinity when there is none or it faces another way
/// (more than 60° apart).
float surfaceDistanceSq(const VerifyModel& view, const SceneIndex& surface,
                        const Eigen::Isometry3f& S, std::size_t k, float max_distance_sq) {
  float distance_sq = 0.0f;
  const std::int64_t near = surface.nearest(S * view.points[k], max_distance_sq, &distance_sq);
  if (near < 0)
    return std::numeric_limits<float>::infinity();
  const Eigen::Vector3f& n = view.normals[k];
  const Eigen::Vector3f& n_surface = surface.normals()[static_cast<std::size_t>(near)];
  const bool agrees = !n.allFinite() || !n_surface.allFinite() ||
                      (S.linear() * n).dot(n_surface) > kMinNormalAgreement;
  return agrees ? distance_sq : std::numeric_limits<float>::infinity();
}

double rotationAngle(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(T.linear()).angle();
}

/// The teach scan's depth as the view shows it: the nearest view point per viewing direction
/// (cells of about 1 mm at the view's depth), so that a point can be tested for being hidden
/// behind the view's own surface.
class ViewDepth {
public:
  ViewDepth(const PointCloud& cloud_model, const Eigen::Isometry3d& T_teach_model)
      : m_T_teach_model(T_teach_model.cast<float>()) {
    std::vector<Eigen::Vector3f> teach;
    double depth_sum = 0;
    for (const auto& p : cloud_model.points_mm)
      if (isValid(p) && (m_T_teach_model * p).z() > 0) {
        teach.push_back(m_T_teach_model * p);
        depth_sum += teach.back().z();
      }
    if (teach.empty())
      return;
    m_step = float(1.0 / (depth_sum / double(teach.size()))); // 1 mm at the mean depth
    Eigen::Vector2f low(1e9f, 1e9f), high(-1e9f, -1e9f);
    for (const auto& p : teach) {
      low = low.cwiseMin(direction(p));
      high = high.cwiseMax(direction(p));
    }
    m_origin = low;
    m_width = static_cast<int>((high.x() - low.x()) / m_step) + 1;
    m_height = static_cast<int>((high.y() - low.y()) / m_step) + 1;
    m_depth.assign(std::size_t(m_width) * std::size_t(m_height), kNone);
    for (const auto& p : teach) {
      float& d = m_depth[cell(p)];
      d = std::min(d, p.z());
    }
  }

  /// Whether the view's surface lies more than `margin_mm` in front of `p_model` (model frame)
  /// as the teach camera sees it (the nearest depth in a 3 x 3 cell neighbourhood).
  [[nodiscard]] bool hides(const Eigen::Vector3f& p_model, float margin_mm) const {
    const Eigen::Vector3f p = m_T_teach_model * p_model;
    if (m_depth.empty() || p.z() <= 0)
      return false;
    const Eigen::Vector2f uv = (direction(p) - m_origin) / m_step;
    const int u = static_cast<int>(std::floor(uv.x())), v = static_cast<int>(std::floor(uv.y()));
    float nearest = kNone;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du)
        if (u + du >= 0 && v + dv >= 0 && u + du < m_width && v + dv < m_height)
          nearest = std::min(
              nearest, m_depth[std::size_t(v + dv) * std::size_t(m_width) + std::size_t(u + du)]);
    return nearest < p.z() - margin_mm;
  }

private:
  static constexpr float kNone = std::numeric_limits<float>::max();
  static Eigen::Vector2f direction(const Eigen::Vector3f& p) {
    return {p.x() / p.z(), p.y() / p.z()};
  }
  std::size_t cell(const Eigen::Vector3f& p) const {
    const Eigen::Vector2f uv = (direction(p) - m_origin) / m_step;
    const int u = std::clamp(static_cast<int>(uv.x()), 0, m_width - 1);
    const int v = std::clamp(static_cast<int>(uv.y()), 0, m_height - 1);
    return std::size_t(v) * std::size_t(m_width) + std::size_t(u);
  }
  Eigen::Isometry3f m_T_teach_model;
  float m_step = 1.0f;
  Eigen::Vector2f m_origin = Eigen::Vector2f::Zero();
  int m_width = 0, m_height = 0;
  std::vector<float> m_depth;
};

/// Whether the teach camera could have seen view point k moved by `S`: a surface facing away
/// from it, or hidden behind the view's own surface, is not in the view whatever the part looks
/// like there.
bool seenFromTeachCamera(const VerifyModel& view, const Eigen::Isometry3f& S, std::size_t k,
                         const Eigen::Vector3f& camera, const ViewDepth& depth, float margin_mm) {
  const Eigen::Vector3f q = S * view.points[k];
  const Eigen::Vector3f& n = view.normals[k];
  if (n.allFinite() && (S.linear() * n).dot(camera - q) <= 0.0f)
    return false;
  return !depth.hides(q, margin_mm);
}

/// The near symmetry `S` would be: its overlap and its differing points. Points that S rotates
/// away from the teach camera or behind the view's own surface tell nothing (the view could not
/// have held them) and are left out of both: a tilted plate's near rim rotated to the far side is
/// not a difference.
NearSymmetry describe(const VerifyModel& view, const SceneIndex& surface,
                      const Eigen::Isometry3d& S_model, const Eigen::Vector3f& camera,
                      const ViewDepth& depth, double tolerance_mm) {
  NearSymmetry s;
  s.S_model = S_model;
  const Eigen::Isometry3f S = S_model.cast<float>();
  const Eigen::Isometry3f S_inverse = S.inverse();
  const auto near_sq = static_cast<float>(tolerance_mm * tolerance_mm);
  const float far_sq = 9.0f * near_sq;
  std::size_t on = 0, seen = 0;
  for (std::size_t k = 0; k < view.points.size(); ++k) {
    const float margin = 3.0f * static_cast<float>(tolerance_mm);
    if (seenFromTeachCamera(view, S, k, camera, depth, margin)) {
      ++seen;
      const float distance_sq = surfaceDistanceSq(view, surface, S, k, far_sq);
      on += distance_sq < near_sq ? 1 : 0;
      if (!(distance_sq < far_sq))
        s.differing.push_back(static_cast<std::uint32_t>(k));
    }
    if (seenFromTeachCamera(view, S_inverse, k, camera, depth, margin) &&
        !(surfaceDistanceSq(view, surface, S_inverse, k, far_sq) < far_sq))
      s.differing_inverse.push_back(static_cast<std::uint32_t>(k));
  }
  s.overlap = seen ? double(on) / double(seen) : 0.0;
  return s;
}

/// A rotation this close to 180° is one (rad, 5°): parts are made with exact symmetries, and a
/// view fitted onto itself leaves its rotation about a plate's normal a degree or two off.
constexpr double k180RotationSnapRad = 5.0 * M_PI / 180.0;
/// How far an exact 180° rotation may be moved across its axis to where the part's outline maps
/// onto itself (mm): the fitted rotation's axis lies up to a couple of millimetres off.
constexpr double kMax180RotationMoveMm = 5.0;

/// With views joined (TaughtModel::joined_views: the part seen from every side, in this view's
/// frame), a rotation `S_model` within k180RotationSnapRad of 180° made an exact 180° rotation
/// about its own axis, then moved across that axis, along the two main directions of the part's
/// spread there, to where the outline of all the views' points maps onto itself (outlineShift,
/// twice); nothing for other rotations or without joined views. The view alone cannot place the
/// axis: its own outline, rotated, shows the sides its teach camera saw edge-on where it saw faces.
std::optional<Eigen::Isometry3d> exact180Rotation(const TaughtModel& model,
                                                  const Eigen::Isometry3d& S_model) {
  const Eigen::AngleAxisd rotation(S_model.linear());
  if (model.joined_views.empty() || !(std::abs(rotation.angle() - M_PI) < k180RotationSnapRad))
    return std::nullopt;
  std::vector<Eigen::Vector3f> part_mm;
  for (const JoinedView& view : model.joined_views)
    for (const auto& p : view.cloud_mm.points_mm)
      if (p.allFinite())
        part_mm.push_back(p);
  if (part_mm.empty())
    return std::nullopt;
  // The 180° rotation about the fitted rotation's axis (the point of it nearest to what S fixes),
  // with S's slide along the axis.
  const Eigen::Vector3d axis = rotation.axis().normalized();
  const Eigen::Vector3d t = S_model.translation();
  const Eigen::Vector3d on_axis = (Eigen::Matrix3d::Identity() - S_model.linear())
                                      .completeOrthogonalDecomposition()
                                      .solve(t - t.dot(axis) * axis);
  const Eigen::Matrix3d R = 2.0 * axis * axis.transpose() - Eigen::Matrix3d::Identity();
  Eigen::Isometry3d S = Eigen::Isometry3d::Identity();
  S.linear() = R;
  S.translation() = on_axis - R * on_axis + t.dot(axis) * axis;
  // The part's main directions across the axis.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : part_mm)
    mean += p.cast<double>();
  mean /= static_cast<double>(part_mm.size());
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - axis * axis.transpose();
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const auto& p : part_mm) {
    const Eigen::Vector3d d = across * (p.cast<double>() - mean);
    spread += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> main_directions(spread);
  OutlineShiftOptions options;
  options.max_shift_mm = kMax180RotationMoveMm;
  std::vector<Eigen::Vector3f> rotated_mm(part_mm.size());
  for (int round = 0; round < 2; ++round)
    for (int k = 1; k < 3; ++k) { // the two largest: across the axis
      const Eigen::Vector3d direction = main_directions.eigenvectors().col(k).normalized();
      for (std::size_t i = 0; i < part_mm.size(); ++i)
        rotated_mm[i] = (S * part_mm[i].cast<double>()).cast<float>();
      if (const auto shift = outlineShift(rotated_mm, part_mm, direction, {}, options))
        S = Eigen::Translation3d(*shift * direction) * S;
    }
  logger()->debug("view '{}': rotation by {:.1f}° made an exact 180° rotation; it moves the "
                  "view's origin by {:.2f} mm",
                  model.name, rotation.angle() * 180.0 / M_PI,
                  (S.translation() - S_model.translation()).norm());
  return S;
}

} // namespace

std::vector<NearSymmetry> findNearSymmetries(const TaughtModel& model, const VerifyModel& view,
                                             const RefineModel& refine_model,
                                             const RefineParams& icp, double tolerance_mm,
                                             double min_overlap) {
  std::vector<NearSymmetry> found;
  if (min_overlap <= 0 || view.points.size() < 10)
    return found;
  // The view's own surface, seen from the teach camera, is the "scene" the rotations are fitted
  // to.
  const SceneIndex& surface = refine_model.surface();
  const Eigen::Vector3f camera = model.T_teach_model.inverse().translation().cast<float>();
  const ViewDepth depth(model.cloud_mm, model.T_teach_model);

  const double sampling_mm = std::max(kSamplingShare * model.diameter_mm, tolerance_mm);
  const OrientedPoints sampled = sampleOriented(view.points, view.normals, sampling_mm);
  if (sampled.points.size() < 3)
    return found;
  const PointPairModel pairs(sampled, sampling_mm);
  VotingOptions voting;
  voting.reference_stride = 1;
  voting.cluster_distance_mm = kClusterShare * model.diameter_mm;
  voting.max_poses = kCandidates;
  voting.exclude_self_mm = kClusterShare * model.diameter_mm;
  const std::vector<VotedPose> candidates = pairs.vote(sampled, voting);
  // Each candidate is described and refined on its own (in parallel); they are then taken in
  // vote order, so the result does not depend on the threads.
  std::vector<std::optional<NearSymmetry>> described(candidates.size());
  tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t c) {
    if (rotationAngle(candidates[c].T_scene_model) < kMinRotationRad)
      return;
    // ICP can slide a rotation along the view's own surface; the better overlap is kept.
    NearSymmetry s =
        describe(view, surface, candidates[c].T_scene_model, camera, depth, tolerance_mm);
    const Eigen::Isometry3d refined =
        refinePose(refine_model, surface, s.S_model, icp).T_scene_model;
    if (rotationAngle(refined) >= kMinRotationRad) {
      NearSymmetry t = describe(view, surface, refined, camera, depth, tolerance_mm);
      if (t.overlap > s.overlap)
        s = std::move(t);
    }
    if (const auto rotation_180 = exact180Rotation(model, s.S_model))
      s = describe(view, surface, *rotation_180, camera, depth, tolerance_mm);
    described[c] = std::move(s);
  });
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!described[c])
      continue;
    NearSymmetry& s = *described[c];
    const bool repeated = std::any_of(found.begin(), found.end(), [&](const NearSymmetry& f) {
      return rotationAngle(f.S_model.inverse() * s.S_model) < kMinRotationRad;
    });
    logger()->debug(
        "view '{}': rotation by {:.0f}° ({} votes): overlap {:.3f}, {} / {} points differ{}",
        model.name, rotationAngle(s.S_model) * 180.0 / M_PI, candidates[c].votes, s.overlap,
        s.differing.size(), s.differing_inverse.size(), repeated ? ", repeated" : "");
    if (!repeated && s.overlap >= min_overlap)
      found.push_back(std::move(s));
  }
  return found;
}

std::size_t minDistinguishingPoints(std::size_t view_points) {
  constexpr double kMinDistinguishingShare = 0.02;
  return std::max<std::size_t>(
      8, static_cast<std::size_t>(kMinDistinguishingShare * static_cast<double>(view_points)));
}

bool repeatsItself(const NearSymmetry& symmetry, std::size_t view_points) {
  const std::size_t min_seen = minDistinguishingPoints(view_points);
  return symmetry.differing.size() < min_seen && symmetry.differing_inverse.size() < min_seen;
}

double contradictedShare(const PointTally& tally, std::size_t min_seen) {
  const std::size_t seen = tally.points - tally.hidden;
  if (seen < std::max<std::size_t>(1, min_seen))
    return std::numeric_limits<double>::quiet_NaN();
  return double(tally.violations) / double(seen);
}

} // namespace scanpick::core
