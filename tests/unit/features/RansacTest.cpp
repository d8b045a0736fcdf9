#include "core/features/Ransac.h"

#include <cmath>
#include <gtest/gtest.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_circle3d.h>
#include <pcl/sample_consensus/sac_model_line.h>
#include <random>

using namespace scanpick::core;

namespace {
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// A line and a circle (mm) with noise, among uniformly scattered outliers.
Cloud::Ptr lineCircleAndClutter() {
  std::mt19937_64 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.2f);
  std::uniform_real_distribution<float> box(-60.0f, 60.0f);
  auto cloud = std::make_shared<Cloud>();
  for (int i = 0; i < 120; ++i)
    cloud->push_back(
        {-50.0f + 0.8f * float(i) + noise(rng), 10.0f + noise(rng), 600.0f + noise(rng)});
  for (int i = 0; i < 150; ++i) {
    const float a = 6.2831853f * float(i) / 150.0f;
    cloud->push_back({20.0f + 25.0f * std::cos(a) + noise(rng),
                      -20.0f + 25.0f * std::sin(a) + noise(rng), 620.0f + noise(rng)});
  }
  for (int i = 0; i < 200; ++i)
    cloud->push_back({box(rng), box(rng), 600.0f + box(rng)});
  return cloud;
}

/// pcl::RandomSampleConsensus's coefficients for a fresh model of type M (PCL seeds each model's
/// sampler with the same constant, so a second fresh model draws the same samples).
template <typename M>
Eigen::VectorXf pclCoefficients(const Cloud::Ptr& cloud, double threshold, int iterations) {
  auto model = std::make_shared<M>(cloud);
  pcl::RandomSampleConsensus<pcl::PointXYZ> sac(model, threshold);
  sac.setMaxIterations(iterations);
  EXPECT_TRUE(sac.computeModel());
  Eigen::VectorXf c;
  sac.getModelCoefficients(c);
  return c;
}
} // namespace

TEST(Ransac, FindsTheSameLineAndCircleAsPclsRansac) {
  const auto cloud = lineCircleAndClutter();
  for (const int iterations : {5, 50, 1000}) {
    SCOPED_TRACE(iterations);
    pcl::SampleConsensusModelLine<pcl::PointXYZ> line(cloud);
    Eigen::VectorXf ours;
    ASSERT_TRUE(ransacModel(line, 0.5, iterations, ours));
    EXPECT_EQ(ours, (pclCoefficients<pcl::SampleConsensusModelLine<pcl::PointXYZ>>(cloud, 0.5,
                                                                                   iterations)));

    pcl::SampleConsensusModelCircle3D<pcl::PointXYZ> circle(cloud);
    ASSERT_TRUE(ransacModel(circle, 0.5, iterations, ours));
    EXPECT_EQ(ours, (pclCoefficients<pcl::SampleConsensusModelCircle3D<pcl::PointXYZ>>(
                        cloud, 0.5, iterations)));
  }
  // With enough trials the best circle is the one put there.
  pcl::SampleConsensusModelCircle3D<pcl::PointXYZ> circle(cloud);
  Eigen::VectorXf c;
  ASSERT_TRUE(ransacModel(circle, 0.5, 1000, c));
  EXPECT_NEAR(c[3], 25.0, 0.5);
  EXPECT_LT((c.head<3>() - Eigen::Vector3f(20, -20, 620)).norm(), 0.5f);
}

TEST(Ransac, TooFewPointsFindNoModel) {
  auto cloud = std::make_shared<Cloud>();
  cloud->push_back({0, 0, 600});
  cloud->push_back({1, 0, 600});
  pcl::SampleConsensusModelCircle3D<pcl::PointXYZ> circle(cloud); // needs three points
  Eigen::VectorXf c;
  EXPECT_FALSE(ransacModel(circle, 0.5, 100, c));
}
