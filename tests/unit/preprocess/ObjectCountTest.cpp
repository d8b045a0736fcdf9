#include "core/preprocess/ObjectCount.h"

#include "core/common/Error.h"
#include "tests/support/RaycastScene.h"

#include <gtest/gtest.h>

using namespace scanpick;

namespace {
// The camera of these tests: 400 x 300 pixels, f = 2000 px, so a pixel spans 0.5 mm at 1 m,
// well inside the 1.5 mm linkage radius; the projector sits 300 mm along +x as on a PhoXi M.
core::SensorModel testSensor(const Eigen::Vector3d& projector_mm) {
  core::SensorModel s;
  s.preset = "custom";
  s.width = 400, s.height = 300, s.fx = s.fy = 2000, s.cx = 199.5, s.cy = 149.5;
  s.T_camera_projector = Eigen::Isometry3d::Identity();
  s.T_camera_projector.translation() = projector_mm;
  return s;
}
const Eigen::Vector3d kProjector(300, 0, 0);
} // namespace

TEST(ObjectCount, CountsSeparatedBoxes) {
  // Four 30 x 30 mm boxes, 20 mm apart, no floor (as after floor removal).
  test::RaycastScene scene;
  for (const auto& c : {Eigen::Vector2d(-45, -30), Eigen::Vector2d(15, -30),
                        Eigen::Vector2d(-45, 25), Eigen::Vector2d(15, 25)})
    scene.boxes.emplace_back(Eigen::Vector3d(c.x() - 15, c.y() - 15, 960),
                             Eigen::Vector3d(c.x() + 15, c.y() + 15, 1000));
  const auto cloud = scene.render(400, 300, 2000, kProjector);
  core::ClusteringParams params;
  params.count_radius_mm = 1.5;
  params.count_min_points = 1000; // each box top holds about 60 x 60 = 3600 pixels
  const auto count = core::countObjects(cloud, testSensor(kProjector), params);
  EXPECT_EQ(count.count, 4);
  ASSERT_GE(count.clusters.size(), 4u);
  std::size_t in_clusters = 0;
  for (const auto& c : count.clusters)
    in_clusters += c.size();
  EXPECT_EQ(in_clusters, cloud.validCount());
  EXPECT_EQ(count.projected_mm.size(), cloud.validCount());
  // Each counted cluster is exactly one box.
  for (int k = 0; k < 4; ++k) {
    const int box =
        scene.labels[static_cast<std::size_t>(count.source_indices[static_cast<std::size_t>(
            count.clusters[static_cast<std::size_t>(k)].front())])];
    for (int j : count.clusters[static_cast<std::size_t>(k)])
      ASSERT_EQ(
          scene.labels[static_cast<std::size_t>(count.source_indices[static_cast<std::size_t>(j)])],
          box);
  }
}

TEST(ObjectCount, ProjectionTowardsTheFartherSourceClosesTheProjectorShadow) {
  // One part: a 10 mm slab (x in [-80, -40]) with a 60 mm pillar on its +x end, at x < 150 so
  // the projector is the farther source. The pillar's projector shadow (about 60 x 380/900
  // = 25 mm long) leaves the slab's top unlit next to the pillar, so in 3D and on the image the
  // pillar top and the slab top are separate pieces; along the projector's rays the last lit
  // slab point and the pillar's edge fall on the same ray and meet again.
  test::RaycastScene scene;
  scene.boxes.emplace_back(Eigen::Vector3d(-80, -20, 990), Eigen::Vector3d(-40, 20, 1000));
  scene.boxes.emplace_back(Eigen::Vector3d(-40, -20, 930), Eigen::Vector3d(-30, 20, 1000));
  const auto cloud = scene.render(400, 300, 2000, kProjector);
  core::ClusteringParams params;
  params.count_radius_mm = 1.5;
  params.count_min_points = 200;

  const auto with_projector = core::countObjects(cloud, testSensor(kProjector), params);
  EXPECT_EQ(with_projector.count, 1) << "the projection along the projector's rays joins the part";

  // The same scan projected along the camera's rays (a sensor whose only source is the camera)
  // keeps the undercut: two pieces.
  const auto camera_only = core::countObjects(cloud, testSensor(Eigen::Vector3d::Zero()), params);
  EXPECT_EQ(camera_only.count, 2);
}

TEST(ObjectCount, EmptyAndBadInput) {
  core::PointCloud empty;
  EXPECT_EQ(core::countObjects(empty, testSensor(kProjector), {}).count, 0);
  core::ClusteringParams params;
  params.count_radius_mm = 0;
  EXPECT_THROW(
      core::countObjects(core::PointCloud::fromPoints({{0, 0, 1}}), testSensor(kProjector), params),
      core::Error);
}

TEST(ObjectCount, ACoordinateFarBeyondAnySceneIsRefusedNotIndexed) {
  // One flipped bit in a float (x = 1.67e20 mm) used to overflow the cell keys and write outside
  // the cell table.
  const auto scene =
      core::PointCloud::fromPoints({{0, 0, 1000}, {1, 0, 1000}, {1.67e20f, 0, 1000}});
  try {
    core::countObjects(scene, testSensor(kProjector), {});
    FAIL() << "expected an Error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not measurements"), std::string::npos) << e.what();
  }
}
