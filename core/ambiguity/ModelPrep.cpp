#include "core/ambiguity/ModelPrep.h"

#include "core/common/Log.h"
#include "core/features/FeatureExtraction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace scanpick::core::detail {
namespace {

/// fitRevolutionAxis's angle tolerance (10°). A view whose normals fit an axis this share or more
/// (but fewer than fitRevolutionAxis's default 98 %) is a surface of revolution but for an
/// asymmetric feature: the cup's side views fit 93-96 %, the support's and the coat-rack's views
/// far less.
constexpr double kRevolutionTolerance = 0.17;
constexpr double kNearRevolutionShare = 0.85;
/// Cells (height along and distance from the axis) in which detailPoints compares angles to find
/// the asymmetric points: 2-3 mm cells split a cup's revolved surface (its points scatter by the
/// fit's residual), 6 mm ones keep it whole.
constexpr double kAsymmetryCellMm = 6.0;
/// Cell of a view's revolved surface (RevolvedBody), mm: about the spacing of its verification
/// points.
constexpr double kRevolvedSurfaceCellMm = 2.0;
/// A view is a surface of revolution but for an asymmetric feature only while that feature is at
/// most this share of its points (a cup's handle: 5-13 %). A flat face seen along its normal fits
/// a rim axis through any circle among its points, and then no cell of it is rotationally
/// symmetric: all of it is "asymmetric".
constexpr double kMaxAsymmetryShare = 0.5;

/// Whether `S` (model frame) is a rotation about `axis`: its rotation axis within 10° of the axis
/// direction, and the axis point staying within 2 mm.
bool isRotationAbout(const RevolutionAxis& axis, const Eigen::Isometry3d& S) {
  const Eigen::AngleAxisd rotation(S.linear());
  return std::abs(rotation.axis().dot(axis.direction)) > std::cos(10.0 * M_PI / 180.0) &&
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

/// At most about this many points make a joined asymmetric feature (the cup's views' own hold
/// 92–222): its rotation search then costs about what the view's own does.
constexpr std::size_t kJoinedAsymmetryPoints = 250;
/// At most about this many points make a joined revolved surface (its differing points under a
/// cup's flip end over end, about a quarter of them, are tallied at 25 places along the axis per
/// detection).
constexpr std::size_t kJoinedSurfacePoints = 2000;
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

/// The points of `all` listed in `indices`, every `stride`-th, with `revolved` (the revolved
/// surface verification follows rays through).
std::shared_ptr<VerifyModel> pick(const VerifyModel& all, const std::vector<std::uint32_t>& indices,
                                  std::size_t stride,
                                  std::shared_ptr<const RevolvedBody> revolved) {
  auto picked = std::make_shared<VerifyModel>();
  for (std::size_t k = 0; k < indices.size(); k += std::max<std::size_t>(1, stride)) {
    picked->points.push_back(all.points[indices[k]]);
    picked->normals.push_back(all.normals[indices[k]]);
  }
  picked->body = std::move(revolved);
  return picked;
}

/// The joined views' asymmetric feature (a cup's handle from every side) and revolved surface
/// (its mouth and its bottom), from `all` (joinedPoints): the points off the surface the view
/// revolves about `axis` (detailPoints), strided to about kJoinedAsymmetryPoints, with the view's
/// revolved surface; and the others, with the revolved surface they make.
std::pair<std::shared_ptr<const VerifyModel>, std::shared_ptr<const VerifyModel>>
joinedAsymmetryAndSurface(const VerifyModel& all, const VerifyModel& view,
                          const RevolutionAxis& axis) {
  const auto asymmetry = detailPoints(all.points, axis, kAsymmetryCellMm);
  std::vector<bool> in_asymmetry(all.points.size(), false);
  for (const std::uint32_t i : asymmetry)
    in_asymmetry[i] = true;
  std::vector<std::uint32_t> surface;
  for (std::uint32_t i = 0; i < all.points.size(); ++i)
    if (!in_asymmetry[i])
      surface.push_back(i);
  const std::size_t asymmetry_stride =
      (asymmetry.size() + kJoinedAsymmetryPoints - 1) / kJoinedAsymmetryPoints;
  const std::size_t surface_stride =
      (surface.size() + kJoinedSurfacePoints - 1) / kJoinedSurfacePoints;
  return {pick(all, asymmetry, asymmetry_stride, view.body),
          pick(all, surface, surface_stride,
               std::make_shared<const RevolvedBody>(all.points, axis, kRevolvedSurfaceCellMm,
                                                    asymmetry))};
}

/// The outer radius of the surface `prep`'s view revolves about its axis (its asymmetric feature
/// left out) and where its wall ends in the taught cloud (`surface`: its points with their
/// normals), seen from the teach camera.
void findWallEnds(ModelPrep& prep, const SceneIndex& surface_points) {
  const RevolutionAxis& axis = prep.axis ? *prep.axis : *prep.near_axis;
  std::vector<bool> in_asymmetry(prep.verify->points.size(), false);
  for (const std::uint32_t i : prep.near_axis_asymmetry)
    in_asymmetry[i] = true;
  std::vector<Eigen::Vector3f> surface;
  for (std::size_t i = 0; i < prep.verify->points.size(); ++i)
    if (!in_asymmetry[i])
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

/// The points of `surface` that `S` (model frame → model frame) moves out of its revolved
/// surface's cells.
std::vector<std::uint32_t> movedOffSurface(const VerifyModel& surface, const Eigen::Isometry3d& S) {
  const Eigen::Isometry3f S_f = S.cast<float>();
  std::vector<std::uint32_t> off;
  for (std::uint32_t k = 0; k < surface.points.size(); ++k)
    if (!surface.body->contains(S_f * surface.points[k]))
      off.push_back(k);
  return off;
}

/// The view's axis: a surface of revolution (ModelPrep::axis), or one but for an asymmetric
/// feature (ModelPrep::near_axis and its asymmetric points); then the surface its points make
/// revolved about it and the ends of its wall. `surface`: the view's points with their normals.
void fitAxes(ModelPrep& prep, const TaughtModel& model, const SceneIndex& surface) {
  prep.axis = fitRevolutionAxis(prep.verify->points, prep.verify->normals);
  if (prep.axis)
    prep.axis = refineRevolutionAxis(prep.verify->points, prep.verify->normals, *prep.axis);
  if (prep.axis)
    logger()->debug("model '{}' is a surface of revolution ({:.0f} % of its normals), its "
                    "rotation is not seen: axis through ({:.1f}, {:.1f}, {:.1f}) mm along ({:.3f}, "
                    "{:.3f}, {:.3f})",
                    model.name, 100.0 * prep.axis->inlier_share, prep.axis->point_mm.x(),
                    prep.axis->point_mm.y(), prep.axis->point_mm.z(), prep.axis->direction.x(),
                    prep.axis->direction.y(), prep.axis->direction.z());
  else if (auto near = fitRevolutionAxis(prep.verify->points, prep.verify->normals,
                                         kRevolutionTolerance, kNearRevolutionShare);
           near || (near = rimAxis(prep.verify->points, prep.verify->normals))) {
    // The axis is refined on the surface without the asymmetric feature, which is then found
    // again.
    auto asymmetry = detailPoints(prep.verify->points, *near, kAsymmetryCellMm);
    near = refineRevolutionAxis(prep.verify->points, prep.verify->normals, *near, asymmetry);
    asymmetry = detailPoints(prep.verify->points, *near, kAsymmetryCellMm);
    const std::size_t count = prep.verify->points.size();
    if (double(asymmetry.size()) <= kMaxAsymmetryShare * double(count)) {
      prep.near_axis = near;
      prep.near_axis_asymmetry = std::move(asymmetry);
      logger()->debug("model '{}' is a surface of revolution but for an asymmetric feature "
                      "({:.0f} % of its normals; {} of its {} points off the surface): its "
                      "rotation is seen only where a scan confirms the asymmetric feature",
                      model.name, 100.0 * near->inlier_share, prep.near_axis_asymmetry.size(),
                      count);
    } else {
      logger()->debug("model '{}' fits an axis with {:.0f} % of its normals, but {} of its {} "
                      "points lie off the surface they revolve: not a surface of revolution",
                      model.name, 100.0 * near->inlier_share, asymmetry.size(), count);
    }
  }
  if (prep.axis || prep.near_axis) {
    auto verify = std::make_shared<VerifyModel>(*prep.verify);
    verify->body = std::make_shared<const RevolvedBody>(
        verify->points, prep.axis ? *prep.axis : *prep.near_axis, kRevolvedSurfaceCellMm,
        prep.near_axis_asymmetry);
    prep.verify = std::move(verify);
    findWallEnds(prep, surface);
  }
}

/// The view's near symmetries (findNearSymmetries) less the rotations about its axis, and what
/// each moves off the joined revolved surface.
void findSymmetries(ModelPrep& prep, const TaughtModel& model, const RecognitionParams& params,
                    double tolerance_mm) {
  prep.symmetries = findNearSymmetries(model, *prep.verify, *prep.refine, params.refine,
                                       tolerance_mm, params.matching.symmetry_overlap);
  // A surface of revolution reports its rotation about the axis as free instead, and one but for
  // an asymmetric feature as seen or free by that feature (seesAsymmetry); their other near
  // symmetries (a cup or a pipe flipped end over end) stay.
  if (prep.axis || prep.near_axis) {
    const RevolutionAxis& axis = prep.axis ? *prep.axis : *prep.near_axis;
    const auto rotations = std::erase_if(
        prep.symmetries, [&](const NearSymmetry& s) { return isRotationAbout(axis, s.S_model); });
    logger()->debug("model '{}': {} near symmetries are rotations about its axis, {} others",
                    model.name, rotations, prep.symmetries.size());
  }
  prep.joined_revolved_surface_differing.clear();
  if (prep.joined_revolved_surface)
    for (const NearSymmetry& s : prep.symmetries) {
      const VerifyModel& surface = *prep.joined_revolved_surface;
      prep.joined_revolved_surface_differing.push_back(
          {movedOffSurface(surface, s.S_model), movedOffSurface(surface, s.S_model.inverse())});
      logger()->debug("model '{}': a near symmetry moves {} / {} of the joined revolved "
                      "surface's {} points off it",
                      model.name, prep.joined_revolved_surface_differing.back().differing.size(),
                      prep.joined_revolved_surface_differing.back().differing_inverse.size(),
                      surface.points.size());
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
  // ICP needs the model prepared: for refinement, to refine surface voting's poses, and to fit
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
    if (!prep->joined_points) {
      prep->joined_points =
          std::make_shared<const VerifyModel>(joinedPoints(*model, *prep->verify, points, radius));
      prep->joined_sample = evenSubset(prep->joined_points->points.size(), kJoinedSamplePoints);
    }
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
      std::tie(prep->joined_asymmetry, prep->joined_revolved_surface) =
          joinedAsymmetryAndSurface(joined(), *prep->verify, *prep->near_axis);
      logger()->debug("model '{}': its asymmetric feature holds {} points with {} views joined "
                      "({} alone), its revolved surface {}",
                      model->name, prep->joined_asymmetry->points.size(),
                      model->joined_views.size(), prep->near_axis_asymmetry.size(),
                      prep->joined_revolved_surface->points.size());
    }
  }
  // Refinement's surface is verification's when their normals agree (the same radius and
  // teach camera): estimated once.
  if (needs_refine && !prep->refine)
    prep->refine = surface && radius == RefineModel::kNormalRadiusMm
                       ? std::make_shared<const RefineModel>(surface, points)
                       : std::make_shared<const RefineModel>(
                             modelSurface(*model, RefineModel::kNormalRadiusMm), points);
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

} // namespace scanpick::core::detail
