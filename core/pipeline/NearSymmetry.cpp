#include "core/pipeline/NearSymmetry.h"

#include "core/common/Log.h"
#include "core/matching/PointPairVoting.h"
#include "core/refine/PoseRefinement.h"
#include "core/refine/SceneIndex.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scanpick::core {
namespace {

/// cos 60°: turned and original normals closer than this agree.
constexpr float kMinNormalAgreement = 0.5f;

/// Turns smaller than this (rad, 30°) are the view itself, not a symmetry.
constexpr double kMinTurnRad = M_PI / 6.0;

/// Candidate turns: the most voted poses of the view against itself (the identity among them).
constexpr int kCandidates = 12;

/// The view is sampled for its self-voting with voxels of this share of its diameter.
constexpr double kSamplingShare = 0.04;

/// Share of the view's points, at least, that must differ for a symmetry to be worth testing.
constexpr double kMinDifferingShare = 0.01;

/// Whether `S` puts view point k within `distance_sq` of the view's surface, facing the same way.
bool landsOnSurface(const VerifyModel& view, const SceneIndex& surface, const Eigen::Isometry3f& S,
                    std::size_t k, float distance_sq) {
  const std::int64_t near = surface.nearest(S * view.points[k], distance_sq);
  if (near < 0)
    return false;
  const Eigen::Vector3f& n = view.normals[k];
  const Eigen::Vector3f& n_surface = surface.normals()[static_cast<std::size_t>(near)];
  return !n.allFinite() || !n_surface.allFinite() ||
         (S.linear() * n).dot(n_surface) > kMinNormalAgreement;
}

double turnAngle(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(T.linear()).angle();
}

/// The near symmetry `S` would be: its overlap and its differing points.
NearSymmetry describe(const VerifyModel& view, const SceneIndex& surface,
                      const Eigen::Isometry3d& S_model, double tolerance_mm) {
  NearSymmetry s;
  s.S_model = S_model;
  const Eigen::Isometry3f S = S_model.cast<float>();
  const Eigen::Isometry3f S_inverse = S.inverse();
  const auto near_sq = static_cast<float>(tolerance_mm * tolerance_mm);
  const float far_sq = 9.0f * near_sq;
  std::size_t on = 0;
  for (std::size_t k = 0; k < view.points.size(); ++k) {
    on += landsOnSurface(view, surface, S, k, near_sq) ? 1 : 0;
    if (!landsOnSurface(view, surface, S, k, far_sq))
      s.differing.push_back(static_cast<std::uint32_t>(k));
    if (!landsOnSurface(view, surface, S_inverse, k, far_sq))
      s.differing_inverse.push_back(static_cast<std::uint32_t>(k));
  }
  s.overlap = double(on) / double(view.points.size());
  return s;
}

} // namespace

std::vector<NearSymmetry> findNearSymmetries(const TaughtModel& model, const VerifyModel& view,
                                             const RefineModel& refine_model,
                                             const RefineParams& icp, double tolerance_mm,
                                             double min_overlap) {
  std::vector<NearSymmetry> found;
  if (min_overlap <= 0 || view.points.size() < 10)
    return found;
  // The view's own surface, seen from the teach camera, is the "scene" the turns are fitted to.
  SceneIndexOptions options;
  options.viewpoint_mm = model.T_teach_model.inverse().translation();
  const SceneIndex surface(model.cloud_mm, options);

  const double sampling_mm = std::max(kSamplingShare * model.diameter_mm, tolerance_mm);
  const OrientedPoints sampled = sampleOriented(view.points, view.normals, sampling_mm);
  if (sampled.points.size() < 3)
    return found;
  const PointPairModel pairs(sampled, sampling_mm);
  VotingOptions voting;
  voting.reference_stride = 1;
  voting.cluster_distance_mm = 0.1 * model.diameter_mm;
  voting.max_poses = kCandidates;
  voting.exclude_self_mm = 0.1 * model.diameter_mm;
  for (const VotedPose& voted : pairs.vote(sampled, voting)) {
    if (turnAngle(voted.T_scene_model) < kMinTurnRad)
      continue;
    // ICP can slide a turn along the view's own surface; the better overlap is kept.
    NearSymmetry s = describe(view, surface, voted.T_scene_model, tolerance_mm);
    const Eigen::Isometry3d polished =
        refinePose(refine_model, surface, s.S_model, icp).T_scene_model;
    if (turnAngle(polished) >= kMinTurnRad) {
      NearSymmetry t = describe(view, surface, polished, tolerance_mm);
      if (t.overlap > s.overlap)
        s = std::move(t);
    }
    const double min_differing = kMinDifferingShare * double(view.points.size());
    const bool repeated = std::any_of(found.begin(), found.end(), [&](const NearSymmetry& f) {
      return turnAngle(f.S_model.inverse() * s.S_model) < kMinTurnRad;
    });
    logger()->debug(
        "view '{}': turn by {:.0f}° ({} votes): overlap {:.3f}, {} / {} points differ{}",
        model.name, turnAngle(s.S_model) * 180.0 / M_PI, voted.votes, s.overlap, s.differing.size(),
        s.differing_inverse.size(), repeated ? ", repeated" : "");
    if (!repeated && s.overlap >= min_overlap && double(s.differing.size()) >= min_differing &&
        double(s.differing_inverse.size()) >= min_differing)
      found.push_back(std::move(s));
  }
  return found;
}

double contradictedShare(const PointTally& tally, std::size_t min_seen) {
  const std::size_t seen = tally.points - tally.hidden;
  if (seen < std::max<std::size_t>(1, min_seen))
    return std::numeric_limits<double>::quiet_NaN();
  return double(tally.violations) / double(seen);
}

} // namespace scanpick::core
