#include "core/matching/FeatureMatcher.h"

#include "core/common/Error.h"

#include <gtest/gtest.h>
#include <random>
#include <tbb/task_arena.h>

using namespace scanpick::core;

namespace {

/// A part with two circles and four lines in a layout without symmetry (sizes in mm).
FeatureList testPart() {
  return {
      {FeatureType::Circle, {0, 0, 0}, {0, 0, 1}, 10.0f, 60},
      {FeatureType::Circle, {45, 10, 5}, Eigen::Vector3f(0, 1, 1).normalized(), 15.0f, 80},
      {FeatureType::Line, {20, -30, 0}, {1, 0, 0}, 40.0f, 40},
      {FeatureType::Line, {-25, 5, 10}, {0, 1, 0}, 60.0f, 60},
      {FeatureType::Line, {10, 35, -5}, Eigen::Vector3f(1, 1, 0).normalized(), 25.0f, 25},
      {FeatureType::Line, {60, -15, 20}, {0, 0, 1}, 50.0f, 50},
  };
}

/// A different part: other sizes, another layout.
FeatureList otherPart() {
  return {
      {FeatureType::Circle, {0, 0, 0}, {1, 0, 0}, 30.0f, 60},
      {FeatureType::Line, {0, 80, 0}, {0, 0, 1}, 120.0f, 40},
      {FeatureType::Line, {70, 0, 0}, {0, 1, 0}, 90.0f, 60},
      {FeatureType::Line, {-60, -40, 0}, {1, 0, 0}, 10.0f, 25},
  };
}

Eigen::Isometry3d pose(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

/// Moves features by T; flips every other axis, since the extractor's signs are arbitrary.
FeatureList moved(const FeatureList& features, const Eigen::Isometry3d& T) {
  FeatureList out = features;
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].centre_mm = (T * features[i].centre_mm.cast<double>()).cast<float>();
    const Eigen::Vector3d d = T.linear() * features[i].direction.cast<double>();
    out[i].direction = ((i % 2 == 0) ? d : Eigen::Vector3d(-d)).cast<float>();
  }
  return out;
}

MatchingParams idealParams() {
  MatchingParams p; // thesis table 5.1
  p.length_tolerance_mm = 10.0;
  p.radius_tolerance_mm = 10.0;
  p.position_tolerance_mm = 2.0;
  p.orientation_tolerance_rad = 0.25;
  p.score_threshold = 0.5;
  return p;
}

double rotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

} // namespace

TEST(FeatureMatcher, RecoversAKnownTransformExactlyWithFullScore) {
  const Eigen::Isometry3d T = pose(2.0 * M_PI / 5.0, {0.3, -1, 0.5}, {120, -40, 700});
  const auto best = findBestTransformation(testPart(), moved(testPart(), T), idealParams());
  ASSERT_TRUE(best);
  EXPECT_DOUBLE_EQ(best->score, 1.0);
  EXPECT_EQ(best->matched_features.size(), 6u);
  EXPECT_LT((best->T_scene_model.translation() - T.translation()).norm(), 1e-3);
  EXPECT_LT(rotationErrorDeg(best->T_scene_model, T), 1e-3);
  for (const auto& [m, s] : best->matched_features)
    EXPECT_EQ(m, s); // a perfect copy matches index to index
}

TEST(FeatureMatcher, ToleratesNoisyFeatures) {
  const Eigen::Isometry3d T = pose(4.0 * M_PI / 5.0, {1, 0, 0}, {-50, 20, 500});
  FeatureList scene = moved(testPart(), T);
  std::mt19937_64 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.3f);
  for (auto& f : scene) {
    f.centre_mm += Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
    f.direction =
        (f.direction + 0.01f * Eigen::Vector3f(noise(rng), noise(rng), noise(rng))).normalized();
    f.size_mm += noise(rng);
  }
  const auto best = findBestTransformation(testPart(), scene, idealParams());
  ASSERT_TRUE(best);
  EXPECT_DOUBLE_EQ(best->score, 1.0);
  // The refinement on all six pairs averages the 0.3 mm centre noise.
  EXPECT_LT((best->T_scene_model.translation() - T.translation()).norm(), 0.5);
  EXPECT_LT(rotationErrorDeg(best->T_scene_model, T), 1.0);
}

TEST(FeatureMatcher, FindsTwoInstancesInOneCluster) {
  const Eigen::Isometry3d Ta = pose(M_PI / 5.0, {0, 1, 0}, {0, 0, 600});
  const Eigen::Isometry3d Tb = pose(3.0 * M_PI / 5.0, {0, 0, 1}, {90, 30, 640});
  FeatureList scene = moved(testPart(), Ta);
  const FeatureList b = moved(testPart(), Tb);
  scene.insert(scene.end(), b.begin(), b.end());
  const auto found = matchFeatures(testPart(), scene, idealParams());
  ASSERT_EQ(found.size(), 2u);
  int hits_a = 0, hits_b = 0;
  for (const auto& c : found) {
    EXPECT_DOUBLE_EQ(c.score, 1.0);
    hits_a += (c.T_scene_model.translation() - Ta.translation()).norm() < 1e-3;
    hits_b += (c.T_scene_model.translation() - Tb.translation()).norm() < 1e-3;
  }
  EXPECT_EQ(hits_a, 1);
  EXPECT_EQ(hits_b, 1);
}

TEST(FeatureMatcher, RejectsADifferentPart) {
  const auto scene = moved(otherPart(), pose(0.4, {1, 1, 0}, {0, 0, 600}));
  const auto found = matchFeatures(testPart(), scene, idealParams());
  EXPECT_TRUE(found.empty());
  // Without a threshold the best it can do still confirms few model features.
  const auto best = findBestTransformation(testPart(), scene, idealParams());
  if (best) {
    EXPECT_LT(best->score, 0.5);
  }
}

TEST(FeatureMatcher, ParallelLinesOnOneAxisGiveNoRoll) {
  // Two collinear lines constrain no roll about their axis: no pose is invented.
  const FeatureList model{{FeatureType::Line, {0, 0, 0}, {1, 0, 0}, 40.0f, 40},
                          {FeatureType::Line, {60, 0, 0}, {1, 0, 0}, 30.0f, 30}};
  const auto scene = moved(model, pose(0.3, {0, 0, 1}, {10, 0, 500}));
  EXPECT_FALSE(findBestTransformation(model, scene, idealParams()));
}

TEST(FeatureMatcher, SameResultWhateverTheThreadCount) {
  const Eigen::Isometry3d Ta = pose(M_PI / 5.0, {1, 0, 0}, {0, 0, 600});
  FeatureList scene = moved(testPart(), Ta);
  const auto other = moved(otherPart(), pose(1.0, {0, 1, 0}, {20, 10, 610}));
  scene.insert(scene.end(), other.begin(), other.end());
  const auto many = matchFeatures(testPart(), scene, idealParams());
  std::vector<MatchCandidate> one;
  tbb::task_arena single(1);
  single.execute([&] { one = matchFeatures(testPart(), scene, idealParams()); });
  ASSERT_EQ(many.size(), one.size());
  ASSERT_FALSE(many.empty());
  for (std::size_t i = 0; i < many.size(); ++i) {
    EXPECT_EQ(many[i].T_scene_model.matrix(), one[i].T_scene_model.matrix()); // bitwise
    EXPECT_EQ(many[i].matched_features, one[i].matched_features);
    EXPECT_EQ(many[i].seed1, one[i].seed1);
  }
}

TEST(FeatureMatcher, ScoreCountsConfirmedFeatures) {
  const Eigen::Isometry3d T = pose(0.5, {0, 0, 1}, {0, 0, 500});
  FeatureList scene = moved(testPart(), T);
  scene.erase(scene.begin() + 2); // one line missing: 5 of 6 model features confirmed
  const auto c = scoreTransformation(testPart(), scene, T, idealParams());
  EXPECT_NEAR(c.score, 5.0 / 6.0, 1e-12);
}

TEST(FeatureMatcher, CancelsWhenAsked) {
  const auto scene = moved(testPart(), pose(0.5, {0, 0, 1}, {0, 0, 500}));
  EXPECT_THROW(
      findBestTransformation(testPart(), scene, idealParams(), {}, [](double) { return false; }),
      Cancelled);
}
