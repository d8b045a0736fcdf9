// The virtual scanner: points lie on surfaces, the projector casts shadows, visible fractions add
// up.
#include "core/sim/Renderer.h"

#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/PartCatalog.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

using namespace scanpick::core;

namespace {

/// PhoXi M geometry at a quarter of the resolution: same field of view, faster tests.
SensorModel smallPhoxi() {
  SensorModel s = sensorPreset("phoxi-m-1032");
  s.width = 258;
  s.height = 193;
  s.fx /= 4;
  s.fy /= 4;
  s.cx = (s.width - 1) / 2.0;
  s.cy = (s.height - 1) / 2.0;
  return s;
}

Scene binOf(const std::string& part, int count, std::uint64_t seed) {
  SceneSpec spec;
  spec.parts = {builtInPart(part)};
  spec.count = count;
  spec.seed = seed;
  return buildScene(spec, smallPhoxi());
}

/// Distance from a scene point to the surface its pixel is labelled with.
double distanceToLabelledSurface(const Scene& scene, const Eigen::Vector3f& p, std::int32_t label) {
  const Eigen::Vector3d q = p.cast<double>();
  if (label == kLabelEnvironment)
    return pointMeshDistance(q, transformed(scene.environment_mm, scene.T_camera_world));
  const auto& inst = scene.instances[static_cast<std::size_t>(label)];
  // Bring the point into the part frame instead of moving the mesh.
  return pointMeshDistance(scene.T_scene_part(inst).inverse() * q, scene.parts[inst.part].mesh());
}

} // namespace

TEST(Renderer, NoiselessPointsLieOnTheSurfaceTheyAreLabelledWith) {
  const Scene scene = binOf("support", 5, 1);
  const RenderResult r = renderScene(scene, smallPhoxi(), SensorNoise::none(), 9);
  ASSERT_EQ(r.cloud.width, 258u);
  ASSERT_EQ(r.cloud.height, 193u);
  std::size_t checked = 0, on_parts = 0;
  for (std::size_t i = 0; i < r.cloud.size(); i += 7) {
    if (!isValid(r.cloud.points_mm[i]))
      continue;
    ASSERT_NE(r.labels[i], kLabelNothing);
    EXPECT_LT(distanceToLabelledSurface(scene, r.cloud.points_mm[i], r.labels[i]), 0.01);
    ++checked;
    on_parts += r.labels[i] >= 0;
  }
  EXPECT_GT(checked, 3000u);
  EXPECT_GT(on_parts, 200u);
}

TEST(Renderer, NoisyPointsStayWithinFourSigma) {
  const Scene scene = binOf("cup", 4, 2);
  SensorNoise noise;
  noise.z_sigma_mm = 0.1;
  const RenderResult r = renderScene(scene, smallPhoxi(), noise, 9);
  double sum_sq = 0, worst = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < r.cloud.size(); i += 11) {
    if (!isValid(r.cloud.points_mm[i]))
      continue;
    const double d = distanceToLabelledSurface(scene, r.cloud.points_mm[i], r.labels[i]);
    worst = std::max(worst, d);
    sum_sq += d * d;
    ++n;
  }
  ASSERT_GT(n, 2000u);
  EXPECT_LE(worst, 4 * 0.1 + 0.01);
  // Depth noise of σ = 0.1 mm moves points off the surface by about σ·cos(incidence).
  const double rms = std::sqrt(sum_sq / static_cast<double>(n));
  EXPECT_GT(rms, 0.04);
  EXPECT_LT(rms, 0.11);
}

TEST(Renderer, ProjectorShadowRemovesPointsTheCameraSees) {
  // A 40 × 40 × 250 mm pillar on the table; the projector sits 300 mm to +x of the camera, so the
  // pillar shadows the table on its -x side, which the camera above still sees.
  Part pillar;
  pillar.name = "pillar";
  pillar.components = {boxMesh({-20, -20, 0}, {20, 20, 250})};
  SceneSpec spec;
  spec.layout = LayoutKind::Teach;
  spec.parts = {pillar};
  spec.count = 1;
  Scene scene = buildScene(spec, smallPhoxi());
  scene.instances[0].T_world_part = Eigen::Isometry3d::Identity();
  const SensorModel s = smallPhoxi();
  const RenderResult r = renderScene(scene, s, SensorNoise::none(), 1);

  const Eigen::Isometry3d T_world_camera = scene.T_camera_world.inverse();
  const Eigen::Vector3d projector_world = T_world_camera * s.projectorPosition();
  auto segmentHitsBox = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double grow) {
    // Slab test of segment a→b against the pillar grown by `grow` mm.
    const Eigen::Vector3d lo(-20 - grow, -20 - grow, -1e9), hi(20 + grow, 20 + grow, 250 + grow);
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 3; ++k) {
      const double d = b[k] - a[k];
      if (std::abs(d) < 1e-12) {
        if (a[k] < lo[k] || a[k] > hi[k])
          return false;
        continue;
      }
      double ta = (lo[k] - a[k]) / d, tb = (hi[k] - a[k]) / d;
      if (ta > tb)
        std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 <= t1;
  };
  std::size_t shadowed = 0, lit = 0;
  for (int v = 0; v < s.height; ++v)
    for (int u = 0; u < s.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * s.width + u;
      if (r.labels[i] != kLabelEnvironment)
        continue; // only where the camera sees the table
      // Where the camera ray meets the table top (z = 0 in the world).
      const Eigen::Vector3d dir_world =
          T_world_camera.linear() * Eigen::Vector3d((u - s.cx) / s.fx, (v - s.cy) / s.fy, 1);
      const Eigen::Vector3d origin = T_world_camera.translation();
      const Eigen::Vector3d table = origin + dir_world * (-origin.z() / dir_world.z());
      if (std::abs(table.x()) > 500 || std::abs(table.y()) > 500)
        continue;
      if (segmentHitsBox(table, projector_world, -1.0)) {
        EXPECT_FALSE(isValid(r.cloud.points_mm[i])) << "pixel " << u << "," << v << " is in shadow";
        ++shadowed;
      } else if (!segmentHitsBox(table, projector_world, 1.0)) {
        EXPECT_TRUE(isValid(r.cloud.points_mm[i])) << "pixel " << u << "," << v << " is lit";
        ++lit;
      }
    }
  EXPECT_GT(shadowed, 200u); // the shadow is large: the pillar is 250 mm tall
  EXPECT_GT(lit, 10000u);
}

TEST(Renderer, VisibleFractionsAgreeWithARecount) {
  const Scene scene = binOf("pump-connector", 6, 4);
  const SensorModel s = smallPhoxi();
  const RenderResult r = renderScene(scene, s, SensorNoise::none(), 3);
  bool some_occluded = false;
  for (const auto& inst : scene.instances) {
    const auto id = static_cast<std::size_t>(inst.id);
    // Without noise every lit pixel is a point: recount from labels and the cloud.
    std::size_t counted = 0;
    for (std::size_t i = 0; i < r.cloud.size(); ++i)
      counted += r.labels[i] == inst.id && isValid(r.cloud.points_mm[i]);
    EXPECT_EQ(counted, r.visible_points[id]);
    EXPECT_EQ(counted, r.lit_pixels[id]);
    // Alone: a scene with only this instance, rendered over the whole image.
    Scene alone = scene;
    alone.environment_mm = {};
    alone.instances = {inst};
    alone.instances[0].id = 0;
    const RenderResult ra = renderScene(alone, s, SensorNoise::none(), 3);
    EXPECT_EQ(ra.lit_pixels[0], r.lit_pixels_alone[id]);
    EXPECT_NEAR(ra.visible_fraction[0], 1.0, 1e-12);
    if (r.lit_pixels_alone[id] > 0) {
      EXPECT_NEAR(r.visible_fraction[id], double(counted) / double(r.lit_pixels_alone[id]), 1e-12);
    }
    some_occluded |= r.visible_fraction[id] < 0.9;
  }
  EXPECT_TRUE(some_occluded) << "a pile of 6 should hide part of some instance";
}

TEST(Renderer, SameSeedSameBitsDifferentSeedDifferentNoise) {
  const Scene scene = binOf("coat-rack", 5, 5);
  const SensorModel s = smallPhoxi();
  const SensorNoise noise = SensorNoise::typical(s);
  const RenderResult a = renderScene(scene, s, noise, 21), b = renderScene(scene, s, noise, 21);
  const RenderResult c = renderScene(scene, s, noise, 22);
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  EXPECT_EQ(std::memcmp(a.cloud.points_mm.data(), b.cloud.points_mm.data(),
                        a.cloud.size() * sizeof(Eigen::Vector3f)),
            0);
  EXPECT_NE(std::memcmp(a.cloud.points_mm.data(), c.cloud.points_mm.data(),
                        a.cloud.size() * sizeof(Eigen::Vector3f)),
            0);
}

TEST(SensorNoise, KinectDepthStepsGrowWithDistanceSquared) {
  const SensorModel kinect = sensorPreset("kinect-v1");
  SensorNoise n = SensorNoise::typical(kinect);
  n.disparity_sigma_px = 0;
  const double b = kinect.T_camera_projector.translation().norm();
  auto step = [&](double z0) {
    // Smallest jump between distinct measured depths around z0.
    double prev = noisyDepth(z0, n, kinect.fx, b, 1, 0), smallest = 1e9;
    for (double z = z0; z < z0 + 100; z += 0.5) {
      const double m = noisyDepth(z, n, kinect.fx, b, 1, 0);
      if (m != prev)
        smallest = std::min(smallest, std::abs(m - prev));
      prev = m;
    }
    return smallest;
  };
  // d = f·b/z, steps of 1/8 px: Δz ≈ z²/(8 f b) = 11.6 mm at 2 m and a quarter of that at 1 m.
  EXPECT_NEAR(step(2000), 2000.0 * 2000.0 / (8 * kinect.fx * b), 1.0);
  EXPECT_NEAR(step(1000) * 4, step(2000), 1.5);
}

TEST(Renderer, SensorWithoutPixelsThrows) {
  SensorModel s = smallPhoxi();
  s.width = 0;
  EXPECT_THROW(renderScene(binOf("cup", 1, 1), s, SensorNoise::none(), 1), Error);
}
