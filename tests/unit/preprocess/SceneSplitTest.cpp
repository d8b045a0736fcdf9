#include "core/preprocess/SceneSplit.h"

#include "tests/support/RaycastScene.h"

#include <gtest/gtest.h>
#include <map>

using namespace scanpick;

namespace {
core::SensorModel sensor() {
  auto s = core::sensorPreset("phoxi-m-1032");
  return s;
}
// A flat 40 x 40 mm patch of points every 0.5 mm at depth z.
void addPatch(std::vector<Eigen::Vector3f>& pts, float x0, float y0, float z, float size = 40) {
  for (float x = 0; x < size; x += 0.5f)
    for (float y = 0; y < size; y += 0.5f)
      pts.emplace_back(x0 + x, y0 + y, z);
}
} // namespace

TEST(SceneSplit, KMeansRemovesATwoPointOutlierClusterAndReRuns) {
  // Two 40 mm patches 60 mm apart and two stray points 2 m away. Farthest-first seeding puts a
  // centre on the strays, so the first k-means run (k = 2, the count) makes a 2-point cluster;
  // the thesis removes it and clusters again, which then separates the patches.
  std::vector<Eigen::Vector3f> pts;
  addPatch(pts, -100, -20, 800);
  addPatch(pts, 0, -20, 800);
  const std::size_t patch = pts.size() / 2;
  pts.emplace_back(2000, 0, 800);
  pts.emplace_back(2000.5f, 0, 800);
  core::ClusteringParams params;
  params.count_min_points = 1000;
  const auto split =
      core::splitIntoObjects(core::PointCloud::fromPoints(pts), sensor(), params, 42);
  EXPECT_EQ(split.count.count, 2);
  EXPECT_EQ(split.kmeans_runs, 2);
  ASSERT_EQ(split.objects.size(), 2u);
  EXPECT_EQ(split.objects[0].size(), patch);
  EXPECT_EQ(split.objects[1].size(), patch);
  EXPECT_EQ(split.point_labels[pts.size() - 1], -1);
  EXPECT_EQ(split.point_labels[pts.size() - 2], -1);
  EXPECT_NE(split.point_labels[0], split.point_labels[patch]);

  params.enabled = false;
  const auto whole =
      core::splitIntoObjects(core::PointCloud::fromPoints(pts), sensor(), params, 42);
  ASSERT_EQ(whole.objects.size(), 1u);
  EXPECT_EQ(whole.objects[0].size(), pts.size());
}

TEST(SceneSplit, ProjectedClustersKeepALongPartApartFromASmallOne) {
  // A 200 x 20 mm bar and a 20 x 20 mm block 10 mm beside its end, rendered from 1 m. The count
  // is 2; k-means (k = 2) minimises squared distances, so it cuts the bar in two and gives one
  // half to the block: its objects mix parts. The projected clusters are the parts themselves.
  test::RaycastScene scene;
  scene.boxes.emplace_back(Eigen::Vector3d(-120, -10, 980), Eigen::Vector3d(80, 10, 1000));
  scene.boxes.emplace_back(Eigen::Vector3d(90, -10, 980), Eigen::Vector3d(110, 10, 1000));
  const auto cloud = scene.render(500, 120, 2000, {300, 0, 0});
  core::SensorModel s = sensor();
  core::ClusteringParams params;
  params.count_min_points = 500;

  const auto purity = [&](const core::SceneSplit& split) {
    // Share of points that sit in an object whose majority part is their own part.
    std::size_t agree = 0, total = 0;
    for (std::size_t o = 0; o < split.objects.size(); ++o) {
      std::map<int, std::size_t> parts;
      for (std::size_t i = 0; i < cloud.size(); ++i)
        if (split.point_labels[i] == static_cast<int>(o))
          ++parts[scene.labels[i]];
      std::size_t best = 0;
      for (const auto& [part, n] : parts) {
        best = std::max(best, n);
        total += n;
      }
      agree += best;
    }
    return static_cast<double>(agree) / static_cast<double>(total);
  };

  const auto kmeans = core::splitIntoObjects(cloud, s, params, 42);
  params.method = core::ClusteringParams::Method::ProjectedClusters;
  const auto projected = core::splitIntoObjects(cloud, s, params, 42);
  EXPECT_EQ(kmeans.count.count, 2);
  ASSERT_EQ(projected.objects.size(), 2u);
  EXPECT_DOUBLE_EQ(purity(projected), 1.0);
  EXPECT_LT(purity(kmeans), 0.95)
      << "k-means splits the bar (the thesis's method, kept as default)";
  // Organized input: each object is its bounding pixel window, still organized.
  EXPECT_TRUE(projected.objects[0].isOrganized());
  EXPECT_LT(projected.objects[0].size(), cloud.size());
  EXPECT_EQ(projected.objects[0].validCount() + projected.objects[1].validCount(),
            cloud.validCount());
}
