// Verification knows the floor (beyond the thesis): a pose that sinks a part into the table it
// lies on is contradicted there, although the camera cannot see through the table to say so.
#include "tests/integration/SynthTeach.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;

TEST(FloorVerification, APoseSunkIntoTheTableIsContradicted) {
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  // Another scan of the support on a table, resting as taught.
  const test::VerifyCase c = test::verifyCase("support", params, 5, 9, 0);
  ASSERT_FALSE(c.floor.planes.empty());
  // 20 mm deeper along the table's normal (it points towards the camera).
  const Eigen::Vector3d down = -c.floor.planes.front().head<3>().cast<double>();
  const Eigen::Isometry3d T_sunk = Eigen::Translation3d(20.0 * down) * c.T_true;
  const VerifyScene blind{c.index.get(), &c.scan.render.cloud, &c.scan.sensor, std::nullopt};
  const VerifyScene knowing{c.index.get(), &c.scan.render.cloud, &c.scan.sensor,
                            c.floor.planes.front()};
  const double tolerance = params.matching.verify_tolerance_mm;
  const PointTally true_blind = tallyPoints(*c.view, blind, c.T_true, tolerance);
  const PointTally true_knowing = tallyPoints(*c.view, knowing, c.T_true, tolerance);
  const PointTally sunk_blind = tallyPoints(*c.view, blind, T_sunk, tolerance);
  const PointTally sunk_knowing = tallyPoints(*c.view, knowing, T_sunk, tolerance);
  std::printf("true pose: %zu of %zu confirmed, %zu / %zu violations without / with the floor; "
              "sunk 20 mm: %zu hidden without the floor, %zu violations with it\n",
              true_knowing.confirmed, true_knowing.points, true_blind.violations,
              true_knowing.violations, sunk_blind.hidden, sunk_knowing.violations);
  // The true pose rests on the table: the floor changes nothing.
  EXPECT_EQ(true_knowing.confirmed, true_blind.confirmed);
  EXPECT_EQ(true_knowing.violations, true_blind.violations);
  EXPECT_GT(true_knowing.confirmed, true_knowing.points * 9 / 10);
  // Sunk, most points lie under the table: without the floor they are only hidden behind it.
  EXPECT_GT(sunk_blind.hidden, sunk_blind.points / 2);
  EXPECT_GT(sunk_knowing.violations, sunk_knowing.points / 2);
  EXPECT_EQ(verifyPose(*c.view, knowing, T_sunk, tolerance, {}), 0.0);
  EXPECT_GT(verifyPose(*c.view, knowing, c.T_true, tolerance, {}), 0.9);
}

/// A scan of the support resting on a table as taught, its floor known.
class VerificationDropBelow : public ::testing::Test {
protected:
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::VerifyCase c = test::verifyCase("support", params, 5, 9, 0);
  const VerifyScene scene{c.index.get(), &c.scan.render.cloud, &c.scan.sensor,
                          c.floor.planes.front()};
  const double tolerance = params.matching.verify_tolerance_mm;
};

// A search that drops every pose scoring under a bound lets verification skip those poses' edge
// check: under the bound a pose gets its surface score or less than the bound that its points
// could still reach (never lower than its full score), from the bound up always the full score.
// Here the only scene keypoints lie 5 m away, so no model keypoint finds one and the full score
// is 0.
TEST_F(VerificationDropBelow, OnlyPosesUnderTheBoundSkipTheEdgeCheck) {
  const SceneIndex far_keypoints(PointCloud::fromPoints(
      {Eigen::Vector3f(0, 0, 5000), Eigen::Vector3f(10, 0, 5000), Eigen::Vector3f(0, 10, 5000)}));
  const EdgeCheck edges{&far_keypoints, 2.0};
  const double surface = verifyPose(*c.view, scene, c.T_true, tolerance, {});
  ASSERT_GT(surface, 0.9);
  EXPECT_EQ(verifyPose(*c.view, scene, c.T_true, tolerance, edges), 0.0);
  EXPECT_EQ(verifyPose(*c.view, scene, c.T_true, tolerance, edges, 0.7), 0.0)
      << "a surface score over the bound gets the edge check";
  const double under = verifyPose(*c.view, scene, c.T_true, tolerance, edges, 1.01);
  EXPECT_GE(under, surface) << "a score under the bound is never lower than the surface score";
  EXPECT_LT(under, 1.01);
}

// Verification under a bound stops looking at a pose's points once they cannot reach it, with the
// verdict and the full scores unchanged: a pose 30 mm off is dropped after part of its points,
// the true pose looks at all of them.
TEST_F(VerificationDropBelow, APoseThatCannotReachTheBoundStopsEarlyWithTheSameVerdict) {
  const Eigen::Isometry3d T_off = Eigen::Translation3d(30.0, 0.0, 0.0) * c.T_true;
  const std::size_t all = c.view->points.size();
  for (const double bound : {0.3, 0.6}) {
    const auto cannot_reach = [&](const PointTally& so_far, std::size_t left) {
      return surfaceScoreBound(so_far, left) < bound;
    };
    const PointTally off =
        tallyPoints(*c.view, scene, T_off, tolerance,
                    {.subset = nullptr, .stop = cannot_reach, .sort_unmeasured = true});
    const PointTally at_truth =
        tallyPoints(*c.view, scene, c.T_true, tolerance,
                    {.subset = nullptr, .stop = cannot_reach, .sort_unmeasured = true});
    std::printf("bound %.1f: the pose 30 mm off stopped after %zu of %zu points\n", bound,
                off.points, all);
    EXPECT_LT(off.points, all);
    EXPECT_EQ(at_truth.points, all);
    const double full_off = verifyPose(*c.view, scene, T_off, tolerance, {});
    const double off_score = verifyPose(*c.view, scene, T_off, tolerance, {}, bound);
    EXPECT_LT(full_off, bound);
    EXPECT_LT(off_score, bound);
    EXPECT_GE(off_score, full_off);
    EXPECT_EQ(verifyPose(*c.view, scene, c.T_true, tolerance, {}, bound),
              verifyPose(*c.view, scene, c.T_true, tolerance, {}));
  }
  // With nothing looked at yet the bound is 1; with every point looked at it is still no lower
  // than the surface score (it takes the expected count at its lowest).
  EXPECT_EQ(surfaceScoreBound(PointTally{}, all), 1.0);
  const PointTally full = tallyPoints(*c.view, scene, c.T_true, tolerance);
  EXPECT_GE(surfaceScoreBound(full, 0), verifyPose(*c.view, scene, c.T_true, tolerance, {}));
}
