#include "core/sim/Renderer.h"

#include "core/common/Error.h"
#include "core/sim/EmbreeMesh.h"

#include <algorithm>
#include <cmath>
#include <embree3/rtcore.h>
#include <limits>
#include <optional>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

/// An Embree device and scene holding triangle meshes in the camera frame, each with a label.
class RayScene {
public:
  RayScene() : m_device(rtcNewDevice(nullptr)) {
    if (!m_device)
      throw Error("cannot start the Embree ray tracer (error " +
                  std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    m_scene = rtcNewScene(m_device);
    // Robust traversal: rays must not slip through the shared edges of a closed mesh.
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
  }
  ~RayScene() {
    rtcReleaseScene(m_scene);
    rtcReleaseDevice(m_device);
  }
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  void add(const TriangleMesh& mesh_camera_mm, std::int32_t label) {
    if (mesh_camera_mm.empty())
      return;
    const unsigned id = attachTriangleMesh(m_device, m_scene, mesh_camera_mm);
    if (m_labels.size() <= id)
      m_labels.resize(id + 1, kLabelNothing);
    m_labels[id] = label;
  }
  void commit() { rtcCommitScene(m_scene); }

  /// What one camera pixel sees.
  struct Sample {
    std::int32_t label = kLabelNothing;
    bool lit = false; ///< in range, lit by the projector, not grazing
    float z_mm = 0;
  };

  Sample trace(const SensorModel& s, int u, int v, const Eigen::Vector3f& projector,
               float grazing_cos) const {
    Sample out;
    const Eigen::Vector3f dir(static_cast<float>((u - s.cx) / s.fx),
                              static_cast<float>((v - s.cy) / s.fy), 1.0f);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = rh.ray.org_y = rh.ray.org_z = 0;
    rh.ray.dir_x = dir.x();
    rh.ray.dir_y = dir.y();
    rh.ray.dir_z = dir.z();
    rh.ray.tnear = 0;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      return out;
    out.label = m_labels[rh.hit.geomID];
    out.z_mm = rh.ray.tfar; // dir.z == 1, so t is the depth along the optical axis
    if (out.z_mm < s.min_range_mm || out.z_mm > s.max_range_mm)
      return out;
    const Eigen::Vector3f p = dir * rh.ray.tfar;
    Eigen::Vector3f n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    n.normalize();
    const Eigen::Vector3f to_camera = -p.normalized();
    if (n.dot(to_camera) < 0)
      n = -n; // the side the camera sees
    Eigen::Vector3f to_projector = projector - p;
    const float dist = to_projector.norm();
    to_projector /= dist;
    const float cos_projector = n.dot(to_projector);
    if (cos_projector <= 0 ||
        (grazing_cos > 0 && (cos_projector < grazing_cos || n.dot(to_camera) < grazing_cos)))
      return out;
    RTCRay shadow{};
    const Eigen::Vector3f origin = p + n * 0.01f;
    shadow.org_x = origin.x();
    shadow.org_y = origin.y();
    shadow.org_z = origin.z();
    shadow.dir_x = to_projector.x();
    shadow.dir_y = to_projector.y();
    shadow.dir_z = to_projector.z();
    shadow.tnear = 0;
    shadow.tfar = dist - 0.02f;
    shadow.mask = 0xFFFFFFFFu;
    rtcOccluded1(m_scene, &ctx, &shadow);
    out.lit = shadow.tfar >= 0; // Embree sets tfar to -inf when occluded
    return out;
  }

private:
  RTCDevice m_device = nullptr;
  RTCScene m_scene = nullptr;
  std::vector<std::int32_t> m_labels;
};

/// Pixel rectangle [u0, u1) × [v0, v1) covering the projection of `mesh` (camera frame).
std::array<int, 4> projectedRect(const TriangleMesh& mesh, const SensorModel& s) {
  const Eigen::AlignedBox3d box = boundingBox(mesh);
  if (box.isEmpty() || box.max().z() <= 0)
    return {0, 0, 0, 0};
  if (box.min().z() <= 1.0)
    return {0, s.width, 0, s.height};
  double u0 = 1e18, u1 = -1e18, v0 = 1e18, v1 = -1e18;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector2d px =
        s.project(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)));
    u0 = std::min(u0, px.x());
    u1 = std::max(u1, px.x());
    v0 = std::min(v0, px.y());
    v1 = std::max(v1, px.y());
  }
  auto clampTo = [](double x, int hi) {
    return static_cast<int>(std::clamp(x, 0.0, static_cast<double>(hi)));
  };
  return {clampTo(std::floor(u0) - 1, s.width), clampTo(std::ceil(u1) + 2, s.width),
          clampTo(std::floor(v0) - 1, s.height), clampTo(std::ceil(v1) + 2, s.height)};
}

/// The posed meshes of the scene's instances (camera frame, by instance id), added to `rays` with
/// the environment's.
std::vector<TriangleMesh> addSceneMeshes(RayScene& rays, const Scene& scene) {
  std::vector<TriangleMesh> posed(scene.instances.size());
  rays.add(transformed(scene.environment_mm, scene.T_camera_world), kLabelEnvironment);
  for (const auto& inst : scene.instances) {
    posed[static_cast<std::size_t>(inst.id)] =
        transformed(scene.parts[inst.part].mesh(), scene.T_scene_part(inst));
    rays.add(posed[static_cast<std::size_t>(inst.id)], inst.id);
  }
  rays.commit();
  return posed;
}

/// What every pixel of the sensor sees in `rays` (row-major), in chunks of rows; the chunks take
/// the first 60 % of `progress`.
std::vector<RayScene::Sample> traceImage(const RayScene& rays, const SensorModel& sensor,
                                         const Eigen::Vector3f& projector, float grazing,
                                         const ProgressFn& progress) {
  const int W = sensor.width, H = sensor.height;
  const std::size_t N = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);
  std::vector<RayScene::Sample> samples(N);
  constexpr int kRowsPerChunk = 64;
  for (int row0 = 0; row0 < H; row0 += kRowsPerChunk) {
    tbb::parallel_for(tbb::blocked_range<int>(row0, std::min(H, row0 + kRowsPerChunk)),
                      [&](const auto& r) {
                        for (int v = r.begin(); v != r.end(); ++v)
                          for (int u = 0; u < W; ++u)
                            samples[static_cast<std::size_t>(v) * W + u] =
                                rays.trace(sensor, u, v, projector, grazing);
                      });
    reportProgress(progress, 0.6 * std::min(H, row0 + kRowsPerChunk) / H);
  }
  return samples;
}

/// The lit pixels of each of the `posed` instances were it alone in the scene, traced only over
/// the pixels its bounding box can cover; reports progress from 0.6 to 0.9.
std::vector<std::size_t> litPixelsAlone(const std::vector<TriangleMesh>& posed,
                                        const SensorModel& sensor, const Eigen::Vector3f& projector,
                                        float grazing, const ProgressFn& progress) {
  const std::size_t count = posed.size();
  std::vector<std::size_t> lit(count, 0);
  for (std::size_t id = 0; id < count; ++id) {
    const auto rect = projectedRect(posed[id], sensor);
    if (rect[1] <= rect[0] || rect[3] <= rect[2])
      continue;
    RayScene alone;
    alone.add(posed[id], static_cast<std::int32_t>(id));
    alone.commit();
    std::vector<std::size_t> per_row(static_cast<std::size_t>(rect[3] - rect[2]), 0);
    tbb::parallel_for(tbb::blocked_range<int>(rect[2], rect[3]), [&](const auto& r) {
      for (int v = r.begin(); v != r.end(); ++v)
        for (int u = rect[0]; u < rect[1]; ++u) {
          const auto sample = alone.trace(sensor, u, v, projector, grazing);
          if (sample.lit && sample.label == static_cast<std::int32_t>(id))
            ++per_row[static_cast<std::size_t>(v - rect[2])];
        }
    });
    for (std::size_t c : per_row)
      lit[id] += c;
    reportProgress(progress, 0.6 + 0.3 * static_cast<double>(id + 1) / static_cast<double>(count));
  }
  return lit;
}

/// The depth jump (mm) from `z` to the 4-neighbour of pixel (u, v) that sees a surface and
/// differs most from it; 0 when none does.
double largestDepthJump(const std::vector<RayScene::Sample>& samples, int W, int H, int u, int v,
                        double z) {
  double jump = 0;
  const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int nu = u + du[k], nv = v + dv[k];
    if (nu < 0 || nv < 0 || nu >= W || nv >= H)
      continue;
    const auto& ns = samples[static_cast<std::size_t>(nv) * W + nu];
    if (ns.label != kLabelNothing && std::abs(ns.z_mm - z) > std::abs(jump))
      jump = ns.z_mm - z;
  }
  return jump;
}

/// The point (camera frame, mm) that pixel (u, v) measures with `noise`: dropouts, flying pixels
/// at depth edges and depth noise, drawn from `seed`. None where it measures nothing.
std::optional<Eigen::Vector3f> measuredPoint(const std::vector<RayScene::Sample>& samples,
                                             const SensorModel& sensor, const SensorNoise& noise,
                                             double baseline_mm, std::uint64_t seed, int u, int v) {
  const int W = sensor.width, H = sensor.height;
  const std::size_t i = static_cast<std::size_t>(v) * W + u;
  if (!samples[i].lit)
    return std::nullopt;
  if (noise.dropout_probability > 0 && hashUniform(seed, i, 10) < noise.dropout_probability)
    return std::nullopt;
  double z = samples[i].z_mm;
  if (noise.flying_probability > 0) {
    const double jump = largestDepthJump(samples, W, H, u, v, z);
    // A mixed pixel: the sensor averages the two depths seen across the edge.
    if (std::abs(jump) > noise.flying_edge_mm &&
        hashUniform(seed, i, 11) < noise.flying_probability)
      z += jump * (0.2 + 0.6 * hashUniform(seed, i, 12));
  }
  z = noisyDepth(z, noise, sensor.fx, baseline_mm, seed, i);
  return Eigen::Vector3f(static_cast<float>((u - sensor.cx) / sensor.fx * z),
                         static_cast<float>((v - sensor.cy) / sensor.fy * z),
                         static_cast<float>(z));
}

} // namespace

RenderResult renderScene(const Scene& scene, const SensorModel& sensor, const SensorNoise& noise,
                         std::uint64_t seed, const ProgressFn& progress) {
  if (sensor.width <= 0 || sensor.height <= 0 || sensor.fx <= 0 || sensor.fy <= 0)
    throw Error("the sensor '" + sensor.preset + "' has no valid image size or focal length");
  const int W = sensor.width, H = sensor.height;
  const std::size_t N = static_cast<std::size_t>(W) * static_cast<std::size_t>(H);
  const Eigen::Vector3f projector = sensor.projectorPosition().cast<float>();
  const auto grazing = static_cast<float>(noise.grazing_cos);
  const std::size_t count = scene.instances.size();

  RayScene rays;
  const std::vector<TriangleMesh> posed = addSceneMeshes(rays, scene);
  const std::vector<RayScene::Sample> samples =
      traceImage(rays, sensor, projector, grazing, progress);

  RenderResult out;
  out.labels.resize(N);
  out.lit_pixels.assign(count, 0);
  out.visible_points.assign(count, 0);
  for (std::size_t i = 0; i < N; ++i) {
    out.labels[i] = samples[i].label;
    if (samples[i].lit && samples[i].label >= 0)
      ++out.lit_pixels[static_cast<std::size_t>(samples[i].label)];
  }

  // Each instance alone, only over the pixels its bounding box can cover.
  out.lit_pixels_alone = litPixelsAlone(posed, sensor, projector, grazing, progress);
  out.visible_fraction.resize(count);
  for (std::size_t id = 0; id < count; ++id)
    out.visible_fraction[id] =
        out.lit_pixels_alone[id] == 0
            ? 0.0
            : std::min(1.0, static_cast<double>(out.lit_pixels[id]) /
                                static_cast<double>(out.lit_pixels_alone[id]));

  // Measurement: dropouts, flying pixels at depth edges, depth noise; reads only the clean samples.
  const double baseline_mm = sensor.T_camera_projector.translation().norm();
  out.cloud.width = static_cast<std::uint32_t>(W);
  out.cloud.height = static_cast<std::uint32_t>(H);
  out.cloud.points_mm.assign(N, invalidPoint());
  tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const auto& r) {
    for (int v = r.begin(); v != r.end(); ++v)
      for (int u = 0; u < W; ++u)
        if (const auto p = measuredPoint(samples, sensor, noise, baseline_mm, seed, u, v))
          out.cloud.points_mm[static_cast<std::size_t>(v) * W + u] = *p;
  });
  for (std::size_t i = 0; i < N; ++i)
    if (out.labels[i] >= 0 && isValid(out.cloud.points_mm[i]))
      ++out.visible_points[static_cast<std::size_t>(out.labels[i])];
  reportProgress(progress, 1.0);
  return out;
}

} // namespace scanpick::core
