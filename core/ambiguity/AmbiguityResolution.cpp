#include "core/ambiguity/AmbiguityResolution.h"

#include "core/common/Log.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace scanpick::core::detail {
namespace {

/// A detection sees the asymmetric feature of its view when the scan confirms at least this
/// share of it.
constexpr double kMinAsymmetrySeenShare = 0.25;

/// Which pose of a detection and its rotation by a near symmetry the scan rules out.
enum class Ruling { Neither, Found, Rotated };

/// A view seen from the side holds its part's place along the axis loosely (a cylinder slides
/// along itself); the joined revolved surface's ends are looked for within this distance of it,
/// mm, in steps of kSurfaceSlideStepMm.
constexpr double kSurfaceSlideMm = 6.0;
constexpr double kSurfaceSlideStepMm = 0.5;

/// (confirmed − violations) of the `subset` of `surface`'s points at `T_scene_model` slid along
/// `axis` (by up to kSurfaceSlideMm) to where it is best, as a share of those facing the camera
/// (at least 8).
double revolvedSurfaceScore(const VerifyModel& surface, const RevolutionAxis& axis,
                            const VerifyScene& scene, const Eigen::Isometry3d& T_scene_model,
                            double tolerance_mm, const std::vector<std::uint32_t>& subset) {
  double best = -std::numeric_limits<double>::infinity();
  const int steps = static_cast<int>(std::lround(kSurfaceSlideMm / kSurfaceSlideStepMm));
  for (int step = -steps; step <= steps; ++step) {
    const Eigen::Isometry3d T =
        T_scene_model * Eigen::Translation3d(step * kSurfaceSlideStepMm * axis.direction);
    const PointTally t = tallyPoints(surface, scene, T, tolerance_mm,
                                     {.subset = &subset, .stop = {}, .sort_unmeasured = false});
    best = std::max(best, (double(t.confirmed) - double(t.violations)) /
                              double(std::max<std::size_t>(8, t.points - t.turned_away)));
  }
  return best;
}

/// A rotation the asymmetric feature chooses is taken only while the pose verifies at most this
/// much worse.
constexpr double kAxisRotationCoverageSlack = 0.05;
/// ICP's refinement of a rotation the joined asymmetric feature chooses is kept while the
/// asymmetric feature's score drops by at most this much.
constexpr double kRefinedAsymmetrySlack = 0.05;

/// A detection is rotated by a near symmetry when the scan contradicts this much larger a share of
/// its differing points than of the rotated pose's (contradictedShare); an asymmetric feature must
/// score this much more for a rotation about the near axis.
constexpr double kRotationMargin = 0.1;

} // namespace

namespace {

/// Which asymmetric feature a tally looks at: the view's own, or the joined one
/// (ModelPrep::joined_asymmetry).
enum class Asymmetry { Own, Joined };

/// (confirmed − violations) of the view's asymmetric feature at `T_scene_model`, as a share: of
/// every point of the view's own asymmetric feature; of a joined one (seen from every side, of
/// which a camera sees at most about half), of its points facing the camera, but at least a
/// quarter of them all.
struct AsymmetryTally {
  PointTally tally;
  double of = 1.0;
  [[nodiscard]] double score() const {
    return (double(tally.confirmed) - double(tally.violations)) / of;
  }
  [[nodiscard]] bool seen() const {
    return double(tally.confirmed) >= kMinAsymmetrySeenShare * of && tally.confirmed > 0;
  }
};

/// The highest AsymmetryTally::score() that `which` asymmetric feature's tally `t` can reach with
/// `left` points not looked at: each of them facing the camera and confirmed (as that raises the
/// score while fewer are confirmed than face the camera); with none left, the score.
double asymmetryScoreBound(Asymmetry which, const PointTally& t, std::size_t left) {
  const double points = double(t.points + left);
  const double reachable = double(t.confirmed) - double(t.violations) + double(left);
  if (which == Asymmetry::Own)
    return reachable / std::max(1.0, points);
  const double facing = double(t.points - t.turned_away + left);
  return reachable / std::max({1.0, facing, 0.25 * points});
}

AsymmetryTally tallyAsymmetry(const ModelPrep& prep, Asymmetry which, const VerifyScene& scene,
                              const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                              const TallyStop& stop = {}) {
  if (which == Asymmetry::Own) {
    const PointTally t =
        tallyPoints(*prep.verify, scene, T_scene_model, tolerance_mm,
                    {.subset = &prep.near_axis_asymmetry, .stop = stop, .sort_unmeasured = false});
    return {t, double(std::max<std::size_t>(1, t.points))};
  }
  const PointTally t = tallyPoints(*prep.joined_asymmetry, scene, T_scene_model, tolerance_mm,
                                   {.subset = nullptr, .stop = stop, .sort_unmeasured = false});
  const double facing = double(t.points - t.turned_away);
  return {t, std::max({1.0, facing, 0.25 * double(t.points)})};
}

/// `which` asymmetric feature's score at `T_scene_model` when it is above `beat`; none otherwise,
/// its tally stopped as soon as it cannot be.
std::optional<double> asymmetryScoreAbove(const ModelPrep& prep, Asymmetry which,
                                          const VerifyScene& scene,
                                          const Eigen::Isometry3d& T_scene_model,
                                          double tolerance_mm, double beat) {
  const std::size_t total = which == Asymmetry::Own ? prep.near_axis_asymmetry.size()
                                                    : prep.joined_asymmetry->points.size();
  const auto cannot_beat = [&](const PointTally& so_far, std::size_t left) {
    return asymmetryScoreBound(which, so_far, left) <= beat;
  };
  const AsymmetryTally t =
      tallyAsymmetry(prep, which, scene, T_scene_model, tolerance_mm, cannot_beat);
  if (t.tally.points < total || !(t.score() > beat))
    return std::nullopt;
  return t.score();
}

/// The rotation about the view's near axis (1° steps) at which `which` asymmetric feature scores
/// best, if it scores at least kMinAsymmetrySeenShare and kRotationMargin more than at
/// `T_scene_model`.
std::optional<AxisRotation> bestRotation(const ModelPrep& prep, Asymmetry which,
                                         const VerifyScene& scene, double tolerance_mm,
                                         const Eigen::Isometry3d& T_scene_model) {
  const RevolutionAxis& axis = *prep.near_axis;
  const double as_found = tallyAsymmetry(prep, which, scene, T_scene_model, tolerance_mm).score();
  // Only a rotation scoring at least this is taken: each tally stops as soon as it cannot reach
  // it (or the best so far), most of them after a few misses.
  const double needed = std::max(kMinAsymmetrySeenShare, as_found + kRotationMargin);
  AxisRotation rotation;
  rotation.T_scene_model = T_scene_model;
  rotation.asymmetry_as_found = as_found;
  // Scores above this are those of at least `needed`.
  rotation.asymmetry_confirmed = std::nextafter(needed, -std::numeric_limits<double>::infinity());
  for (int degrees = 1; degrees < 360; ++degrees) {
    const Eigen::Isometry3d T = T_scene_model * axis.turn(degrees * M_PI / 180.0);
    if (const auto score = asymmetryScoreAbove(prep, which, scene, T, tolerance_mm,
                                               rotation.asymmetry_confirmed)) {
      rotation.asymmetry_confirmed = *score;
      rotation.T_scene_model = T;
    }
  }
  if (rotation.asymmetry_confirmed < needed)
    return std::nullopt;
  return rotation;
}

} // namespace

bool seesAsymmetry(const ModelPrep& prep, const VerifyScene& scene,
                   const Eigen::Isometry3d& T_scene_model, double tolerance_mm) {
  return tallyAsymmetry(prep, Asymmetry::Own, scene, T_scene_model, tolerance_mm).seen() ||
         (prep.joined_asymmetry &&
          tallyAsymmetry(prep, Asymmetry::Joined, scene, T_scene_model, tolerance_mm).seen());
}

std::optional<AxisRotation>
rotationByAsymmetry(const ModelPrep& prep, const VerifyScene& scene, const MatchingParams& params,
                    const PoseVerifier& verify, const PoseRefiner& refine,
                    const Eigen::Isometry3d& T_scene_model, double coverage, bool ask_joined) {
  if (!prep.near_axis || prep.near_axis_asymmetry.empty())
    return std::nullopt;
  const double tolerance = params.verify_tolerance_mm;
  if (auto rotation = bestRotation(prep, Asymmetry::Own, scene, tolerance, T_scene_model)) {
    // The rotation is known to a degree: ICP finishes it.
    rotation->coverage = verify(rotation->T_scene_model);
    const Eigen::Isometry3d refined = refine(rotation->T_scene_model);
    if (const double refined_coverage = verify(refined); refined_coverage >= rotation->coverage) {
      rotation->T_scene_model = refined;
      rotation->coverage = refined_coverage;
      rotation->refined = true;
    }
    // The revolved surface must still agree: a side view rotated far about its axis moves its
    // visible half out of the camera's sight, where a handle-like patch of another part can
    // confirm the asymmetric feature.
    if (rotation->coverage >= coverage - kAxisRotationCoverageSlack)
      return rotation;
  }
  if (!prep.joined_asymmetry || !ask_joined)
    return std::nullopt;
  // Where the view's own asymmetric feature tells nothing, the asymmetric feature as the joined
  // views saw it (a handle seen from the front by a view that saw it from behind). The revolved
  // surface is the same at any rotation, but rotated far the view's own half of it faces away
  // from the camera: the pose keeps the coverage it was found with, and ICP's refinement only
  // while the asymmetric feature stays as confirmed.
  auto rotation = bestRotation(prep, Asymmetry::Joined, scene, tolerance, T_scene_model);
  if (!rotation)
    return std::nullopt;
  const Eigen::Isometry3d refined = refine(rotation->T_scene_model);
  if (tallyAsymmetry(prep, Asymmetry::Joined, scene, refined, tolerance).score() >=
      rotation->asymmetry_confirmed - kRefinedAsymmetrySlack) {
    rotation->T_scene_model = refined;
    rotation->refined = true;
  }
  rotation->coverage = std::max(coverage, verify(rotation->T_scene_model));
  return rotation;
}

std::vector<Detection> resolveAxisRotations(std::vector<Detection> detections,
                                            const ModelPrep& prep, const VerifyScene& scene,
                                            const MatchingParams& params,
                                            const PoseVerifier& verify, const PoseRefiner& refine) {
  tbb::parallel_for(std::size_t{0}, detections.size(), [&](std::size_t k) {
    Detection& d = detections[k];
    const auto rotation =
        rotationByAsymmetry(prep, scene, params, verify, refine, d.T_scene_model, d.coverage);
    if (!rotation)
      return;
    logger()->debug("detection {} rotated about its axis by its asymmetric feature: {:.2f} -> "
                    "{:.2f} of it confirmed, coverage {:.3f} -> {:.3f}",
                    k, rotation->asymmetry_as_found, rotation->asymmetry_confirmed, d.coverage,
                    rotation->coverage);
    applyRotation(d, *rotation);
  });
  return detections;
}

void applyRotation(Detection& detection, const AxisRotation& rotation) {
  detection.T_scene_model = rotation.T_scene_model;
  detection.coverage = rotation.coverage;
  detection.score = rotation.coverage;
  detection.refined = rotation.refined;
  detection.matched_features.clear();
  detection.alternative_poses.clear();
}

namespace {

/// How the scan rules between a detection's pose and its pose rotated by one near symmetry.
struct SymmetryRuling {
  Ruling ruling = Ruling::Neither;
  const char* ruled_by = "the view's differing points";
  double as_found = 0.0, rotated = 0.0; ///< the view's differing points contradicted
  Eigen::Isometry3d T_rotated;          ///< T·S, refined (and rotated by its asymmetric feature)
  double coverage = 0.0;                ///< T_rotated's verification score
};

/// The ruling between detection `d` (number `k`, for the log) at T and T·S for the view's near
/// symmetry `j` (resolveNearSymmetries). `rotation_unseen`: the rotation about the view's near
/// axis is not seen at T. `min_seen`: fewer differing points seen tell nothing
/// (contradictedShare).
SymmetryRuling ruleSymmetry(const ModelPrep& prep, std::size_t j, const VerifyScene& scene,
                            const MatchingParams& params, const PoseVerifier& verify,
                            const PoseRefiner& refine, const Detection& d, std::size_t k,
                            bool rotation_unseen, std::size_t min_seen) {
  const NearSymmetry& s = prep.symmetries[j];
  SymmetryRuling r;
  r.as_found = contradictedShare(
      tallyPoints(*prep.verify, scene, d.T_scene_model, params.verify_tolerance_mm,
                  {.subset = &s.differing_inverse, .stop = {}, .sort_unmeasured = true}),
      min_seen);
  r.T_rotated = refine(d.T_scene_model * s.S_model);
  r.coverage = verify(r.T_rotated);
  // Flipped end over end, a cup's handle lies at another rotation about its axis: its asymmetric
  // feature says which.
  if (const auto rotation =
          rotationByAsymmetry(prep, scene, params, verify, refine, r.T_rotated, r.coverage)) {
    logger()->trace("detection {} rotated by a near symmetry: then about its axis by its "
                    "asymmetric feature, {:.2f} -> {:.2f} of it confirmed",
                    k, rotation->asymmetry_as_found, rotation->asymmetry_confirmed);
    r.T_rotated = rotation->T_scene_model;
    r.coverage = rotation->coverage;
  }
  r.rotated =
      contradictedShare(tallyPoints(*prep.verify, scene, r.T_rotated, params.verify_tolerance_mm,
                                    {.subset = &s.differing, .stop = {}, .sort_unmeasured = true}),
                        min_seen);
  logger()->trace("detection {}: {:.2f} of the differing points contradicted as found, {:.2f} "
                  "rotated",
                  k, r.as_found, r.rotated);
  // The view's differing points rule a pose out only where they are seen at a known rotation.
  if (!rotation_unseen && r.rotated > r.as_found + kRotationMargin)
    r.ruling = Ruling::Rotated;
  else if (!rotation_unseen && r.as_found > r.rotated + kRotationMargin)
    r.ruling = Ruling::Found;
  // With views joined, the revolved surface they saw tells at any rotation what the view cannot:
  // a cup's mouth from its bottom (the scan sees into the one and onto the other). It decides
  // when it can.
  if (prep.joined_revolved_surface) {
    const auto& surface = prep.joined_revolved_surface_differing[j];
    const double tolerance = params.verify_tolerance_mm;
    const double surface_found =
        revolvedSurfaceScore(*prep.joined_revolved_surface, *prep.near_axis, scene, d.T_scene_model,
                             tolerance, surface.differing_inverse);
    const double surface_rotated =
        revolvedSurfaceScore(*prep.joined_revolved_surface, *prep.near_axis, scene, r.T_rotated,
                             tolerance, surface.differing);
    logger()->trace("detection {}: the joined revolved surface's differing points score {:.2f} "
                    "as found, {:.2f} rotated",
                    k, surface_found, surface_rotated);
    if (surface_found > surface_rotated + kRotationMargin)
      r.ruling = Ruling::Rotated;
    else if (surface_rotated > surface_found + kRotationMargin)
      r.ruling = Ruling::Found;
    if (std::abs(surface_found - surface_rotated) > kRotationMargin)
      r.ruled_by = "the joined revolved surface";
  }
  // The found pose's asymmetric feature is confirmed at no rotation about its axis
  // (resolveAxisRotations); a rotated pose whose asymmetric feature the scan confirms explains
  // the handle the found one leaves unexplained.
  if (r.ruling == Ruling::Neither && rotation_unseen &&
      seesAsymmetry(prep, scene, r.T_rotated, params.verify_tolerance_mm)) {
    r.ruling = Ruling::Found;
    r.ruled_by = "the rotated pose's asymmetric feature";
  }
  return r;
}

} // namespace

std::vector<Detection> resolveNearSymmetries(std::vector<Detection> detections,
                                             const ModelPrep& prep, const VerifyScene& scene,
                                             const MatchingParams& params,
                                             const PoseVerifier& verify,
                                             const PoseRefiner& refine) {
  const std::size_t min_seen = minDistinguishingPoints(prep.verify->points.size());
  tbb::parallel_for(std::size_t{0}, detections.size(), [&](std::size_t k) {
    Detection& d = detections[k];
    // With the rotation about a near axis not seen (seesAsymmetry), the differing points of both
    // poses lie at unknown rotations: they rule neither out.
    const bool rotation_unseen =
        prep.near_axis && !seesAsymmetry(prep, scene, d.T_scene_model, params.verify_tolerance_mm);
    for (std::size_t j = 0; j < prep.symmetries.size(); ++j) {
      const NearSymmetry& s = prep.symmetries[j];
      if (repeatsItself(s, prep.verify->points.size())) {
        // The view repeats itself under S: nothing in any scan can tell T from T·S. (Verifying
        // T·S would not tell either: the view's own self-occlusion, seen from the teach camera,
        // favours the pose that keeps it where the scan's camera sees it.)
        d.alternative_poses.push_back(d.T_scene_model * s.S_model);
        continue;
      }
      const SymmetryRuling r =
          ruleSymmetry(prep, j, scene, params, verify, refine, d, k, rotation_unseen, min_seen);
      if (r.ruling == Ruling::Rotated || r.coverage < params.min_coverage)
        continue;
      if (r.ruling == Ruling::Found) {
        logger()->debug("detection {} rotated by a near symmetry, ruled by {} ({:.2f} of the "
                        "view's differing points contradicted as found, {:.2f} rotated); "
                        "coverage {:.3f} -> {:.3f}",
                        k, r.ruled_by, r.as_found, r.rotated, d.coverage, r.coverage);
        d.T_scene_model = r.T_rotated;
        d.coverage = r.coverage;
        d.score = r.coverage;
        d.refined = true;
        d.matched_features.clear();  // they supported the pose it had,
        d.alternative_poses.clear(); // and so did these
      } else {
        d.alternative_poses.push_back(r.T_rotated);
      }
    }
  });
  return detections;
}

} // namespace scanpick::core::detail
