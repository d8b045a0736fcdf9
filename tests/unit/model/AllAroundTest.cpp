#include "core/model/AllAround.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <numbers>

using namespace scanpick::core;

namespace {

/// Points every `step_mm` over the faces of a box of `size_mm` centred at `centre_mm`, with each
/// face's outward normal beside them (not in the cloud).
struct Sampled {
  PointCloud cloud;
  std::vector<Eigen::Vector3f> outward;
};

Sampled boxSurface(const Eigen::Vector3f& size_mm, const Eigen::Vector3f& centre_mm,
                   float step_mm) {
  Sampled out;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      // Inset by half a step so that no two faces share a point.
      for (float s = -size_mm[a] / 2 + step_mm / 2; s < size_mm[a] / 2; s += step_mm)
        for (float t = -size_mm[b] / 2 + step_mm / 2; t < size_mm[b] / 2; t += step_mm) {
          Eigen::Vector3f p;
          p[axis] = side * size_mm[axis] / 2;
          p[a] = s;
          p[b] = t;
          out.cloud.points_mm.push_back(centre_mm + p);
          out.outward.push_back(side * Eigen::Vector3f::Unit(axis));
        }
    }
  out.cloud.width = static_cast<std::uint32_t>(out.cloud.points_mm.size());
  out.cloud.height = 1;
  return out;
}

/// About `count` points spread evenly over a sphere (a Fibonacci lattice).
Sampled sphereSurface(double radius_mm, const Eigen::Vector3f& centre_mm, int count) {
  Sampled out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3f n =
        Eigen::Vector3d(r * std::cos(golden * i), r * std::sin(golden * i), z).cast<float>();
    out.cloud.points_mm.push_back(centre_mm + static_cast<float>(radius_mm) * n);
    out.outward.push_back(n);
  }
  out.cloud.width = static_cast<std::uint32_t>(count);
  out.cloud.height = 1;
  return out;
}

/// The share of normals within 25° of the true outward ones.
double outwardShare(const Sampled& s, const std::vector<Eigen::Vector3f>& normals) {
  std::size_t good = 0;
  for (std::size_t i = 0; i < normals.size(); ++i)
    good += normals[i].allFinite() && normals[i].dot(s.outward[i]) > 0.9f ? 1 : 0;
  return static_cast<double>(good) / static_cast<double>(normals.size());
}

} // namespace

TEST(AllAround, APartSampledAllAroundIsNotOneScanItsHalfFacingTheCameraIs) {
  const Eigen::Vector3f centre(10.0f, -20.0f, 700.0f);
  const Sampled sphere = sphereSurface(50.0, centre, 20000);
  const double spacing = 50.0 * std::sqrt(4.0 * std::numbers::pi / 20000);
  EXPECT_FALSE(seenFromOneCamera(sphere.cloud, Eigen::Vector3d::Zero(), spacing));
  PointCloud facing;
  for (std::size_t i = 0; i < sphere.cloud.size(); ++i)
    if (sphere.outward[i].dot(-sphere.cloud.points_mm[i]) > 0)
      facing.points_mm.push_back(sphere.cloud.points_mm[i]);
  EXPECT_TRUE(seenFromOneCamera(facing, Eigen::Vector3d::Zero(), spacing));
  EXPECT_FALSE(
      seenFromOneCamera(facing, (centre - Eigen::Vector3f(0, 0, 20)).cast<double>(), spacing))
      << "a camera inside the cloud's box took no scan of it";
  const Sampled box = boxSurface({80.0f, 60.0f, 40.0f}, centre, 1.0f);
  EXPECT_FALSE(seenFromOneCamera(box.cloud, Eigen::Vector3d::Zero(), 1.0));
}

TEST(AllAround, NormalsFaceOutOfTheSphereAndTheBox) {
  const Sampled sphere = sphereSurface(50.0, {0.0f, 0.0f, 700.0f}, 20000);
  const auto sphere_normals = outwardNormals(sphere.cloud, 3.0);
  ASSERT_EQ(sphere_normals.size(), sphere.cloud.size());
  EXPECT_GT(outwardShare(sphere, sphere_normals), 0.999);
  const Sampled box = boxSurface({80.0f, 60.0f, 40.0f}, {5.0f, 5.0f, 650.0f}, 1.0f);
  // Within 2 mm of an edge a fitted normal blends two faces; the rest must all face out.
  EXPECT_GT(outwardShare(box, outwardNormals(box.cloud, 2.0)), 0.93);
}

TEST(AllAround, AThinPlatesTwoFacesFaceAwayFromEachOther) {
  // 1.5 mm thick, sampled every 1 mm: each point's nearest neighbours include the other face's.
  // The normals come with the cloud (as from a mesh), their signs scrambled.
  Sampled plate = boxSurface({100.0f, 80.0f, 1.5f}, {0.0f, 0.0f, 600.0f}, 1.0f);
  for (std::size_t i = 0; i < plate.outward.size(); ++i)
    plate.cloud.normals.push_back(i % 3 == 0 ? -plate.outward[i] : plate.outward[i]);
  const auto normals = outwardNormals(plate.cloud, 2.0);
  for (std::size_t i = 0; i < normals.size(); ++i)
    ASSERT_GT(normals[i].dot(plate.outward[i]), 0.9999f) << i;
}

namespace {

/// Points every `step_mm` over the axis-aligned rectangle of `face` from `from` to `to` (one of
/// their coordinates equal), kept where `keep` says, each with `outward` beside it.
void sampleFace(Sampled& out, const Eigen::Vector3f& from, const Eigen::Vector3f& to,
                const Eigen::Vector3f& outward, float step_mm,
                const std::function<bool(const Eigen::Vector3f&)>& keep = {}) {
  const Eigen::Vector3f size = to - from;
  for (float s = step_mm / 2; s < std::max({size.x(), size.y(), size.z()}); s += step_mm)
    for (float t = step_mm / 2; t < std::max({size.x(), size.y(), size.z()}); t += step_mm) {
      // The face spans the two axes along which it has an extent.
      Eigen::Vector3f p = from;
      int used = 0;
      for (int axis = 0; axis < 3; ++axis)
        if (size[axis] > 0) {
          const float along = used++ == 0 ? s : t;
          if (along >= size[axis])
            p[axis] = NAN;
          p[axis] += along;
        }
      if (p.allFinite() && (!keep || keep(p))) {
        out.cloud.points_mm.push_back(p);
        out.outward.push_back(outward);
      }
    }
}

} // namespace

TEST(AllAround, AShallowStepsFacesBothFaceUp) {
  // A block 100 x 60 mm, 20 mm high for x < 50 and 21.5 mm beyond: the two top faces lie 1.5 mm
  // apart along their normals, closer than the neighbours the graph links (spacing 1 mm).
  const float low = 20.0f, high = 21.5f;
  const auto height = [&](float x) { return x < 50.0f ? low : high; };
  Sampled block;
  sampleFace(block, {0, 0, 0}, {100, 60, 0}, -Eigen::Vector3f::UnitZ(), 1.0f);
  sampleFace(block, {0, 0, low}, {50, 60, low}, Eigen::Vector3f::UnitZ(), 1.0f);
  sampleFace(block, {50, 0, high}, {100, 60, high}, Eigen::Vector3f::UnitZ(), 1.0f);
  sampleFace(block, {50, 0, low}, {50, 60, high}, -Eigen::Vector3f::UnitX(), 0.5f);
  sampleFace(block, {0, 0, 0}, {0, 60, low}, -Eigen::Vector3f::UnitX(), 1.0f);
  sampleFace(block, {100, 0, 0}, {100, 60, high}, Eigen::Vector3f::UnitX(), 1.0f);
  const auto under = [&](const Eigen::Vector3f& p) { return p.z() < height(p.x()); };
  sampleFace(block, {0, 0, 0}, {100, 0, high}, -Eigen::Vector3f::UnitY(), 1.0f, under);
  sampleFace(block, {0, 60, 0}, {100, 60, high}, Eigen::Vector3f::UnitY(), 1.0f, under);
  for (auto& p : block.cloud.points_mm)
    p.z() += 600.0f;
  block.cloud.width = static_cast<std::uint32_t>(block.cloud.points_mm.size());
  block.cloud.height = 1;
  for (std::size_t i = 0; i < block.outward.size(); ++i)
    block.cloud.normals.push_back(i % 3 == 0 ? -block.outward[i] : block.outward[i]);
  const auto normals = outwardNormals(block.cloud, 2.0);
  for (std::size_t i = 0; i < normals.size(); ++i)
    ASSERT_GT(normals[i].dot(block.outward[i]), 0.9999f) << i << " at " << block.cloud.points_mm[i];
}

TEST(AllAround, TheCloudsOwnNormalsAreTurnedConsistentlyOutward) {
  Sampled sphere = sphereSurface(40.0, {0.0f, 0.0f, 500.0f}, 10000);
  // Normals of a scan's file with random signs, as merged views bring them.
  for (std::size_t i = 0; i < sphere.outward.size(); ++i)
    sphere.cloud.normals.push_back((i * 2654435761u) % 7 < 3 ? -sphere.outward[i]
                                                             : sphere.outward[i]);
  const auto normals = outwardNormals(sphere.cloud, 3.0);
  for (std::size_t i = 0; i < normals.size(); ++i)
    ASSERT_GT(normals[i].dot(sphere.outward[i]), 0.9999f) << i;
  EXPECT_EQ(outwardNormals(sphere.cloud, 3.0), normals) << "deterministic";
}

TEST(AllAround, InvalidPointsKeepTheirPlaceWithoutANormal) {
  Sampled sphere = sphereSurface(40.0, {0.0f, 0.0f, 500.0f}, 5000);
  sphere.cloud.points_mm[7] = invalidPoint();
  const auto normals = outwardNormals(sphere.cloud, 4.0);
  ASSERT_EQ(normals.size(), sphere.cloud.size());
  EXPECT_FALSE(normals[7].allFinite());
  EXPECT_GT(normals[8].dot(sphere.outward[8]), 0.99f);
}
