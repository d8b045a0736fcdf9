// SceneIndex and RefineModel on exact geometry: planes whose normals are known.
#include "core/refine/SceneIndex.h"

#include "core/common/Error.h"
#include "core/refine/RefineModel.h"
#include "tests/unit/refine/BracketScene.h"

#include <gtest/gtest.h>
#include <random>
#include <vector>

using namespace scanpick;

namespace {

/// A floor at 600 mm seen by a 200 x 150 camera (f 500 px): every normal is (0, 0, -1), facing
/// the camera at the origin.
core::PointCloud floorScan(double sigma_mm) {
  return test::renderSolids({}, 600.0, 200, 150, 500, sigma_mm, 0.05, 5);
}

/// The camera floorScan renders with, as a sensor.
core::SensorModel floorCamera() {
  core::SensorModel sensor;
  sensor.width = 200;
  sensor.height = 150;
  sensor.fx = sensor.fy = 500;
  sensor.cx = (200 - 1) / 2.0;
  sensor.cy = (150 - 1) / 2.0;
  return sensor;
}

/// Asks both indexes for the nearest point to every `stride`-th indexed point moved by each of
/// `offsets`, within each of `radii`, and expects the same answers. Returns how many were found.
std::size_t expectSameNearest(const core::SceneIndex& windows, const core::SceneIndex& tree,
                              std::size_t stride, const std::vector<float>& radii,
                              const std::vector<Eigen::Vector3f>& offsets) {
  std::size_t found = 0;
  for (std::size_t k = 0; k < tree.size(); k += stride)
    for (const float radius : radii)
      for (const Eigen::Vector3f& offset : offsets) {
        const Eigen::Vector3f query = tree.points()[k] + offset;
        float d_tree = -1.0f, d_windows = -2.0f;
        const std::int64_t near = tree.nearest(query, radius * radius, &d_tree);
        EXPECT_EQ(windows.nearest(query, radius * radius, &d_windows), near) << radius;
        if (near >= 0) {
          EXPECT_EQ(d_windows, d_tree);
          ++found;
        }
      }
  return found;
}

} // namespace

TEST(SceneIndex, OrganizedAndUnorganizedNormalsFaceTheCamera) {
  const auto scan = floorScan(0.0);
  for (const auto& cloud : {scan, core::dropInvalid(scan)}) {
    const core::SceneIndex index(cloud);
    ASSERT_EQ(index.size(), scan.validCount());
    std::size_t with_normal = 0;
    for (const auto& n : index.normals())
      if (n.allFinite()) {
        ++with_normal;
        EXPECT_NEAR(n.z(), -1.0f, 1e-4f);
      }
    // Only isolated pixels among dropouts can lack the 5 neighbours a normal needs.
    EXPECT_GT(with_normal, index.size() * 99 / 100);
  }
}

TEST(SceneIndex, ACloudsOwnNormalsFaceTheViewpointUnlessTakenAsTheyAre) {
  // Two points whose normals face the viewpoint (the origin) and away from it: a model joined from
  // views keeps each view's normals facing its own teach camera.
  core::PointCloud cloud;
  cloud.points_mm = {{0, 0, 500}, {10, 0, 500}};
  cloud.normals = {{0, 0, -1}, {0, 0, 1}};
  cloud.width = 2;
  cloud.height = 1;
  core::SceneIndexOptions options;
  const core::SceneIndex oriented(cloud, options);
  options.orient_cloud_normals = false;
  const core::SceneIndex as_they_are(cloud, options);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(oriented.normals()[i], Eigen::Vector3f(0, 0, -1)) << i;
    EXPECT_EQ(as_they_are.normals()[i], cloud.normals[i]) << i;
  }
}

TEST(SceneIndex, NearestRespectsTheDistanceBoundAndSurvivesAMove) {
  core::SceneIndex index(floorScan(0.0));
  const core::SceneIndex moved(std::move(index));
  // 0.4 mm in front of an indexed point: the neighbours lie 1.2 mm apart (f 500 px at 600 mm),
  // so that point is the nearest, 0.16 mm² away.
  const std::size_t k = moved.size() / 2;
  const Eigen::Vector3f above = moved.points()[k] - Eigen::Vector3f(0, 0, 0.4f);
  float d2 = -1;
  EXPECT_EQ(moved.nearest(above, 1.0f, &d2), static_cast<std::int64_t>(k));
  EXPECT_NEAR(d2, 0.16f, 1e-4f);
  EXPECT_LT(moved.nearest(above, 0.1f), 0); // bound 0.32 mm: nothing that close
  EXPECT_LT(moved.nearest(Eigen::Vector3f(0, 0, 605), 4.0f), 0); // 5 mm away, bound 2 mm
  EXPECT_LT(moved.nearest(core::invalidPoint(), 1e9f), 0);
}

TEST(SceneIndex, WithoutNormalsItFindsTheSameNearestPoints) {
  const auto cloud = core::dropInvalid(floorScan(0.3));
  core::SceneIndexOptions nearest_only;
  nearest_only.estimate_normals = false;
  const core::SceneIndex full(cloud), bare(cloud, nearest_only);
  ASSERT_EQ(bare.size(), full.size());
  ASSERT_EQ(bare.normals().size(), bare.size());
  for (std::size_t k = 0; k < bare.size(); k += 97) {
    EXPECT_FALSE(bare.normals()[k].allFinite());
    const Eigen::Vector3f query = bare.points()[k] + Eigen::Vector3f(0.3f, -0.2f, 0.5f);
    EXPECT_EQ(bare.nearest(query, 4.0f), full.nearest(query, 4.0f));
  }
}

TEST(SceneIndex, StridedNormalsAreThoseOfEveryNthPoint) {
  // Organized (pixel windows) and not (kd-tree): the normals kept are the full index's, bit for
  // bit; the others are not estimated.
  for (const auto& cloud : {floorScan(0.3), core::dropInvalid(floorScan(0.3))}) {
    core::SceneIndexOptions strided;
    strided.normal_stride = 7;
    const core::SceneIndex full(cloud), part(cloud, strided);
    ASSERT_EQ(part.size(), full.size());
    std::size_t estimated = 0;
    for (std::size_t k = 0; k < part.size(); ++k) {
      if (k % 7 != 0) {
        ASSERT_FALSE(part.normals()[k].allFinite()) << k;
        continue;
      }
      ASSERT_EQ(part.normals()[k].allFinite(), full.normals()[k].allFinite()) << k;
      if (full.normals()[k].allFinite()) {
        EXPECT_EQ(part.normals()[k], full.normals()[k]) << k;
        ++estimated;
      }
    }
    EXPECT_GT(estimated, part.size() / 10);
  }
  core::SceneIndexOptions none;
  none.normal_stride = 0;
  EXPECT_THROW(core::SceneIndex(floorScan(0.0), none), core::Error);
}

TEST(SceneIndex, APixelWindowFindsWhatTheTreeFindsWithinIt) {
  // f 500 px at 600 mm: 1.2 mm per pixel, so points within 1 mm of a query lie within two
  // pixels of its own.
  const auto scan = floorScan(0.3);
  const core::SceneIndex index(scan);
  ASSERT_EQ(index.width(), 200);
  ASSERT_EQ(index.pixelIndex().size(), scan.size());
  std::size_t found = 0;
  for (std::size_t pixel = 0; pixel < scan.size(); pixel += 37) {
    const std::int32_t k = index.pixelIndex()[pixel];
    if (k < 0)
      continue;
    const int u = int(pixel % 200), v = int(pixel / 200);
    const Eigen::Vector3f query =
        index.points()[std::size_t(k)] + Eigen::Vector3f(0.5f, 0.4f, 0.3f);
    const std::int64_t near = index.nearest(query, 1.0f);
    EXPECT_EQ(index.nearestInWindow(query, 1.0f, u, v, 2, 2), near);
    found += near >= 0;
    EXPECT_LT(index.nearestInWindow(query, 1.0f, u + 10, v, 2, 2), 0) << "window elsewhere";
  }
  EXPECT_GT(found, 500u);
  const core::SceneIndex unorganized(core::dropInvalid(scan));
  EXPECT_TRUE(unorganized.pixelIndex().empty());
  EXPECT_LT(unorganized.nearestInWindow(unorganized.points()[0], 1.0f, 0, 0, 2, 2), 0);
}

TEST(SceneIndex, PixelWindowsOfAnyWidthGiveTheNearestAndTheLowestIndexAtTies) {
  // Windows narrower and wider than the eight pixels searched at a time, at the image's edges
  // and last pixel; on a noise-free floor, queries between pixels are as near to several points.
  for (const double sigma_mm : {0.0, 0.3}) {
    const auto scan = floorScan(sigma_mm);
    const core::SceneIndex index(scan);
    const int width = index.width(), height = index.height();
    // Every pixel of the window, nearest first, at equal distances the lowest index.
    const auto bruteForce = [&](const Eigen::Vector3f& query, float max_sq, int u, int v, int hu,
                                int hv, float* d_sq) {
      std::int64_t best_index = -1;
      float best = max_sq;
      for (int r = std::max(0, v - hv); r <= std::min(height - 1, v + hv); ++r)
        for (int c = std::max(0, u - hu); c <= std::min(width - 1, u + hu); ++c) {
          const std::int32_t k = index.pixelIndex()[std::size_t(r) * std::size_t(width) + c];
          if (k < 0)
            continue;
          const Eigen::Vector3f& p = index.points()[std::size_t(k)];
          float d = 0.0f;
          for (int a = 0; a < 3; ++a)
            d += (query[a] - p[a]) * (query[a] - p[a]);
          if (d < best || (d == best && (best_index < 0 || k < best_index))) {
            best = d;
            best_index = k;
          }
        }
      *d_sq = best;
      return best_index;
    };
    std::vector<int> pixels{0, width - 1, (height - 1) * width, height * width - 1};
    for (int pixel = 13; pixel < width * height; pixel += 211)
      pixels.push_back(pixel);
    std::size_t found = 0, compared = 0;
    for (const int pixel : pixels) {
      const std::int32_t k = index.pixelIndex()[std::size_t(pixel)];
      if (k < 0)
        continue;
      const int u = pixel % width, v = pixel / width;
      for (const Eigen::Vector3f& offset :
           {Eigen::Vector3f(0, 0, -0.5f), Eigen::Vector3f(0.6f, 0, 0),
            Eigen::Vector3f(0.6f, 0.6f, -0.2f)})
        for (const auto& [hu, hv] : {std::pair{0, 0}, {1, 2}, {3, 3}, {4, 1}, {6, 6}, {9, 9}})
          for (const float max_sq : {0.5f, 25.0f}) {
            const Eigen::Vector3f query = index.points()[std::size_t(k)] + offset;
            float got = -1.0f, want = -1.0f;
            const std::int64_t near = bruteForce(query, max_sq, u, v, hu, hv, &want);
            ASSERT_EQ(index.nearestInWindow(query, max_sq, u, v, hu, hv, &got), near)
                << "pixel " << pixel << ", window " << hu << " x " << hv;
            if (near >= 0) {
              EXPECT_EQ(got, want);
            }
            found += near >= 0;
            ++compared;
          }
    }
    EXPECT_GT(found, compared / 3);
  }
}

TEST(SceneIndex, WithItsSensorNearestLooksInPixelWindowsWithTheSameAnswers) {
  // The floor's camera as a sensor: each point lies on its pixel's ray (depth noise moves it
  // along the ray), so nearest() looks in pixel windows for small spheres, the tree otherwise.
  const auto scan = floorScan(0.3);
  const core::SensorModel sensor = floorCamera();
  core::SceneIndexOptions options;
  options.sensor = sensor;
  const core::SceneIndex windows(scan, options), tree(scan);
  EXPECT_GE(windows.pixelSlack(), 0.0f);
  EXPECT_LT(windows.pixelSlack(), 1e-3f);
  EXPECT_LT(tree.pixelSlack(), 0.0f) << "no sensor, no windows";
  EXPECT_GT(expectSameNearest(windows, tree, 29, {0.5f, 1.0f, 2.5f, 5.0f, 8.0f, 12.0f},
                              {Eigen::Vector3f(0.6f, -0.7f, 0.4f)}),
            1500u);
  // A sensor of another size, or a cloud not organized: no windows.
  core::SensorModel other = sensor;
  other.width = 100;
  options.sensor = other;
  EXPECT_LT(core::SceneIndex(scan, options).pixelSlack(), 0.0f);
  options.sensor = sensor;
  EXPECT_LT(core::SceneIndex(core::dropInvalid(scan), options).pixelSlack(), 0.0f);
}

// Points off their pixel's ray (up to 0.45 px sideways, as a real scan's may lie): the pixel
// windows, which skip the rows and columns whose points all lie farther than the nearest found,
// still give the tree's answers, ties to the lower index included.
TEST(SceneIndex, PixelWindowsGiveTheTreesAnswersWhenPointsLieOffTheirPixels) {
  core::PointCloud scan = floorScan(0.3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> jitter(-0.45f, 0.45f);
  for (auto& p : scan.points_mm)
    if (core::isValid(p)) {
      const float mm_per_px = p.z() / 500.0f;
      p.x() += jitter(rng) * mm_per_px;
      p.y() += jitter(rng) * mm_per_px;
    }
  const core::SensorModel sensor = floorCamera();
  core::SceneIndexOptions options;
  options.sensor = sensor;
  const core::SceneIndex windows(scan, options), tree(scan);
  EXPECT_GT(windows.pixelSlack(), 0.3f);
  EXPECT_LE(windows.pixelSlack(), core::kMaxPixelWindowSlack);
  EXPECT_GT(expectSameNearest(windows, tree, 13, {0.5f, 1.0f, 2.5f, 5.0f},
                              {Eigen::Vector3f(0.6f, -0.7f, 0.4f),
                               Eigen::Vector3f(-1.5f, 0.2f, -0.3f), Eigen::Vector3f::Zero()}),
            3000u);
}

TEST(SceneIndex, OwnNormalsAreUsedAndTurnedTowardsTheViewpoint) {
  auto cloud = core::dropInvalid(floorScan(0.0));
  cloud.normals.assign(cloud.size(), Eigen::Vector3f(0, 0, 1)); // pointing away from the camera
  const core::SceneIndex index(cloud);
  for (const auto& n : index.normals())
    ASSERT_EQ(n, Eigen::Vector3f(0, 0, -1));
}

TEST(SceneIndex, BadOptionsThrow) {
  core::SceneIndexOptions options;
  options.neighbours = 2;
  EXPECT_THROW(core::SceneIndex(floorScan(0.0), options), core::Error);
}

TEST(RefineModel, SubsampleIsEvenDeterministicAndBounded) {
  const auto scan = floorScan(0.1);
  const core::RefineModel a(scan, 500), b(scan, 500);
  EXPECT_LE(a.size(), 500u);
  EXPECT_GT(a.size(), 350u); // the finest grid under the bound fills it well
  EXPECT_GT(a.voxel_mm(), 0.0);
  EXPECT_EQ(a.points(), b.points());
  // Towards the teach camera; 0.1 mm noise over 1.2 mm pixels tilts 3 x 3-window normals a few
  // degrees, so allow 18°.
  for (const auto& n : a.normals())
    EXPECT_LT(n.z(), -0.95f);
  const core::RefineModel all(scan, 1000000);
  EXPECT_EQ(all.voxel_mm(), 0.0);
  EXPECT_THROW(core::RefineModel(core::PointCloud{}, 500), core::Error);
  EXPECT_THROW(core::RefineModel(scan, 0), core::Error);
}

TEST(RefineModel, FromAnIndexedSurfaceItIsTheSameAsFromTheCloud) {
  // The recognizer indexes a view once for verification and refinement: the same model.
  const auto scan = floorScan(0.1);
  const Eigen::Vector3d camera(0, 0, 0);
  core::SceneIndexOptions options;
  options.viewpoint_mm = camera;
  const auto surface = std::make_shared<const core::SceneIndex>(scan, options);
  const core::RefineModel from_cloud(scan, 500, camera), from_index(surface, 500);
  EXPECT_EQ(from_index.points(), from_cloud.points());
  EXPECT_EQ(from_index.normals(), from_cloud.normals());
  EXPECT_EQ(from_index.voxel_mm(), from_cloud.voxel_mm());
  EXPECT_EQ(from_index.radius_mm(), from_cloud.radius_mm());
  EXPECT_EQ(&from_index.surface(), surface.get());
  EXPECT_THROW(core::RefineModel(surface, 2), core::Error);
  EXPECT_THROW(core::RefineModel(std::shared_ptr<const core::SceneIndex>{}, 500), core::Error);
}
