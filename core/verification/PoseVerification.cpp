#include "core/verification/PoseVerification.h"

#include "core/model/AutoParams.h"
#include "core/verification/SelfOcclusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scanpick::core {
namespace {

/// Verification never expects fewer than this share of the model's points to be seen, however
/// many are hidden: a pose confirmed on one leg of a bracket whose other leg falls behind other
/// parts must not score as a whole part.
constexpr double kMinExpectedShare = 0.75;

/// A tally with a stop asks it after this many points and every as many more.
constexpr std::size_t kStopCheckPoints = 16;

/// cos 65°: a model seen from every side expects the points that face the camera more squarely.
constexpr float kMinAllAroundFacing = 0.42f;

/// cos 60°: model and scene normals closer than this agree.
constexpr float kMinNormalAgreement = 0.5f;

/// Share of the model's keypoints lying on confirmed scene surface that also have a scene keypoint
/// within the edge tolerance (1 when off or when fewer than 10 lie on surface).
double edgeAgreement(const VerifyModel& model, const SceneIndex& index, const Eigen::Isometry3f& T,
                     double tolerance_mm, const EdgeCheck& edges) {
  // A model seen from every side was not scanned as the scene is: its keypoints are not the edges
  // a scan shows (silhouettes and jump edges depend on the view), so they cannot be compared.
  if (!edges.scene_keypoints || edges.tolerance_mm <= 0 || model.all_around)
    return 1.0;
  const auto surface_tol_sq = static_cast<float>(tolerance_mm * tolerance_mm);
  const auto edge_tol_sq = static_cast<float>(edges.tolerance_mm * edges.tolerance_mm);
  std::size_t on_surface = 0, on_edge = 0;
  for (const auto& k : model.keypoints) {
    const Eigen::Vector3f p = T * k;
    if (index.nearest(p, 4.0f * surface_tol_sq) < 0)
      continue;
    ++on_surface;
    if (edges.scene_keypoints->nearest(p, edge_tol_sq) >= 0)
      ++on_edge;
  }
  return on_surface < 10 ? 1.0 : double(on_edge) / double(on_surface);
}

/// The point of organized `scan` (of `sensor`'s size) at the pixel `p` projects to; null outside
/// the image.
const Eigen::Vector3f* scanPointAt(const PointCloud& scan, const SensorModel& sensor,
                                   const Eigen::Vector3f& p) {
  const auto pixel = sensor.pixelOf(p);
  if (!pixel || !sensor.inImage(*pixel))
    return nullptr;
  return &scan.points_mm[sensor.pixelIndex(*pixel)];
}

/// Whether organized `scan` (of `sensor`'s size) sees clearly behind `p`, more than `margin_mm`:
/// a line of sight that passes `p` from the far side of a part seen from every side would have
/// passed through the part.
bool seenBehind(const PointCloud& scan, const SensorModel& sensor, const Eigen::Vector3f& p,
                float margin_mm) {
  const Eigen::Vector3f* s = scanPointAt(scan, sensor, p);
  return s && isValid(*s) && s->z() > p.z() + margin_mm;
}

/// The points a tally's pose could show the camera: those not shadowed and, of a model seen from
/// every side, neither turned away nor behind its own body (its far side and its recesses are no
/// part of what one scan shows).
double seeablePoints(const PointTally& t, bool all_around) {
  return double(t.points) - double(t.shadowed) - double(t.self_hidden) -
         (all_around ? double(t.turned_away) : 0.0);
}

} // namespace

ProjectorShadow::ProjectorShadow(const PointCloud& scan, const SensorModel& sensor)
    : m_T_projector_scene(sensor.T_camera_projector.inverse().cast<float>()), m_sensor(sensor),
      m_depth_mm(std::size_t(std::max(0, sensor.width * sensor.height)),
                 std::numeric_limits<float>::infinity()) {
  for (const auto& s : scan.points_mm) {
    if (!isValid(s))
      continue;
    const auto pixel = projectorPixel(s);
    if (pixel && m_sensor.inImage(pixel->first)) {
      float& depth = m_depth_mm[m_sensor.pixelIndex(pixel->first)];
      depth = std::min(depth, pixel->second);
    }
  }
}

std::optional<std::pair<Eigen::Vector2i, float>>
ProjectorShadow::projectorPixel(const Eigen::Vector3f& p) const {
  const Eigen::Vector3f q = m_T_projector_scene * p;
  const auto pixel = m_sensor.pixelOf(q);
  if (!pixel)
    return std::nullopt;
  return std::pair{*pixel, q.z()};
}

bool ProjectorShadow::shadowed(const Eigen::Vector3f& p, float margin_mm) const {
  const auto pixel = projectorPixel(p);
  if (!pixel)
    return false;
  // Within a pixel: measured points fall between the projector pixels' centres.
  for (int v = pixel->first.y() - 1; v <= pixel->first.y() + 1; ++v)
    for (int u = pixel->first.x() - 1; u <= pixel->first.x() + 1; ++u)
      if (m_sensor.inImage({u, v}) &&
          m_depth_mm[m_sensor.pixelIndex({u, v})] < pixel->second - margin_mm)
        return true;
  return false;
}

std::shared_ptr<const SceneIndex> modelSurface(const TaughtModel& model, double normal_radius_mm) {
  SceneIndexOptions model_options;
  model_options.normal_radius_mm = normal_radius_mm;
  model_options.viewpoint_mm = model.T_teach_model.inverse().translation();
  // A part seen from every side keeps its normals, which face out of it.
  model_options.orient_cloud_normals = !model.all_around;
  return std::make_shared<const SceneIndex>(model.cloud_mm, model_options);
}

std::shared_ptr<const VerifyModel> makeVerifyModel(const TaughtModel& model, int points,
                                                   double normal_radius_mm) {
  return makeVerifyModel(model, *modelSurface(model, normal_radius_mm), points);
}

std::size_t verifyModelStride(std::size_t valid_points, int points) {
  const auto wanted = static_cast<std::size_t>(std::max(1, points));
  return std::max<std::size_t>(1, (valid_points + wanted - 1) / wanted);
}

std::shared_ptr<const VerifyModel> makeVerifyModel(const TaughtModel& model,
                                                   const SceneIndex& model_index, int points) {
  const auto& valid = model_index.points();
  const std::size_t stride = verifyModelStride(valid.size(), points);
  auto strided = std::make_shared<VerifyModel>();
  for (std::size_t i = 0; i < valid.size(); i += stride) {
    strided->points.push_back(valid[i]);
    strided->normals.push_back(model_index.normals()[i]);
  }
  strided->all_around = model.all_around;
  if (model.all_around)
    strided->spacing_mm =
        measureScan(PointCloud::fromPoints(std::vector(strided->points))).spacing_mm;
  const std::size_t key_stride = std::max<std::size_t>(1, (model.keypoints_mm.size() + 399) / 400);
  for (std::size_t i = 0; i < model.keypoints_mm.size(); i += key_stride)
    strided->keypoints.push_back(model.keypoints_mm[i]);
  return strided;
}

PointTally tallyPoints(const VerifyModel& model, const VerifyScene& scene,
                       const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                       const TallyOptions& options) {
  const SceneIndex& index = *scene.index;
  const PointCloud& scan = *scene.scan;
  const SensorModel& sensor = *scene.sensor;
  const bool organized = scan.height > 1 && static_cast<int>(scan.width) == sensor.width &&
                         static_cast<int>(scan.height) == sensor.height && sensor.fx > 0;
  const Eigen::Isometry3f T = T_scene_model.cast<float>();
  const auto tol_sq = static_cast<float>(tolerance_mm * tolerance_mm);
  const auto margin = static_cast<float>(3.0 * tolerance_mm);
  const float facing_cosine = model.all_around ? kMinAllAroundFacing : 0.0f;
  // The camera and the projector in the model frame, for the model's own body.
  const Eigen::Isometry3f T_model_scene = T.inverse();
  const Eigen::Vector3f camera_model = T_model_scene.translation();
  const Eigen::Vector3f projector_model = T_model_scene * sensor.projectorPosition().cast<float>();
  const std::vector<char> self_hidden = model.all_around
                                            ? selfHidden(model.points, T, model.spacing_mm, margin)
                                            : std::vector<char>{};
  PointTally tally;
  const auto look = [&](std::size_t k) {
    ++tally.points;
    const Eigen::Vector3f p = T * model.points[k];
    const Eigen::Vector3f& n_model = model.normals[k];
    // The camera sits at the scene origin. Of a model seen from every side, points the camera
    // sees at a grazing angle count as turned away too: a scan samples them too sparsely to
    // confirm the model's dense samples.
    const bool turned_away =
        n_model.allFinite() && (T.linear() * n_model).dot(-p) <= facing_cosine * p.norm();
    tally.turned_away += turned_away;
    const bool below_floor =
        scene.floor_plane &&
        scene.floor_plane->head<3>().dot(p) + (*scene.floor_plane)(3) < -margin;
    if (turned_away && model.all_around) { // the far side of a part seen from every side
      ++(below_floor || (organized && seenBehind(scan, sensor, p, margin)) ? tally.violations
                                                                           : tally.hidden);
      return;
    }
    if (below_floor) {
      ++tally.violations;
      return;
    }
    if (!self_hidden.empty() && self_hidden[k]) {
      ++tally.self_hidden;
      return;
    }
    const std::int64_t near = turned_away ? -1 : index.nearest(p, tol_sq);
    if (near >= 0) {
      // A surface confirms a point only when it faces the same way: the far face of a thin plate
      // lies within tolerance of the near one's points but turned away.
      const Eigen::Vector3f& n_scene = index.normals()[static_cast<std::size_t>(near)];
      if (!n_scene.allFinite() || !n_model.allFinite() ||
          (T.linear() * n_model).dot(n_scene) > kMinNormalAgreement) {
        ++tally.confirmed;
        return;
      }
    }
    const Eigen::Vector3f* s = turned_away || !organized ? nullptr : scanPointAt(scan, sensor, p);
    if (turned_away || !s) {
      tally.hidden += turned_away;
      return;
    }
    if (!isValid(*s)) {
      if (!options.sort_unmeasured)
        return;
      if (model.body && model.body->blocks(model.points[k], camera_model))
        ++tally.hidden;
      else if ((scene.shadow && scene.shadow->shadowed(p, margin)) ||
               (model.body && model.body->blocks(model.points[k], projector_model)))
        ++tally.shadowed;
      return;
    }
    if (s->z() > p.z() + margin)
      ++tally.violations;
    else if (s->z() < p.z() - margin)
      ++tally.hidden;
  };
  const std::size_t total = options.subset ? options.subset->size() : model.points.size();
  for (std::size_t j = 0; j < total; ++j) {
    look(options.subset ? std::size_t{(*options.subset)[j]} : j);
    if (options.stop && (j + 1) % kStopCheckPoints == 0 && j + 1 < total &&
        options.stop(tally, total - j - 1))
      break;
  }
  return tally;
}

double surfaceScoreBound(const PointTally& tally, std::size_t left, bool all_around) {
  // Each point left can add one confirmation, or else be shadowed (or, of a model seen from
  // every side, turned away) and lower the expected count; with fewer confirmations than points
  // not shadowed, confirming all of them scores highest.
  const double seeable = seeablePoints(tally, all_around) + double(left);
  if (seeable <= 0.0)
    return 1.0;
  return std::clamp((double(tally.confirmed) - double(tally.violations) + double(left)) /
                        (kMinExpectedShare * seeable),
                    0.0, 1.0);
}

PointCloud edgeKeypointCloud(const std::vector<Keypoints>& keypoints, const SensorModel& sensor) {
  std::vector<Eigen::Vector3f> points;
  for (const auto& k : keypoints)
    points.insert(points.end(), k.points_mm.begin(), k.points_mm.end());
  PointCloud list = PointCloud::fromPoints(std::move(points));
  if (sensor.width <= 0 || sensor.height <= 0 || !(sensor.fx > 0) || !(sensor.fy > 0))
    return list;
  PointCloud image;
  image.width = static_cast<std::uint32_t>(sensor.width);
  image.height = static_cast<std::uint32_t>(sensor.height);
  image.points_mm.assign(std::size_t(image.width) * image.height, invalidPoint());
  for (const auto& p : list.points_mm) {
    const auto at = sensor.pixelOf(p);
    if (!at || !sensor.inImage(*at))
      return list;
    Eigen::Vector3f& pixel = image.points_mm[sensor.pixelIndex(*at)];
    if (isValid(pixel) && pixel != p)
      return list;
    pixel = p;
  }
  return image;
}

double wholePartScore(const VerifyModel& part, const VerifyScene& scene,
                      const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                      const std::vector<std::uint32_t>* subset) {
  const PointTally t = tallyPoints(part, scene, T_scene_model, tolerance_mm,
                                   {.subset = subset, .stop = {}, .sort_unmeasured = true});
  const double expected =
      double(t.points) - double(t.hidden) - double(t.shadowed) - double(t.self_hidden);
  return expected > 0 ? (double(t.confirmed) - double(t.violations)) / expected : 0.0;
}

std::vector<std::uint32_t> evenSubset(std::size_t count, std::size_t target) {
  const std::size_t stride = std::max<std::size_t>(1, count / std::max<std::size_t>(1, target));
  std::vector<std::uint32_t> every;
  for (std::size_t k = 0; k < count; k += stride)
    every.push_back(static_cast<std::uint32_t>(k));
  return every;
}

double verifyPose(const VerifyModel& model, const VerifyScene& scene,
                  const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                  const EdgeCheck& edges, double drop_below) {
  if (model.points.empty())
    return 0.0;
  const auto cannot_reach = [&](const PointTally& so_far, std::size_t left) {
    return surfaceScoreBound(so_far, left, model.all_around) < drop_below;
  };
  const PointTally t = tallyPoints(model, scene, T_scene_model, tolerance_mm,
                                   {.subset = nullptr,
                                    .stop = drop_below > 0 ? TallyStop(cannot_reach) : TallyStop(),
                                    .sort_unmeasured = true});
  if (const std::size_t left = model.points.size() - t.points; left > 0)
    return surfaceScoreBound(t, left, model.all_around); // stopped: under drop_below
  const double seeable = seeablePoints(t, model.all_around);
  const double occluded = double(t.hidden) - (model.all_around ? double(t.turned_away) : 0.0);
  const double expected = std::max(seeable - occluded, kMinExpectedShare * seeable);
  if (expected <= 0.0)
    return 0.0;
  const double surface =
      std::clamp((double(t.confirmed) - double(t.violations)) / expected, 0.0, 1.0);
  if (surface < drop_below)
    return surface; // the edge agreement (at most 1) could only lower it
  return surface *
         edgeAgreement(model, *scene.index, T_scene_model.cast<float>(), tolerance_mm, edges);
}

} // namespace scanpick::core
