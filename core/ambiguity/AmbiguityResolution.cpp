#include "core/ambiguity/AmbiguityResolution.h"

#include "core/common/Log.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace scanpick::core::detail {
namespace {

/// A detection sees the detail of its view when the scan confirms at least this share of it.
constexpr double kMinDetailSeenShare = 0.25;

/// Which pose of a detection and its turn by a near symmetry the scan rules out.
enum class Ruling { Neither, Found, Turned };

/// A view seen from the side holds its part's place along the axis loosely (a cylinder slides
/// along itself); the joined body's ends are looked for within this distance of it, mm, in steps
/// of kBodySlideStepMm.
constexpr double kBodySlideMm = 6.0;
constexpr double kBodySlideStepMm = 0.5;

/// (confirmed − violations) of the `subset` of `body`'s points at `T_scene_model` slid along
/// `axis` (by up to kBodySlideMm) to where it is best, as a share of those facing the camera (at
/// least 8).
double bodyScore(const VerifyModel& body, const RevolutionAxis& axis, const VerifyScene& scene,
                 const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                 const std::vector<std::uint32_t>& subset) {
  double best = -std::numeric_limits<double>::infinity();
  const int steps = static_cast<int>(std::lround(kBodySlideMm / kBodySlideStepMm));
  for (int step = -steps; step <= steps; ++step) {
    const Eigen::Isometry3d T =
        T_scene_model * Eigen::Translation3d(step * kBodySlideStepMm * axis.direction);
    const PointTally t = tallyPoints(body, scene, T, tolerance_mm,
                                     {.subset = &subset, .stop = {}, .sort_unmeasured = false});
    best = std::max(best, (double(t.confirmed) - double(t.violations)) /
                              double(std::max<std::size_t>(8, t.points - t.turned_away)));
  }
  return best;
}

/// A turn the detail chooses is taken only while the pose verifies at most this much worse.
constexpr double kDetailTurnCoverageSlack = 0.05;
/// ICP's polish of a turn the joined detail chooses is kept while the detail's score drops by at
/// most this much.
constexpr double kPolishedDetailSlack = 0.05;

/// The differing points of a near symmetry tell two poses apart only when at least this share of
/// the view's points (and 8) are among them and not hidden: a handful at the view's edges is noise.
constexpr double kMinDistinguishingShare = 0.02;

/// A detection is turned by a near symmetry when the scan contradicts this much larger a share of
/// its differing points than of the turned pose's (contradictedShare).
constexpr double kTurnMargin = 0.1;

} // namespace

namespace {

/// Which detail a tally looks at: the view's own, or the joined one (ModelPrep::joined_detail).
enum class Detail { Own, Joined };

/// (confirmed − violations) of the view's detail at `T_scene_model`, as a share: of every point of
/// the view's own detail; of a joined detail (seen from every side, of which a camera sees at most
/// about half), of its points facing the camera, but at least a quarter of them all.
struct DetailTally {
  PointTally tally;
  double of = 1.0;
  [[nodiscard]] double score() const {
    return (double(tally.confirmed) - double(tally.violations)) / of;
  }
  [[nodiscard]] bool seen() const {
    return double(tally.confirmed) >= kMinDetailSeenShare * of && tally.confirmed > 0;
  }
};

/// The highest DetailTally::score() that `which` detail's tally `t` can reach with `left` points
/// not looked at: each of them facing the camera and confirmed (as that raises the score while
/// fewer are confirmed than face the camera); with none left, the score.
double detailScoreBound(Detail which, const PointTally& t, std::size_t left) {
  const double points = double(t.points + left);
  const double reachable = double(t.confirmed) - double(t.violations) + double(left);
  if (which == Detail::Own)
    return reachable / std::max(1.0, points);
  const double facing = double(t.points - t.turned_away + left);
  return reachable / std::max({1.0, facing, 0.25 * points});
}

DetailTally tallyDetail(const ModelPrep& prep, Detail which, const VerifyScene& scene,
                        const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                        const TallyStop& stop = {}) {
  if (which == Detail::Own) {
    const PointTally t =
        tallyPoints(*prep.verify, scene, T_scene_model, tolerance_mm,
                    {.subset = &prep.near_axis_detail, .stop = stop, .sort_unmeasured = false});
    return {t, double(std::max<std::size_t>(1, t.points))};
  }
  const PointTally t = tallyPoints(*prep.joined_detail, scene, T_scene_model, tolerance_mm,
                                   {.subset = nullptr, .stop = stop, .sort_unmeasured = false});
  const double facing = double(t.points - t.turned_away);
  return {t, std::max({1.0, facing, 0.25 * double(t.points)})};
}

/// `which` detail's score at `T_scene_model` when it is above `beat`; none otherwise, its tally
/// stopped as soon as it cannot be.
std::optional<double> detailScoreAbove(const ModelPrep& prep, Detail which,
                                       const VerifyScene& scene,
                                       const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                                       double beat) {
  const std::size_t total =
      which == Detail::Own ? prep.near_axis_detail.size() : prep.joined_detail->points.size();
  const auto cannot_beat = [&](const PointTally& so_far, std::size_t left) {
    return detailScoreBound(which, so_far, left) <= beat;
  };
  const DetailTally t = tallyDetail(prep, which, scene, T_scene_model, tolerance_mm, cannot_beat);
  if (t.tally.points < total || !(t.score() > beat))
    return std::nullopt;
  return t.score();
}

/// The turn about the view's near axis (1° steps) at which `which` detail scores best, if it
/// scores at least kMinDetailSeenShare and kTurnMargin more than at `T_scene_model`.
std::optional<DetailTurn> bestTurn(const ModelPrep& prep, Detail which, const VerifyScene& scene,
                                   double tolerance_mm, const Eigen::Isometry3d& T_scene_model) {
  const RevolutionAxis& axis = *prep.near_axis;
  const double as_found = tallyDetail(prep, which, scene, T_scene_model, tolerance_mm).score();
  // Only a turn scoring at least this is taken: each tally stops as soon as it cannot reach it
  // (or the best so far), most of them after a few misses.
  const double needed = std::max(kMinDetailSeenShare, as_found + kTurnMargin);
  DetailTurn turn;
  turn.T_scene_model = T_scene_model;
  turn.detail_as_found = as_found;
  // Scores above this are those of at least `needed`.
  turn.detail_confirmed = std::nextafter(needed, -std::numeric_limits<double>::infinity());
  for (int degrees = 1; degrees < 360; ++degrees) {
    const Eigen::Isometry3d T = T_scene_model * axis.turn(degrees * M_PI / 180.0);
    if (const auto score =
            detailScoreAbove(prep, which, scene, T, tolerance_mm, turn.detail_confirmed)) {
      turn.detail_confirmed = *score;
      turn.T_scene_model = T;
    }
  }
  if (turn.detail_confirmed < needed)
    return std::nullopt;
  return turn;
}

} // namespace

bool seesDetail(const ModelPrep& prep, const VerifyScene& scene,
                const Eigen::Isometry3d& T_scene_model, double tolerance_mm) {
  return tallyDetail(prep, Detail::Own, scene, T_scene_model, tolerance_mm).seen() ||
         (prep.joined_detail &&
          tallyDetail(prep, Detail::Joined, scene, T_scene_model, tolerance_mm).seen());
}

std::optional<DetailTurn> turnByDetail(const ModelPrep& prep, const VerifyScene& scene,
                                       const MatchingParams& params, const PoseVerifier& verify,
                                       const PosePolisher& polish,
                                       const Eigen::Isometry3d& T_scene_model, double coverage,
                                       bool ask_joined) {
  if (!prep.near_axis || prep.near_axis_detail.empty())
    return std::nullopt;
  const double tolerance = params.verify_tolerance_mm;
  if (auto turn = bestTurn(prep, Detail::Own, scene, tolerance, T_scene_model)) {
    // The turn is known to a degree: ICP finishes it.
    turn->coverage = verify(turn->T_scene_model);
    const Eigen::Isometry3d polished = polish(turn->T_scene_model);
    if (const double polished_coverage = verify(polished); polished_coverage >= turn->coverage) {
      turn->T_scene_model = polished;
      turn->coverage = polished_coverage;
      turn->refined = true;
    }
    // The body must still agree: a side view turned far about its axis moves its visible half
    // out of the camera's sight, where a handle-like patch of another part can confirm the
    // detail.
    if (turn->coverage >= coverage - kDetailTurnCoverageSlack)
      return turn;
  }
  if (!prep.joined_detail || !ask_joined)
    return std::nullopt;
  // Where the view's own detail tells nothing, the detail as the joined views saw it (a handle
  // seen from the front by a view that saw it from behind). The body is the same surface at any
  // turn, but turned far the view's own half of it faces away from the camera: the pose keeps the
  // coverage it was found with, and ICP's polish only while the detail stays as confirmed.
  auto turn = bestTurn(prep, Detail::Joined, scene, tolerance, T_scene_model);
  if (!turn)
    return std::nullopt;
  const Eigen::Isometry3d polished = polish(turn->T_scene_model);
  if (tallyDetail(prep, Detail::Joined, scene, polished, tolerance).score() >=
      turn->detail_confirmed - kPolishedDetailSlack) {
    turn->T_scene_model = polished;
    turn->refined = true;
  }
  turn->coverage = std::max(coverage, verify(turn->T_scene_model));
  return turn;
}

std::vector<Detection> resolveDetailTurns(std::vector<Detection> detections, const ModelPrep& prep,
                                          const VerifyScene& scene, const MatchingParams& params,
                                          const PoseVerifier& verify, const PosePolisher& polish) {
  tbb::parallel_for(std::size_t{0}, detections.size(), [&](std::size_t k) {
    Detection& d = detections[k];
    const auto turn =
        turnByDetail(prep, scene, params, verify, polish, d.T_scene_model, d.coverage);
    if (!turn)
      return;
    logger()->debug("detection {} turned about its axis by its detail: {:.2f} -> {:.2f} of the "
                    "detail confirmed, coverage {:.3f} -> {:.3f}",
                    k, turn->detail_as_found, turn->detail_confirmed, d.coverage, turn->coverage);
    takeTurn(d, *turn);
  });
  return detections;
}

void takeTurn(Detection& detection, const DetailTurn& turn) {
  detection.T_scene_model = turn.T_scene_model;
  detection.coverage = turn.coverage;
  detection.score = turn.coverage;
  detection.refined = turn.refined;
  detection.matched_features.clear();
  detection.alternative_poses.clear();
}

namespace {

/// How the scan rules between a detection's pose and its pose turned by one near symmetry.
struct SymmetryRuling {
  Ruling ruling = Ruling::Neither;
  const char* ruled_by = "the view's differing points";
  double as_found = 0.0, turned = 0.0; ///< the view's differing points contradicted
  Eigen::Isometry3d T_turned;          ///< T·S, polished (and turned by its detail)
  double coverage = 0.0;               ///< T_turned's verification score
};

/// The ruling between detection `d` (number `k`, for the log) at T and T·S for the view's near
/// symmetry `j` (resolveNearSymmetries). `turn_unseen`: the turn about the view's near axis is not
/// seen at T. `min_seen`: fewer differing points seen tell nothing (contradictedShare).
SymmetryRuling ruleSymmetry(const ModelPrep& prep, std::size_t j, const VerifyScene& scene,
                            const MatchingParams& params, const PoseVerifier& verify,
                            const PosePolisher& polish, const Detection& d, std::size_t k,
                            bool turn_unseen, std::size_t min_seen) {
  const NearSymmetry& s = prep.symmetries[j];
  SymmetryRuling r;
  r.as_found = contradictedShare(
      tallyPoints(*prep.verify, scene, d.T_scene_model, params.verify_tolerance_mm,
                  {.subset = &s.differing_inverse, .stop = {}, .sort_unmeasured = true}),
      min_seen);
  r.T_turned = polish(d.T_scene_model * s.S_model);
  r.coverage = verify(r.T_turned);
  // Turned end over end, a cup's handle lies at another turn about its axis: its detail says
  // which.
  if (const auto turn = turnByDetail(prep, scene, params, verify, polish, r.T_turned, r.coverage)) {
    logger()->trace("detection {} turned by a near symmetry: then about its axis by its "
                    "detail, {:.2f} -> {:.2f} of it confirmed",
                    k, turn->detail_as_found, turn->detail_confirmed);
    r.T_turned = turn->T_scene_model;
    r.coverage = turn->coverage;
  }
  r.turned =
      contradictedShare(tallyPoints(*prep.verify, scene, r.T_turned, params.verify_tolerance_mm,
                                    {.subset = &s.differing, .stop = {}, .sort_unmeasured = true}),
                        min_seen);
  logger()->trace("detection {}: {:.2f} of the differing points contradicted as found, {:.2f} "
                  "turned",
                  k, r.as_found, r.turned);
  // The view's differing points rule a pose out only where they are seen at a known turn.
  if (!turn_unseen && r.turned > r.as_found + kTurnMargin)
    r.ruling = Ruling::Turned;
  else if (!turn_unseen && r.as_found > r.turned + kTurnMargin)
    r.ruling = Ruling::Found;
  // With views joined, the body they saw tells at any turn what the view cannot: a cup's
  // mouth from its bottom (the scan sees into the one and onto the other). It decides when it
  // can.
  if (prep.joined_body) {
    const auto& body = prep.joined_body_differing[j];
    const double tolerance = params.verify_tolerance_mm;
    const double body_found = bodyScore(*prep.joined_body, *prep.near_axis, scene, d.T_scene_model,
                                        tolerance, body.differing_inverse);
    const double body_turned =
        bodyScore(*prep.joined_body, *prep.near_axis, scene, r.T_turned, tolerance, body.differing);
    logger()->trace("detection {}: the joined body's differing points score {:.2f} as found, "
                    "{:.2f} turned",
                    k, body_found, body_turned);
    if (body_found > body_turned + kTurnMargin)
      r.ruling = Ruling::Turned;
    else if (body_turned > body_found + kTurnMargin)
      r.ruling = Ruling::Found;
    if (std::abs(body_found - body_turned) > kTurnMargin)
      r.ruled_by = "the joined body";
  }
  // The found pose's detail is confirmed at no turn about its axis (resolveDetailTurns); a
  // turned pose whose detail the scan confirms explains the handle the found one leaves
  // unexplained.
  if (r.ruling == Ruling::Neither && turn_unseen &&
      seesDetail(prep, scene, r.T_turned, params.verify_tolerance_mm)) {
    r.ruling = Ruling::Found;
    r.ruled_by = "the turned pose's detail";
  }
  return r;
}

} // namespace

std::vector<Detection> resolveNearSymmetries(std::vector<Detection> detections,
                                             const ModelPrep& prep, const VerifyScene& scene,
                                             const MatchingParams& params,
                                             const PoseVerifier& verify,
                                             const PosePolisher& polish) {
  const std::size_t min_seen = std::max<std::size_t>(
      8, static_cast<std::size_t>(kMinDistinguishingShare * double(prep.verify->points.size())));
  tbb::parallel_for(std::size_t{0}, detections.size(), [&](std::size_t k) {
    Detection& d = detections[k];
    // With the turn about a near axis not seen (seesDetail), the differing points of both poses
    // lie at unknown turns: they rule neither out.
    const bool turn_unseen =
        prep.near_axis && !seesDetail(prep, scene, d.T_scene_model, params.verify_tolerance_mm);
    for (std::size_t j = 0; j < prep.symmetries.size(); ++j) {
      const NearSymmetry& s = prep.symmetries[j];
      if (s.differing.size() < min_seen && s.differing_inverse.size() < min_seen) {
        // The view repeats itself under S: nothing in any scan can tell T from T·S. (Verifying
        // T·S would not tell either: the view's own self-occlusion, seen from the teach camera,
        // favours the pose that keeps it where the scan's camera sees it.)
        d.alternative_poses.push_back(d.T_scene_model * s.S_model);
        continue;
      }
      const SymmetryRuling r =
          ruleSymmetry(prep, j, scene, params, verify, polish, d, k, turn_unseen, min_seen);
      if (r.ruling == Ruling::Turned || r.coverage < params.min_coverage)
        continue;
      if (r.ruling == Ruling::Found) {
        logger()->debug("detection {} turned by a near symmetry, ruled by {} ({:.2f} of the "
                        "view's differing points contradicted as found, {:.2f} turned); coverage "
                        "{:.3f} -> {:.3f}",
                        k, r.ruled_by, r.as_found, r.turned, d.coverage, r.coverage);
        d.T_scene_model = r.T_turned;
        d.coverage = r.coverage;
        d.score = r.coverage;
        d.refined = true;
        d.matched_features.clear();  // they supported the pose it had,
        d.alternative_poses.clear(); // and so did these
      } else {
        d.alternative_poses.push_back(r.T_turned);
      }
    }
  });
  return detections;
}

} // namespace scanpick::core::detail
