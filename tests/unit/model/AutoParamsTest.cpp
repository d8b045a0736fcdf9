#include "core/model/AutoParams.h"

#include "core/common/Error.h"
#include "core/model/TaughtModel.h"
#include "core/params/ParameterTable.h"
#include "tests/support/RaycastScene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <gtest/gtest.h>
#include <optional>
#include <random>

using namespace scanpick;
using namespace scanpick::core;

namespace {

/// Points spread over the surface of a box of the given size centred at the origin.
PointCloud boxSurface(const Eigen::Vector3f& size_mm, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(-0.5f, 0.5f);
  std::uniform_int_distribution<int> face(0, 5);
  PointCloud cloud;
  for (std::size_t i = 0; i < count; ++i) {
    Eigen::Vector3f p(unit(rng), unit(rng), unit(rng));
    const int f = face(rng);
    p[f / 2] = f % 2 ? 0.5f : -0.5f;
    cloud.points_mm.push_back(p.cwiseProduct(size_mm));
  }
  cloud.width = static_cast<std::uint32_t>(count);
  cloud.height = 1;
  return cloud;
}

/// The table on its own, 1000 mm from a camera of focal length 300 px: 3.33 mm point spacing.
PointCloud tableScan(double noise_mm) {
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  return scene.render(200, 150, 300.0, {0, 0, 0}, noise_mm, 3);
}

/// A 150 x 100 x 30 mm block on a table 1000 mm away, camera looking straight down.
PointCloud blockOnTable() {
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-75, -50, 970), Eigen::Vector3d(75, 50, 1000));
  return scene.render(400, 300, 600.0, {300, 0, 0}, 0.1, 4);
}

} // namespace

TEST(AutoParams, MeasuresTheSpacingAndNoiseOfAScan) {
  const ScanMeasures quiet = measureScan(tableScan(0.0));
  EXPECT_NEAR(quiet.spacing_mm, 1000.0 / 300.0, 0.05);
  EXPECT_LT(quiet.noise_mm, 0.01);
  const ScanMeasures noisy = measureScan(tableScan(0.5));
  EXPECT_NEAR(noisy.spacing_mm, 1000.0 / 300.0, 0.2);
  EXPECT_GT(noisy.noise_mm, 0.3);
  EXPECT_LT(noisy.noise_mm, 0.6);
  PointCloud few;
  few.points_mm.assign(5, Eigen::Vector3f(1, 2, 3));
  few.width = 5;
  few.height = 1;
  EXPECT_THROW(measureScan(few), Error);
}

TEST(AutoParams, TheDiameterIsTheLargestDistanceBetweenTwoPoints) {
  for (const std::uint64_t seed : {3u, 4u, 5u}) {
    PointCloud part = boxSurface({70, 45, 12}, 3000, seed);
    // A bump on one corner, so the farthest pair is not a pair of the box's corners.
    part.points_mm.push_back({37, 24, 8});
    part.width += 1;
    double brute_force = 0;
    for (const auto& p : part.points_mm)
      for (const auto& q : part.points_mm)
        brute_force = std::max(brute_force, (p - q).cast<double>().norm());
    EXPECT_NEAR(measurePart(part, 50.0).diameter_mm, brute_force, 1e-9) << "seed " << seed;
  }
}

TEST(AutoParams, TheDiameterAndTheDerivedValuesDoNotDependOnTheYaw) {
  const Eigen::Vector3f size(120, 60, 20);
  const PointCloud part = boxSurface(size, 20000, 1);
  const double diagonal = size.cast<double>().norm();
  const ScanMeasures scan{0.7, 0.1};
  const AutoParams first = deriveParams(scan, measurePart(part, scan.spacing_mm));
  EXPECT_NEAR(first.part.diameter_mm, diagonal, 0.01 * diagonal);
  EXPECT_NEAR(first.part.extent_mm.x(), 120.0, 1.0);
  EXPECT_NEAR(first.part.extent_mm.y(), 60.0, 1.0);
  EXPECT_NEAR(first.part.extent_mm.z(), 20.0, 1.0);
  for (int step = 1; step < 24; ++step) {
    SCOPED_TRACE("yaw " + std::to_string(15 * step) + " deg");
    const Eigen::Isometry3f T(Eigen::AngleAxisf(float(step * M_PI / 12), Eigen::Vector3f::UnitZ()));
    const AutoParams turned =
        deriveParams(scan, measurePart(transformed(part, T), scan.spacing_mm));
    EXPECT_NEAR(turned.part.diameter_mm, first.part.diameter_mm, 1e-4);
    ASSERT_EQ(turned.values.size(), first.values.size());
    for (std::size_t i = 0; i < first.values.size(); ++i)
      EXPECT_NEAR(turned.values[i].value, first.values[i].value,
                  1e-5 * std::abs(first.values[i].value) + 1e-9)
          << first.values[i].key;
  }
}

TEST(AutoParams, FlyingPixelsDoNotEnlargeThePart) {
  PointCloud part = boxSurface({40, 30, 10}, 5000, 2);
  const double clean = measurePart(part, 0.5).diameter_mm;
  part.points_mm.push_back({300, 0, 0});
  part.points_mm.push_back({0, -250, 40});
  part.width += 2;
  EXPECT_NEAR(measurePart(part, 0.5).diameter_mm, clean, 1e-6);
}

TEST(AutoParams, ValuesFollowTheScanAndThePartWithAReasonEach) {
  PartMeasures part;
  part.diameter_mm = 150.0;
  part.points = 20000;
  const AutoParams fine = deriveParams({0.7, 0.1}, part);
  const AutoParams coarse = deriveParams({2.0, 1.5}, part); // a Kinect-class scan
  const auto value = [](const AutoParams& a, const std::string& key) {
    return findParameter(key)->get(a.params);
  };
  // Neighbourhoods scale with the spacing; tolerances keep above the noise; the surface sampling
  // scales with the part.
  EXPECT_NEAR(value(coarse, "keypoints.neighbourhood_radius_mm") /
                  value(fine, "keypoints.neighbourhood_radius_mm"),
              2.0 / 0.7, 1e-9);
  EXPECT_GE(value(coarse, "matching.verify_tolerance_mm"), 5 * 1.5);
  EXPECT_GE(value(coarse, "floor.distance_mm"), 8 * 1.5);
  EXPECT_NEAR(value(fine, "matching.surface_sampling_mm"), 0.035 * 150.0, 1e-9);
  part.diameter_mm = 25.0;
  part.points = 400;
  const AutoParams small = deriveParams({0.7, 0.1}, part);
  EXPECT_LT(value(small, "features.ransac_size"), value(fine, "features.ransac_size"));
  EXPECT_LT(value(small, "clustering.count_min_points"), 100.0);
  EXPECT_GE(value(small, "matching.surface_sampling_mm"), 2.5 * 0.7);
  EXPECT_EQ(value(fine, "refine.enabled"), 1.0);
  for (const AutoParams* a : {&fine, &coarse, &small})
    for (const auto& v : a->values) {
      EXPECT_FALSE(v.reason.empty()) << v.key;
      EXPECT_NO_THROW(checkParamValue(*findParameter(v.key), v.value)) << v.key;
      EXPECT_EQ(value(*a, v.key), v.value) << v.key;
    }
}

TEST(AutoParams, AThinPlateLyingFlatStaysAboveTheFloorDistance) {
  // A 60 x 40 x 1.5 mm plate on the table: the floor distance the spacing asks (3 x 1.67 mm) would
  // take the plate with the table; half its height above the table keeps it.
  test::RaycastScene scene;
  scene.floor_z_mm = 1000.0;
  scene.boxes.emplace_back(Eigen::Vector3d(-30, -20, 998.5), Eigen::Vector3d(30, 20, 1000));
  const PointCloud scan = scene.render(400, 300, 600.0, {300, 0, 0}, 0.05, 4);
  TeachOptions options;
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-40, -30, 900), Eigen::Vector3f(40, 30, 1010));
  options.remove_floor = true;
  const AutoParams a = autoTeachParams(scan, options);
  EXPECT_NEAR(a.scan.part_layer_mm, 1.5, 0.3);
  EXPECT_NEAR(a.params.floor.distance_mm, 0.75, 0.15);
  const auto floor = std::find_if(a.values.begin(), a.values.end(), [](const DerivedValue& v) {
    return v.key == "floor.distance_mm";
  });
  ASSERT_NE(floor, a.values.end());
  EXPECT_NE(floor->reason.find("lowest face"), std::string::npos) << floor->reason;
  EXPECT_NEAR(a.part.diameter_mm, Eigen::Vector2d(60, 40).norm(), 5.0);
  // A 30 mm block keeps the distance the spacing asks.
  const AutoParams block = autoTeachParams(blockOnTable(), [] {
    TeachOptions o;
    o.crop_box_mm =
        Eigen::AlignedBox3f(Eigen::Vector3f(-90, -65, 900), Eigen::Vector3f(90, 65, 1010));
    o.remove_floor = true;
    return o;
  }());
  EXPECT_NEAR(block.params.floor.distance_mm, 3.0 * block.scan.spacing_mm, 0.01);
}

TEST(AutoParams, TeachMeasuresThePartWithoutItsTable) {
  // The block cropped with the table inside the box.
  const PointCloud scan = blockOnTable();
  TeachOptions options;
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-90, -65, 900), Eigen::Vector3f(90, 65, 1010));
  options.remove_floor = true;
  const AutoParams a = autoTeachParams(scan, options);
  EXPECT_NEAR(a.scan.spacing_mm, 1000.0 / 600.0, 0.15);
  // The block's visible top and side faces span its diagonal (the table went with the floor).
  EXPECT_NEAR(a.part.diameter_mm, Eigen::Vector3d(150, 100, 30).norm(), 6.0);
  EXPECT_EQ(findParameter("refine.enabled")->get(a.params), 1.0);
}

TEST(AutoParams, TeachingOneScanTurnedInSteps) {
  // One scan of a block on a table, turned about the table's normal through the block in 15°
  // steps: teach derives the same diameter and the same values at every yaw, and the model it
  // teaches keeps that diameter.
  const PointCloud scan = blockOnTable();
  TeachOptions options;
  options.remove_floor = true;
  const Eigen::Vector3f centre(0, 0, 985);
  std::optional<AutoParams> first;
  double first_model_diameter_mm = 0.0;
  for (int step = 0; step < 24; ++step) {
    SCOPED_TRACE("yaw " + std::to_string(15 * step) + " deg");
    const Eigen::Isometry3f T =
        Eigen::Translation3f(centre) *
        Eigen::AngleAxisf(float(step * M_PI / 12), Eigen::Vector3f::UnitZ()) *
        Eigen::Translation3f(-centre);
    const PointCloud turned = transformed(scan, T);
    // The crop box turns with the scan, so it holds the same points at every yaw.
    options.crop_oriented = OrientedBox{T * Eigen::Translation3f(0, 0, 955), {90, 65, 55}};
    const AutoParams a = autoTeachParams(turned, options);
    const double model_diameter_mm = teach(turned, options, a.params).diameter_mm;
    if (!first) {
      first = a;
      first_model_diameter_mm = model_diameter_mm;
      EXPECT_NEAR(a.part.diameter_mm, Eigen::Vector3d(150, 100, 30).norm(), 6.0);
      EXPECT_NEAR(model_diameter_mm, a.part.diameter_mm, 0.05 * a.part.diameter_mm);
      continue;
    }
    EXPECT_NEAR(a.part.diameter_mm, first->part.diameter_mm, 1e-3);
    EXPECT_NEAR(model_diameter_mm, first_model_diameter_mm, 1e-3);
    ASSERT_EQ(a.values.size(), first->values.size());
    for (std::size_t i = 0; i < a.values.size(); ++i)
      EXPECT_NEAR(a.values[i].value, first->values[i].value,
                  1e-4 * std::abs(first->values[i].value) + 1e-9)
          << a.values[i].key;
  }
}
