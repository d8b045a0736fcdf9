#include "core/pipeline/ModelPrep.h"

#include "core/common/Log.h"
#include "core/features/FeatureExtraction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>
#include <tuple>

namespace scanpick::core::detail {
namespace {

/// fitRevolutionAxis's angle tolerance (10°). A view whose normals fit an axis this share or more
/// (but fewer than fitRevolutionAxis's default 98 %) is a surface of revolution but for a detail:
/// the cup's side views fit 93-96 %, the support's and the coat-rack's views far less.
constexpr double kRevolutionTolerance = 0.17;
constexpr double kNearRevolutionShare = 0.85;
/// Cells (height along and distance from the axis) in which detailPoints compares angles: 2-3 mm
/// cells split a cup's body (its points scatter by the fit's residual), 6 mm ones keep it whole.
constexpr double kDetailCellMm = 6.0;
/// Cell of a view's revolved body (RevolvedBody), mm: about the spacing of its verification points.
constexpr double kBodyCellMm = 2.0;
/// A view is a surface of revolution but for a detail only while the detail is at most this
/// share of its points (a cup's handle: 5-13 %). A flat face seen along its normal fits a rim axis
/// through any circle among its points, and then no cell of it turns: all of it is "detail".
constexpr double kMaxDetailShare = 0.5;
/// A detection sees the detail of its view when the scan confirms at least this share of it.
constexpr double kMinDetailSeenShare = 0.25;

/// Whether `S` (model frame) is a turn about `axis`: its rotation axis within 10° of the axis
/// direction, and the axis point staying within 2 mm.
bool isTurnAbout(const RevolutionAxis& axis, const Eigen::Isometry3d& S) {
  const Eigen::AngleAxisd turn(S.linear());
  return std::abs(turn.axis().dot(axis.direction)) > std::cos(10.0 * M_PI / 180.0) &&
         (S * axis.point_mm - axis.point_mm).norm() < 2.0;
}

/// How deep below a view's nearest flat point rimAxis looks for its rim, mm.
constexpr float kRimDepthMm = 3.0f;
/// cos 10°: a flat point's normal, and the rim circle's, agree with the view's mean normal.
const float kRimAngleCos = std::cos(static_cast<float>(M_PI) / 18.0f);

/// The axis of a view seen along it (a cup from above: its rim's ring and its inside's disk, whose
/// normals point one way and so fit no axis): the mean direction of its normals, through the
/// centre of the circle (the project's circle search) that the nearest of its flat points make.
/// Nothing unless most normals agree within 10° and those points hold a circle.
std::optional<RevolutionAxis> rimAxis(const std::vector<Eigen::Vector3f>& points,
                                      const std::vector<Eigen::Vector3f>& normals) {
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  for (const auto& n : normals)
    if (n.allFinite())
      mean += n;
  if (mean.norm() < 1e-6f)
    return std::nullopt;
  const Eigen::Vector3f direction = mean.normalized();
  std::vector<std::size_t> flat;
  float top = -std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    if (normals[i].allFinite() && normals[i].dot(direction) > kRimAngleCos) {
      flat.push_back(i);
      top = std::max(top, points[i].dot(direction));
    }
  if (flat.size() < points.size() / 2)
    return std::nullopt;
  std::vector<Eigen::Vector3f> nearest;
  for (const std::size_t i : flat)
    if (points[i].dot(direction) > top - kRimDepthMm)
      nearest.push_back(points[i]);
  FeatureParams circle;
  circle.lines = false;
  circle.circle_threshold_mm = 1.5;
  circle.ransac_size = std::max(30, int(nearest.size() / 3));
  circle.max_iterations = 500;
  circle.max_features = 1;
  circle.min_circle_radius_mm = 10.0;
  const FeatureExtraction found = extractFeatures(nearest, circle, 0);
  if (found.features.empty())
    return std::nullopt;
  const Feature& rim = found.features.front();
  if (std::abs(rim.direction.dot(direction)) < kRimAngleCos)
    return std::nullopt;
  RevolutionAxis axis;
  axis.point_mm = rim.centre_mm.cast<double>();
  axis.direction = direction.cast<double>();
  axis.inlier_share = double(flat.size()) / double(points.size());
  return axis;
}

/// At most about this many points make a joined detail (the cup's views' own details hold 92–222):
/// its turn search then costs about what the view's own does.
constexpr std::size_t kJoinedDetailPoints = 250;
/// At most about this many points make a joined body (its differing points under a cup's turn end
/// over end, about a quarter of them, are tallied at 25 places along the axis per detection).
constexpr std::size_t kJoinedBodyPoints = 2000;
/// The joined views' ICP model keeps as many points as this many views (refine.model_points each):
/// it covers the whole part, where one view's count leaves the others' surfaces sparse
/// (docs/design-notes-refinement.md).
constexpr int kJoinedRefineViews = 3;

/// The points of a view and of the views joined to it (TaughtModel::joined_views), in the view's
/// frame: each strided to about `points`, with normals facing its own teach camera.
VerifyModel joinedPoints(const TaughtModel& model, const VerifyModel& view, int points,
                         double normal_radius_mm) {
  VerifyModel all = view;
  for (const JoinedView& other : model.joined_views) {
    SceneIndexOptions options;
    options.normal_radius_mm = normal_radius_mm;
    options.viewpoint_mm = other.camera_mm;
    // Normals for the points makeVerifyModel keeps only.
    options.normal_stride =
        static_cast<int>(verifyModelStride(other.cloud_mm.validCount(), points));
    const auto seen = makeVerifyModel(TaughtModel{}, SceneIndex(other.cloud_mm, options), points);
    all.points.insert(all.points.end(), seen->points.begin(), seen->points.end());
    all.normals.insert(all.normals.end(), seen->normals.begin(), seen->normals.end());
  }
  all.body = nullptr;
  return all;
}

/// The ICP model of a view and the views joined to it (`all`, joinedPoints): at most `points` of
/// theirs, each with the normal it had facing its own teach camera.
std::shared_ptr<const RefineModel> joinedRefineModel(const VerifyModel& all, int points) {
  PointCloud cloud;
  cloud.points_mm = all.points;
  cloud.normals = all.normals;
  cloud.width = static_cast<std::uint32_t>(cloud.points_mm.size());
  cloud.height = 1;
  SceneIndexOptions options;
  options.orient_cloud_normals = false;
  options.normal_radius_mm = RefineModel::kNormalRadiusMm;
  return std::make_shared<const RefineModel>(std::make_shared<const SceneIndex>(cloud, options),
                                             points);
}

/// The points of `all` listed in `indices`, every `stride`-th, with `body`.
std::shared_ptr<VerifyModel> pick(const VerifyModel& all, const std::vector<std::uint32_t>& indices,
                                  std::size_t stride, std::shared_ptr<const RevolvedBody> body) {
  auto picked = std::make_shared<VerifyModel>();
  for (std::size_t k = 0; k < indices.size(); k += std::max<std::size_t>(1, stride)) {
    picked->points.push_back(all.points[indices[k]]);
    picked->normals.push_back(all.normals[indices[k]]);
  }
  picked->body = std::move(body);
  return picked;
}

/// The joined views' detail (a cup's handle from every side) and body (its mouth and its bottom),
/// from `all` (joinedPoints): the points off the surface the view turns about `axis`
/// (detailPoints), strided to about kJoinedDetailPoints, with the view's body; and the others,
/// with the body they make.
std::pair<std::shared_ptr<const VerifyModel>, std::shared_ptr<const VerifyModel>>
joinedDetailAndBody(const VerifyModel& all, const VerifyModel& view, const RevolutionAxis& axis) {
  const auto detail = detailPoints(all.points, axis, kDetailCellMm);
  std::vector<bool> in_detail(all.points.size(), false);
  for (const std::uint32_t i : detail)
    in_detail[i] = true;
  std::vector<std::uint32_t> body;
  for (std::uint32_t i = 0; i < all.points.size(); ++i)
    if (!in_detail[i])
      body.push_back(i);
  const std::size_t detail_stride = (detail.size() + kJoinedDetailPoints - 1) / kJoinedDetailPoints;
  const std::size_t body_stride = (body.size() + kJoinedBodyPoints - 1) / kJoinedBodyPoints;
  return {pick(all, detail, detail_stride, view.body),
          pick(all, body, body_stride,
               std::make_shared<const RevolvedBody>(all.points, axis, kBodyCellMm, detail))};
}

/// The outer radius of the surface `prep`'s view turns about its axis (its detail left out) and
/// where its wall ends in the taught cloud (`surface`: its points with their normals), seen from
/// the teach camera.
void findWallEnds(ModelPrep& prep, const SceneIndex& surface_points) {
  const RevolutionAxis& axis = prep.axis ? *prep.axis : *prep.near_axis;
  std::vector<bool> in_detail(prep.verify->points.size(), false);
  for (const std::uint32_t i : prep.near_axis_detail)
    in_detail[i] = true;
  std::vector<Eigen::Vector3f> surface;
  for (std::size_t i = 0; i < prep.verify->points.size(); ++i)
    if (!in_detail[i])
      surface.push_back(prep.verify->points[i]);
  prep.wall_radius_mm = outerRadius(surface, axis.point_mm, axis.direction);
  const TaughtModel& model = *prep.model;
  prep.wall_ends = findAxialEnds(
      surface_points.points(), axis.point_mm, axis.direction, prep.wall_radius_mm,
      model.T_teach_model.inverse().translation(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), {}, surface_points.normals());
  const double unseen = std::numeric_limits<double>::quiet_NaN();
  logger()->debug("model '{}': wall of radius {:.2f} mm about its axis, its ends at {:.2f} and "
                  "{:.2f} mm (nan: not seen)",
                  model.name, prep.wall_radius_mm, prep.wall_ends.low_mm.value_or(unseen),
                  prep.wall_ends.high_mm.value_or(unseen));
}

/// The points of `body` that `S` (model frame → model frame) moves out of its body's cells.
std::vector<std::uint32_t> movedOffBody(const VerifyModel& body, const Eigen::Isometry3d& S) {
  const Eigen::Isometry3f S_f = S.cast<float>();
  std::vector<std::uint32_t> off;
  for (std::uint32_t k = 0; k < body.points.size(); ++k)
    if (!body.body->contains(S_f * body.points[k]))
      off.push_back(k);
  return off;
}

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

/// The view's axis: a surface of revolution (ModelPrep::axis), or one but for a detail
/// (ModelPrep::near_axis and its detail); then the body its points make turned about it and the
/// ends of its wall. `surface`: the view's points with their normals.
void fitAxes(ModelPrep& prep, const TaughtModel& model, const SceneIndex& surface) {
  prep.axis = fitRevolutionAxis(prep.verify->points, prep.verify->normals);
  if (prep.axis)
    prep.axis = refineRevolutionAxis(prep.verify->points, prep.verify->normals, *prep.axis);
  if (prep.axis)
    logger()->debug("model '{}' is a surface of revolution ({:.0f} % of its normals), its turn "
                    "is not seen: axis through ({:.1f}, {:.1f}, {:.1f}) mm along ({:.3f}, "
                    "{:.3f}, {:.3f})",
                    model.name, 100.0 * prep.axis->inlier_share, prep.axis->point_mm.x(),
                    prep.axis->point_mm.y(), prep.axis->point_mm.z(), prep.axis->direction.x(),
                    prep.axis->direction.y(), prep.axis->direction.z());
  else if (auto near = fitRevolutionAxis(prep.verify->points, prep.verify->normals,
                                         kRevolutionTolerance, kNearRevolutionShare);
           near || (near = rimAxis(prep.verify->points, prep.verify->normals))) {
    // The axis is refined on the surface without the detail, which is then found again.
    auto detail = detailPoints(prep.verify->points, *near, kDetailCellMm);
    near = refineRevolutionAxis(prep.verify->points, prep.verify->normals, *near, detail);
    detail = detailPoints(prep.verify->points, *near, kDetailCellMm);
    const std::size_t count = prep.verify->points.size();
    if (double(detail.size()) <= kMaxDetailShare * double(count)) {
      prep.near_axis = near;
      prep.near_axis_detail = std::move(detail);
      logger()->debug("model '{}' is a surface of revolution but for a detail ({:.0f} % of its "
                      "normals; {} of its {} points off the surface): its turn is seen only "
                      "where a scan confirms the detail",
                      model.name, 100.0 * near->inlier_share, prep.near_axis_detail.size(), count);
    } else {
      logger()->debug("model '{}' fits an axis with {:.0f} % of its normals, but {} of its {} "
                      "points lie off the surface they turn: not a surface of revolution",
                      model.name, 100.0 * near->inlier_share, detail.size(), count);
    }
  }
  if (prep.axis || prep.near_axis) {
    auto verify = std::make_shared<VerifyModel>(*prep.verify);
    verify->body = std::make_shared<const RevolvedBody>(verify->points,
                                                        prep.axis ? *prep.axis : *prep.near_axis,
                                                        kBodyCellMm, prep.near_axis_detail);
    prep.verify = std::move(verify);
    findWallEnds(prep, surface);
  }
}

/// The view's near symmetries (findNearSymmetries) less the turns about its axis, and what each
/// moves off the joined body.
void findSymmetries(ModelPrep& prep, const TaughtModel& model, const RecognitionParams& params,
                    double tolerance_mm) {
  prep.symmetries = findNearSymmetries(model, *prep.verify, *prep.refine, params.refine,
                                       tolerance_mm, params.matching.symmetry_overlap);
  // A surface of revolution reports its turn about the axis as free instead, and one but for a
  // detail as seen or free by the detail (seesDetail); their other near symmetries (a cup or a
  // pipe turned end over end) stay.
  if (prep.axis || prep.near_axis) {
    const RevolutionAxis& axis = prep.axis ? *prep.axis : *prep.near_axis;
    const auto turns = std::erase_if(
        prep.symmetries, [&](const NearSymmetry& s) { return isTurnAbout(axis, s.S_model); });
    logger()->debug("model '{}': {} near symmetries are turns about its axis, {} others",
                    model.name, turns, prep.symmetries.size());
  }
  prep.joined_body_differing.clear();
  if (prep.joined_body)
    for (const NearSymmetry& s : prep.symmetries) {
      prep.joined_body_differing.push_back({movedOffBody(*prep.joined_body, s.S_model),
                                            movedOffBody(*prep.joined_body, s.S_model.inverse())});
      logger()->debug(
          "model '{}': a near symmetry moves {} / {} of the joined body's {} points off it",
          model.name, prep.joined_body_differing.back().differing.size(),
          prep.joined_body_differing.back().differing_inverse.size(),
          prep.joined_body->points.size());
    }
}

/// What the near symmetries are found with: none without a search (matching.symmetry_overlap) or
/// verification. The symmetries' ICP is the same whether the detections are refined in the end or
/// not.
std::optional<SymmetryKey> symmetryKey(const RecognitionParams& params) {
  const double tolerance = params.matching.verify_tolerance_mm;
  if (!(params.matching.symmetry_overlap > 0 && tolerance > 0))
    return std::nullopt;
  RefineParams symmetry_icp = params.refine;
  symmetry_icp.enabled = false;
  return SymmetryKey{params.matching.symmetry_overlap, tolerance, symmetry_icp};
}

} // namespace

bool needsModelPrep(const RecognitionParams& params) {
  return params.matching.verify_tolerance_mm > 0 || params.refine.enabled;
}

std::shared_ptr<const ModelPrep> prepareModel(std::vector<std::shared_ptr<const ModelPrep>>& preps,
                                              const std::shared_ptr<const TaughtModel>& model,
                                              const RecognitionParams& params) {
  const int points = std::max(10, params.refine.model_points);
  const double radius = params.keypoints.normal_radius_mm;
  const double sampling = params.matching.surface_sampling_mm;
  const double tolerance = params.matching.verify_tolerance_mm;
  const std::optional<SymmetryKey> symmetry_key = symmetryKey(params);
  // ICP needs the model prepared: for refinement, to polish surface voting's poses, and to fit
  // near symmetries.
  const bool needs_refine = params.refine.enabled || sampling > 0 || symmetry_key;
  auto found = std::find_if(preps.begin(), preps.end(), [&](const auto& p) {
    return p->model == model && p->points == points && p->normal_radius_mm == radius;
  });
  // Refinement fits the views joined to this one too, when there are any.
  const bool joined_refine = params.refine.enabled && !model->joined_views.empty();
  if (found != preps.end() && (!needs_refine || (*found)->refine) &&
      (!joined_refine || (*found)->joined_refine) &&
      (sampling <= 0 || ((*found)->pairs && (*found)->surface_sampling_mm == sampling)) &&
      (!symmetry_key || (*found)->symmetry_key == symmetry_key))
    return *found;
  auto prep = std::make_shared<ModelPrep>();
  std::shared_ptr<const SceneIndex> surface; // the model's points and normals, when made here
  // The views joined to this one, made once when something needs them.
  const auto joined = [&]() -> const VerifyModel& {
    if (!prep->joined_points)
      prep->joined_points =
          std::make_shared<const VerifyModel>(joinedPoints(*model, *prep->verify, points, radius));
    return *prep->joined_points;
  };
  if (found != preps.end()) {
    *prep = **found;
    preps.erase(found);
  } else {
    prep->model = model;
    prep->points = points;
    prep->normal_radius_mm = radius;
    surface = modelSurface(*model, radius);
    prep->verify = makeVerifyModel(*model, *surface, points);
    fitAxes(*prep, *model, *surface);
    if (prep->near_axis && !model->joined_views.empty()) {
      std::tie(prep->joined_detail, prep->joined_body) =
          joinedDetailAndBody(joined(), *prep->verify, *prep->near_axis);
      logger()->debug("model '{}': its detail holds {} points with {} views joined ({} alone), "
                      "its body {}",
                      model->name, prep->joined_detail->points.size(), model->joined_views.size(),
                      prep->near_axis_detail.size(), prep->joined_body->points.size());
    }
  }
  // Refinement's surface is verification's when their normals agree (the same radius and
  // teach camera): estimated once.
  if (needs_refine && !prep->refine)
    prep->refine = surface && radius == RefineModel::kNormalRadiusMm
                       ? std::make_shared<const RefineModel>(surface, points)
                       : std::make_shared<const RefineModel>(
                             model->cloud_mm, points,
                             Eigen::Vector3d(model->T_teach_model.inverse().translation()));
  if (joined_refine && !prep->joined_refine)
    prep->joined_refine = joinedRefineModel(joined(), kJoinedRefineViews * points);
  if (!model->joined_views.empty())
    joined(); // the whole part, for the views' merge (Recognizer::partScorer)
  if (sampling > 0 && (!prep->pairs || prep->surface_sampling_mm != sampling)) {
    prep->pairs = std::make_shared<const PointPairModel>(
        sampleOriented(prep->verify->points, prep->verify->normals, sampling), sampling);
    prep->surface_sampling_mm = sampling;
  }
  if (symmetry_key && prep->symmetry_key != symmetry_key) {
    findSymmetries(*prep, *model, params, tolerance);
    prep->symmetry_key = symmetry_key;
  }
  constexpr std::size_t kKeptModels = 8;
  if (preps.size() >= kKeptModels)
    preps.erase(preps.begin());
  preps.push_back(prep);
  return prep;
}

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
