// Whether a scan's depth image pins a pose that point-to-plane ICP leaves loose, and how near a
// render-and-compare step with the taught model comes to that (docs/design-notes-refinement.md,
// "Render and compare: studied, not built"). Every instance of PART at least 50 % visible is
// refined from its true pose as study_icp_from_truth does; the pose ICP settles at is then moved,
// translation only, along three directions (coordinate descent, two rounds; the oracle takes the
// least cost by 0.1 mm then by 0.02 mm, the others the middle of the run of least costs by 0.05 mm
// within ±0.8 mm) to where a rendering differs least from the scan:
//
//   study_render_pin SUITE_DIR PART PRESET.json TOLERANCE_MM MODE MODEL.spmodel [MODEL ...]
//
// MODE "oracle": the whole scene rendered from its ground truth with the instance moved (other
// instances, bin, projector shadows), compared pixel by pixel with the scan over a window around
// the instance: how far the depth image itself tells the pose. Otherwise the part alone is rendered
// and compared (mismatch() below, what recognition could do): MODE "mesh" renders the part's true
// mesh, a number renders the taught views' points as discs of that many times half the distance
// from each point to its fourth nearest neighbour (at most 1 mm). Directions: the part's own axes
// with PART_AXES=1 (from the truth), the directions point-to-plane ICP hardly pins with WEAK=SHARE
// (eigenvectors of Σ n nᵀ of the model points facing the camera below SHARE of the largest
// eigenvalue; only those are searched), else the principal axes of the model's points.
// OWN_VIEW=1 renders each view's own points only, not those of the views joined to it.
// PRINT_CURVES=1 prints the cost along each direction. Not a test: run it by hand and write the
// figures in the docs.
#include "FromTruthStudy.h"
#include "core/cloud/CloudIo.h"
#include "core/cloud/PointKdTree.h"
#include "core/eval/RenderCheck.h"
#include "core/sim/EmbreeMesh.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/Renderer.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <embree3/rtcore.h>
#include <exception>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace scanpick::core;
using namespace scanpick::study;

namespace {

/// The pixel rectangle [u0, u1) × [v0, v1) of the scan compared.
struct Window {
  int u0 = 0, v0 = 0, u1 = 0, v1 = 0;
};

constexpr float kMaxDiscRadiusMm = 1.0f;

/// The part in the model frame for ray casting (Embree): the taught views' points as oriented discs
/// (each `radius_factor` times half the distance to its fourth nearest neighbour in its own view),
/// or the true mesh; and points on it (for its principal axes).
class SplatModel {
public:
  /// `views`: each view's points in the model frame and its teach camera there.
  SplatModel(const std::vector<std::pair<const PointCloud*, Eigen::Vector3d>>& views,
             double radius_factor, double normal_radius_mm)
      : m_device(rtcNewDevice(nullptr)), m_scene(rtcNewScene(m_device)) {
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
    std::vector<float> discs, normals;
    for (const auto& [view, camera] : views) {
      SceneIndexOptions options;
      options.normal_radius_mm = normal_radius_mm;
      options.viewpoint_mm = camera;
      const SceneIndex index(*view, options);
      std::vector<Eigen::Vector3f> points;
      std::vector<Eigen::Vector3f> n;
      for (std::size_t i = 0; i < index.points().size(); ++i)
        if (isValid(index.points()[i]) && index.normals()[i].allFinite()) {
          points.push_back(index.points()[i]);
          n.push_back(index.normals()[i]);
        }
      const PointVectorSource source{&points};
      PointKdTree tree(3, source);
      tree.buildIndex();
      for (std::size_t i = 0; i < points.size(); ++i) {
        std::uint32_t idx[5];
        float d2[5];
        const std::size_t found = tree.knnSearch(points[i].data(), 5, idx, d2);
        const float radius = std::min(kMaxDiscRadiusMm, static_cast<float>(radius_factor) * 0.5f *
                                                            std::sqrt(d2[found - 1]));
        discs.insert(discs.end(), {points[i].x(), points[i].y(), points[i].z(), radius});
        normals.insert(normals.end(), {n[i].x(), n[i].y(), n[i].z()});
        points_all.push_back(points[i]);
        normals_all.push_back(n[i]);
      }
    }
    RTCGeometry g = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT);
    const std::size_t count = discs.size() / 4;
    std::copy(discs.begin(), discs.end(),
              static_cast<float*>(rtcSetNewGeometryBuffer(
                  g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), count)));
    std::copy(normals.begin(), normals.end(),
              static_cast<float*>(rtcSetNewGeometryBuffer(
                  g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), count)));
    rtcCommitGeometry(g);
    rtcAttachGeometry(m_scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(m_scene);
  }
  /// The true part's mesh in the model frame (an ideal model): rendered as triangles, and sampled
  /// every ~0.3 mm.
  explicit SplatModel(const TriangleMesh& mesh_model_mm)
      : m_device(rtcNewDevice(nullptr)), m_scene(rtcNewScene(m_device)) {
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
    attachTriangleMesh(m_device, m_scene, mesh_model_mm);
    rtcCommitScene(m_scene);
    for (const auto& t : mesh_model_mm.triangles) {
      const Eigen::Vector3d a = mesh_model_mm.vertices_mm[static_cast<std::size_t>(t[0])];
      const Eigen::Vector3d b = mesh_model_mm.vertices_mm[static_cast<std::size_t>(t[1])];
      const Eigen::Vector3d c = mesh_model_mm.vertices_mm[static_cast<std::size_t>(t[2])];
      const int n =
          1 + static_cast<int>(std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / 0.3);
      for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j)
          points_all.push_back((a + (b - a) * i / n + (c - a) * j / n).cast<float>());
    }
  }
  ~SplatModel() {
    rtcReleaseScene(m_scene);
    rtcReleaseDevice(m_device);
  }
  SplatModel(const SplatModel&) = delete;
  SplatModel& operator=(const SplatModel&) = delete;

  /// True when the segment from `from` towards `to` (model frame), past its first `skip_mm`, meets
  /// the model.
  [[nodiscard]] bool blocks(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                            double skip_mm) const {
    RTCRay ray = rayAlong(from, (to - from).normalized(), static_cast<float>(skip_mm),
                          static_cast<float>((to - from).norm()));
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(m_scene, &context, &ray);
    return ray.tfar < 0.0f; // Embree sets tfar to -inf on a hit
  }
  /// Depth (z, mm) of the model at pose T_scene_model seen by `sensor` at pixel (u, v); NaN: none.
  [[nodiscard]] float depth(const Eigen::Isometry3d& T_model_scene, const SensorModel& sensor,
                            int u, int v) const {
    // The camera ray in the model frame; its direction has z = 1 in the camera frame, so the hit's
    // distance along it is the depth.
    const Eigen::Vector3d d((u - sensor.cx) / sensor.fx, (v - sensor.cy) / sensor.fy, 1.0);
    RTCRayHit rh{};
    rh.ray = rayAlong(T_model_scene.translation(), T_model_scene.linear() * d, 0.0f,
                      std::numeric_limits<float>::infinity());
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(m_scene, &context, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::quiet_NaN()
                                                    : rh.ray.tfar;
  }
  std::vector<Eigen::Vector3f> points_all;
  std::vector<Eigen::Vector3f> normals_all; ///< with discs only

  /// The translations point-to-plane ICP hardly pins at T_scene_model: eigenvectors (scene frame)
  /// of Σ n nᵀ over the points facing the camera whose eigenvalue is below `share` of the largest.
  [[nodiscard]] std::vector<Eigen::Vector3d> weakDirections(const Eigen::Isometry3d& T_scene_model,
                                                            double share) const {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < normals_all.size(); ++i) {
      const Eigen::Vector3d p = T_scene_model * points_all[i].cast<double>();
      const Eigen::Vector3d n = T_scene_model.linear() * normals_all[i].cast<double>();
      if (n.dot(-p) > 0)
        m += n * n.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
    std::vector<Eigen::Vector3d> out;
    for (int k = 0; k < 3; ++k)
      if (eig.eigenvalues()[k] < share * eig.eigenvalues()[2])
        out.push_back(eig.eigenvectors().col(k));
    return out;
  }

private:
  static RTCRay rayAlong(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         float tnear, float tfar) {
    RTCRay ray{};
    ray.org_x = static_cast<float>(origin.x());
    ray.org_y = static_cast<float>(origin.y());
    ray.org_z = static_cast<float>(origin.z());
    ray.dir_x = static_cast<float>(direction.x());
    ray.dir_y = static_cast<float>(direction.y());
    ray.dir_z = static_cast<float>(direction.z());
    ray.tnear = tnear;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    return ray;
  }

  RTCDevice m_device;
  RTCScene m_scene;
};

/// How badly the part alone at T_scene_model explains the scan over `window`: each pixel where the
/// part is seen and the scan has a point adds min(|Δz| / tolerance, 1)² − 1 (a point on the part
/// lowers the cost by up to 1), each where the scan has none though the projector lights the part
/// there adds 1. Pixels where the part is not seen add nothing, whatever the scan shows there (a
/// model drawn a little too wide costs nothing over the floor).
double mismatch(const SplatModel& model, const Eigen::Isometry3d& T_scene_model,
                const SensorModel& sensor, const PointCloud& scan, const Window& window,
                double tolerance_mm) {
  const Eigen::Isometry3d T_model_scene = T_scene_model.inverse();
  const Eigen::Vector3d projector_model = T_model_scene * sensor.projectorPosition();
  double cost = 0.0;
  for (int v = window.v0; v < window.v1; ++v)
    for (int u = window.u0; u < window.u1; ++u) {
      const Eigen::Vector3f& s = scan.points_mm[static_cast<std::size_t>(v * scan.width + u)];
      const float z = model.depth(T_model_scene, sensor, u, v);
      if (std::isnan(z))
        continue; // not the part's pixel: whatever the scan shows there, the part does not say
      if (isValid(s)) {
        const double d = std::min(1.0, std::abs(s.z() - z) / tolerance_mm);
        cost += d * d - 1.0; // a scan point on the part lowers the cost by up to 1
        continue;
      }
      // The scan has no point where the part is seen: right where the part shadows itself from
      // the projector, wrong where the projector lights it.
      const Eigen::Vector3d on_model =
          T_model_scene *
          Eigen::Vector3d(z * (u - sensor.cx) / sensor.fx, z * (v - sensor.cy) / sensor.fy, z);
      if (!model.blocks(on_model, projector_model, tolerance_mm))
        cost += 1.0;
    }
  return cost;
}

/// The truth's scene with instance `label` at `T_scene_part`.
Scene movedScene(const eval::TruthRenderer& truth, std::size_t label,
                 const Eigen::Isometry3d& T_scene_part) {
  Scene moved = truth.scene();
  moved.instances[label].T_world_part = moved.T_camera_world.inverse() * T_scene_part;
  return moved;
}

/// Renders the truth's scene, instance `label` at `T_scene_part`, over `window` only, and returns
/// how much it differs from the scan there: per pixel min(|Δz| / tolerance, 1)², 1 where only one
/// of the two measures a point.
double difference(const eval::TruthRenderer& truth, std::size_t label,
                  const Eigen::Isometry3d& T_scene_part, const PointCloud& scan,
                  const Window& window, double tolerance_mm) {
  SensorModel sensor = truth.sensor();
  sensor.width = window.u1 - window.u0;
  sensor.height = window.v1 - window.v0;
  sensor.cx -= window.u0;
  sensor.cy -= window.v0;
  const RenderResult render =
      renderScene(movedScene(truth, label, T_scene_part), sensor, SensorNoise{}, 0);
  double cost = 0.0;
  for (int v = 0; v < sensor.height; ++v)
    for (int u = 0; u < sensor.width; ++u) {
      const Eigen::Vector3f& r =
          render.cloud.points_mm[static_cast<std::size_t>(v * sensor.width + u)];
      const Eigen::Vector3f& s =
          scan.points_mm[static_cast<std::size_t>((v + window.v0) * scan.width + u + window.u0)];
      if (isValid(r) != isValid(s))
        cost += 1.0;
      else if (isValid(r)) {
        const double d = std::min(1.0, std::abs(r.z() - s.z()) / tolerance_mm);
        cost += d * d;
      }
    }
  return cost;
}

/// The window around the pixels where instance `label` is seen at `T_scene_part`, `margin` wider.
Window windowAround(const eval::TruthRenderer& truth, std::size_t label,
                    const Eigen::Isometry3d& T_scene_part, int margin) {
  const SensorModel& sensor = truth.sensor();
  const RenderResult render =
      renderScene(movedScene(truth, label, T_scene_part), sensor, SensorNoise{}, 0);
  Window w{sensor.width, sensor.height, 0, 0};
  for (int v = 0; v < sensor.height; ++v)
    for (int u = 0; u < sensor.width; ++u)
      if (render.labels[static_cast<std::size_t>(v * sensor.width + u)] ==
          static_cast<std::int32_t>(label)) {
        w.u0 = std::min(w.u0, u);
        w.v0 = std::min(w.v0, v);
        w.u1 = std::max(w.u1, u + 1);
        w.v1 = std::max(w.v1, v + 1);
      }
  if (w.u1 <= w.u0)
    throw Error("the instance is not seen at the pose ICP settled at");
  return {std::max(0, w.u0 - margin), std::max(0, w.v0 - margin),
          std::min(sensor.width, w.u1 + margin), std::min(sensor.height, w.v1 + margin)};
}

/// The shift (mm) along one direction where `cost` is least in the middle of its run of least
/// costs: sampled every 0.05 mm within ±0.8 mm; the run is the samples next to the least cost
/// nearest 0 that lie within max(2, 3 % of it) of it; at the end of the range, that least cost.
template <class Cost> double leastCostRunMiddle(const Cost& cost_at, bool print) {
  std::vector<double> at, cost;
  for (int k = -16; k <= 16; ++k) {
    at.push_back(0.05 * k);
    cost.push_back(cost_at(at.back()));
  }
  const double least = *std::min_element(cost.begin(), cost.end());
  const double slack = std::max(2.0, 0.03 * least);
  std::size_t m = 16;
  for (std::size_t k = 0; k < cost.size(); ++k)
    if (cost[k] == least && (cost[m] != least || std::abs(at[k]) < std::abs(at[m])))
      m = k;
  std::size_t lo = m, hi = m;
  while (lo > 0 && cost[lo - 1] <= least + slack)
    --lo;
  while (hi + 1 < cost.size() && cost[hi + 1] <= least + slack)
    ++hi;
  const double shift = (lo == 0 || hi + 1 == cost.size()) ? at[m] : 0.5 * (at[lo] + at[hi]);
  if (print) {
    for (const double c : cost)
      std::printf(" %.0f", c);
    std::printf(" -> %.3f", shift);
  }
  return shift;
}

/// The shift (mm) with the least `cost`: within ±0.6 mm by 0.1 mm, then ±0.1 mm around it by
/// 0.02 mm; ties go to the smaller shift.
template <class Cost> double leastCostShift(const Cost& cost_at) {
  double step = 0.1, centre = 0.0;
  for (const int reach : {6, 5}) {
    double best_cost = std::numeric_limits<double>::infinity(), best_at = centre;
    for (int k = -reach; k <= reach; ++k) {
      const double at = centre + k * step;
      const double cost = cost_at(at);
      if (cost < best_cost || (cost == best_cost && std::abs(at) < std::abs(best_at))) {
        best_cost = cost;
        best_at = at;
      }
    }
    centre = best_at;
    step = 0.02;
  }
  return centre;
}

/// Eigenvectors of the points' covariance, smallest eigenvalue first.
Eigen::Matrix3d principalAxes(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points)
    mean += p.cast<double>();
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points)
    cov += (p.cast<double>() - mean) * (p.cast<double>() - mean).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors();
}

/// `T` moved by `shift_mm` along `direction` (scene frame).
Eigen::Isometry3d movedBy(Eigen::Isometry3d T, const Eigen::Vector3d& direction, double shift_mm) {
  T.pretranslate(shift_mm * direction);
  return T;
}

int run(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr,
                 "usage: %s SUITE_DIR PART PRESET.json TOLERANCE_MM oracle|RADIUS_FACTOR "
                 "MODEL.spmodel ...\n",
                 argv[0]);
    return 2;
  }
  const fs::path suite = argv[1];
  const std::string part = argv[2];
  RecognitionParams params = loadPreset(argv[3]).params;
  params.refine.enabled = true;
  const double tolerance_mm = std::stod(argv[4]);
  // MODE: "oracle" (the truth's meshes) or a disc radius factor for the taught model's points.
  const std::string mode = argv[5];
  const double splat_factor = mode == "oracle" ? 0.0 : mode == "mesh" ? 1.0 : std::stod(mode);
  const bool print_curves = std::getenv("PRINT_CURVES") != nullptr;
  const double weak_share = std::getenv("WEAK") ? std::atof(std::getenv("WEAK")) : 0.0;
  const bool part_axes = std::getenv("PART_AXES") != nullptr; // the true part's axes, not PCA
  const PreparedViews prepared = prepareViews({argv + 6, argv + argc}, params);
  const auto& views = prepared.views;
  std::vector<std::unique_ptr<SplatModel>> splats;
  std::vector<Eigen::Matrix3d> axes;
  if (splat_factor > 0)
    for (const auto& view : views) {
      if (mode == "mesh") {
        splats.push_back(std::make_unique<SplatModel>(
            transformed(builtInPart(part).mesh(), view->T_part_model->inverse())));
      } else {
        std::vector<std::pair<const PointCloud*, Eigen::Vector3d>> clouds{
            {&view->cloud_mm, view->T_teach_model.inverse().translation()}};
        if (!std::getenv("OWN_VIEW"))
          for (const auto& joined : view->joined_views)
            clouds.emplace_back(&joined.cloud_mm, joined.camera_mm);
        splats.push_back(
            std::make_unique<SplatModel>(clouds, splat_factor, params.keypoints.normal_radius_mm));
      }
      axes.push_back(principalAxes(splats.back()->points_all));
    }

  std::vector<double> icp_mm, pinned_mm;
  for (const auto& scene : sceneFiles(suite)) {
    const auto truth = truthOf(scene);
    bool wanted = false;
    for (const auto& instance : truth.instances)
      wanted = wanted || (instance.part == part && instance.visible_fraction >= 0.5);
    if (!wanted)
      continue;
    const PointCloud cloud = loadCloud(scene, LengthUnit::Millimetres).cloud;
    const SceneIndex index = sceneIndexFor(cloud, truth, params);
    const eval::TruthRenderer renderer(truth);
    for (const auto& instance : truth.instances) {
      if (instance.part != part || instance.visible_fraction < 0.5)
        continue;
      const std::size_t best = bestView(prepared, index, instance.T_scene_part, params);
      const Eigen::Isometry3d T_part_model = *views[best]->T_part_model;
      const Eigen::Isometry3d T_true = instance.T_scene_part * T_part_model;
      const RefinementResult r = refineFrom(prepared, best, index, T_true, params);
      // The part at ICP's pose, then moved along its own axes (scene frame) to the least
      // difference.
      Eigen::Isometry3d T_scene_part = r.T_scene_model * T_part_model.inverse();
      const auto label = static_cast<std::size_t>(
          std::find(renderer.truthIds().begin(), renderer.truthIds().end(), instance.id) -
          renderer.truthIds().begin());
      const Window window = windowAround(renderer, label, T_scene_part, 8);
      const auto originError = [&](const Eigen::Isometry3d& T) {
        return (T_true.inverse() * (T * T_part_model)).translation().norm();
      };
      const double before = originError(T_scene_part);
      if (splat_factor > 0) {
        const SplatModel& model = *splats[best];
        Eigen::Isometry3d T = r.T_scene_model;
        const std::vector<Eigen::Vector3d> weak =
            weak_share > 0 ? model.weakDirections(T, weak_share) : std::vector<Eigen::Vector3d>{};
        if (weak_share > 0)
          std::printf("  %zu weak directions\n", weak.size());
        const int directions = weak_share > 0 ? static_cast<int>(weak.size()) : 3;
        for (int round = 0; round < 2; ++round)
          for (int axis = 0; axis < directions; ++axis) {
            const Eigen::Vector3d d = weak_share > 0 ? weak[static_cast<std::size_t>(axis)]
                                      : part_axes
                                          ? Eigen::Vector3d(T_scene_part.linear().col(axis))
                                          : Eigen::Vector3d(T.linear() * axes[best].col(axis));
            if (print_curves)
              std::printf("  axis %d:", axis);
            const double shift = leastCostRunMiddle(
                [&](double at) {
                  return mismatch(model, movedBy(T, d, at), renderer.sensor(), cloud, window,
                                  tolerance_mm);
                },
                print_curves);
            if (print_curves)
              std::printf(" (truth at %.3f)\n", d.dot(instance.T_scene_part.translation() -
                                                      (T * T_part_model.inverse()).translation()));
            T.pretranslate(shift * d);
          }
        T_scene_part = T * T_part_model.inverse();
      } else {
        for (int round = 0; round < 2; ++round)
          for (int axis = 0; axis < 3; ++axis) {
            const Eigen::Vector3d d = T_scene_part.linear().col(axis);
            T_scene_part.pretranslate(leastCostShift([&](double at) {
                                        return difference(renderer, label,
                                                          movedBy(T_scene_part, d, at), cloud,
                                                          window, tolerance_mm);
                                      }) *
                                      d);
          }
      }
      icp_mm.push_back(before);
      pinned_mm.push_back(originError(T_scene_part));
      std::printf("%s instance %d (visible %.2f, view %zu): ICP %.3f mm, pinned %.3f mm\n",
                  scene.stem().c_str(), instance.id, instance.visible_fraction, best, before,
                  pinned_mm.back());
      std::fflush(stdout);
    }
  }
  std::printf("%s: %zu instances, median origin error ICP %.3f mm, pinned by the render %.3f mm\n",
              part.c_str(), icp_mm.size(), median(icp_mm), median(pinned_mm));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return scanpick::study::studyMain("study_render_pin", run, argc, argv);
}
