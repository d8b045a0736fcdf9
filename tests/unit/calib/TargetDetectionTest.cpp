// Finding the calibration target in a scan: spheres of the known radius are fitted to within a
// few hundredths of a millimetre, matched to the layout whatever order they are found in, and
// the target's pose follows; a scan without the target says so.
#include "core/calib/TargetDetection.h"

#include "core/common/Error.h"
#include "tests/unit/calib/CalibScenes.h"

#include <gtest/gtest.h>
#include <random>

using namespace scanpick;
using namespace scanpick::core::calib;

namespace {

/// Points on the upper half of a sphere and a plane under it, with Gaussian noise.
core::PointCloud sphereOnPlane(const Eigen::Vector3d& centre, double radius, double sigma,
                               std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 3000; ++i) { // a cap from the top down to 37° below the equator
    Eigen::Vector3d d(u(rng), u(rng), u(rng));
    if (d.norm() > 1 || d.norm() < 0.1)
      continue;
    d.normalize();
    if (d.z() < -0.6)
      continue;
    points.push_back((centre + (radius + noise(rng)) * d).cast<float>());
  }
  for (int i = 0; i < 20000; ++i) // the plate 10 mm below the centre
    points.emplace_back(float(centre.x() + 150 * u(rng)), float(centre.y() + 150 * u(rng)),
                        float(centre.z() - 10 + noise(rng)));
  return core::PointCloud::fromPoints(points);
}

} // namespace

TEST(SphereFit, FindsTheCentreOfANoisySphereOnAPlate) {
  // 0.1 mm noise over ~1,400 points: the centre is known to a few hundredths of a millimetre.
  const Eigen::Vector3d centre(12.3, -40.7, 655.2);
  const auto fits = fitSpheres(sphereOnPlane(centre, 12.5, 0.1, 3), 12.5);
  ASSERT_EQ(fits.size(), 1u);
  EXPECT_LT((fits[0].centre_mm - centre).norm(), 0.03);
  EXPECT_NEAR(fits[0].rms_mm, 0.1, 0.02);
  EXPECT_GT(fits[0].points, 1000);
}

TEST(SphereFit, IgnoresSpheresOfAnotherRadius) {
  EXPECT_TRUE(fitSpheres(sphereOnPlane({0, 0, 700}, 20.0, 0.1, 4), 12.5).empty());
}

TEST(SphereFit, RefinementHoldsTheKnownRadius) {
  // Exact points on a quarter sphere: from a start 1 mm off, the centre comes back exactly.
  std::vector<Eigen::Vector3d> points;
  for (int a = 0; a < 20; ++a)
    for (int b = 0; b < 20; ++b) {
      const double th = 0.08 * a, ph = 0.3 * b;
      points.push_back(Eigen::Vector3d(1, 2, 3) + 10 * Eigen::Vector3d(std::sin(th) * std::cos(ph),
                                                                       std::sin(th) * std::sin(ph),
                                                                       std::cos(th)));
    }
  int inliers = 0;
  double rms = 1;
  const Eigen::Vector3d c =
      refineSphereCentre(points, Eigen::Vector3d(1.5, 2.5, 2.4), 10, 2.0, inliers, rms);
  EXPECT_LT((c - Eigen::Vector3d(1, 2, 3)).norm(), 1e-6);
  EXPECT_EQ(inliers, 400);
  EXPECT_LT(rms, 1e-6);
}

TEST(TargetMatching, AssignsSpheresByTheirDistancesInAnyOrder) {
  const TargetLayout layout = defaultTarget();
  const Eigen::Isometry3d T = test::pose({30, -20, 640}, test::rotation(150, {1, 2, 3}));
  // Found in another order, one missing, a stray sphere added.
  const std::vector<Eigen::Vector3d> fits{T * layout.sphere_centres_mm[2],
                                          {5, 5, 600},
                                          T * layout.sphere_centres_mm[0],
                                          T * layout.sphere_centres_mm[3]};
  EXPECT_EQ(matchSpheres(fits, layout, 2.0), (std::vector<int>{2, -1, 0, 3}));
  // Two spheres are not enough.
  EXPECT_TRUE(matchSpheres({fits[0], fits[2]}, layout, 2.0).empty());
}

TEST(TargetMatching, RigidFitRecoversThePose) {
  const TargetLayout layout = defaultTarget();
  const Eigen::Isometry3d T = test::pose({30, -20, 640}, test::rotation(150, {1, 2, 3}));
  std::vector<Eigen::Vector3d> to;
  for (const auto& c : layout.sphere_centres_mm)
    to.push_back(T * c);
  const Eigen::Isometry3d fit = rigidFit(layout.sphere_centres_mm, to);
  EXPECT_LT((fit.matrix() - T.matrix()).norm(), 1e-9);
}

TEST(TargetDetection, FindsTheTargetInAPhoxiScan) {
  // The virtual PhoXi M 1032 with its noise (σ 0.1 mm, dropouts, flying pixels) sees the target
  // tilted 10-30° at about 650 mm: all four spheres, the pose within 0.03 mm and 0.01°.
  const auto cell = test::eyeToHandCell(3, 7);
  const auto mesh = test::targetMesh(defaultTarget());
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    const TargetObservation obs = detectTarget(test::scanOf(cell, i, mesh), defaultTarget());
    EXPECT_EQ(obs.found(), 4);
    const Eigen::Isometry3d& truth = cell.T_camera_target[std::size_t(i)];
    EXPECT_LT(test::distanceBetween_mm(obs.T_camera_target, truth), 0.03);
    EXPECT_LT(test::angleBetween_deg(obs.T_camera_target, truth), 0.01);
    EXPECT_LT(obs.fit_rms_mm, 0.03);
    // The sensor's noise, nothing more: σ = 0.1 mm along the ray, less across the sphere's
    // surface where the ray meets it at a slant.
    for (const double rms : obs.sphere_rms_mm) {
      EXPECT_GT(rms, 0.04);
      EXPECT_LT(rms, 0.1);
    }
  }
}

TEST(TargetDetection, AScanWithoutTheTargetSaysWhatToCheck) {
  const auto cell = test::eyeInHandCell(1, 8);
  const auto scan = test::scanOf(cell, 0, test::targetMesh(defaultTarget()), true, false);
  try {
    detectTarget(scan, defaultTarget());
    FAIL() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no sphere of radius 12.5 mm found"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("in view"), std::string::npos) << e.what();
  }
}
