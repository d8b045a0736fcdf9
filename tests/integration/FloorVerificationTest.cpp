// Verification knows the floor (beyond the thesis): a pose that sinks a part into the table it
// lies on is contradicted there, although the camera cannot see through the table to say so.
#include "core/pipeline/PoseVerification.h"
#include "core/preprocess/FloorRemoval.h"
#include "tests/integration/SynthTeach.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;

TEST(FloorVerification, APoseSunkIntoTheTableIsContradicted) {
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::SynthTeach taught = test::teachFromSynth("support", 5, params, 0);
  // Another scan of the support on a table, resting as taught.
  const SynthScene scan = test::teachScan("support", 9, 0);
  const Eigen::Isometry3d T_true =
      scan.scene.T_scene_part(scan.scene.instances.at(0)) * taught.T_part_model();
  const FloorRemovalResult floor = removeFloor(scan.render.cloud, params.floor, params.seed);
  ASSERT_FALSE(floor.planes.empty());
  // 20 mm deeper along the table's normal (it points towards the camera).
  const Eigen::Vector3d down = -floor.planes.front().head<3>().cast<double>();
  const Eigen::Isometry3d T_sunk = Eigen::Translation3d(20.0 * down) * T_true;

  const auto view =
      makeVerifyModel(*taught.model, params.refine.model_points, params.keypoints.normal_radius_mm);
  const SceneIndex index(floor.remaining);
  const VerifyScene blind{&index, &scan.render.cloud, &scan.sensor, std::nullopt};
  const VerifyScene knowing{&index, &scan.render.cloud, &scan.sensor, floor.planes.front()};
  const double tolerance = params.matching.verify_tolerance_mm;
  const PointTally true_blind = tallyPoints(*view, blind, T_true, tolerance);
  const PointTally true_knowing = tallyPoints(*view, knowing, T_true, tolerance);
  const PointTally sunk_blind = tallyPoints(*view, blind, T_sunk, tolerance);
  const PointTally sunk_knowing = tallyPoints(*view, knowing, T_sunk, tolerance);
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
  EXPECT_EQ(verifyPose(*view, knowing, T_sunk, tolerance, {}), 0.0);
  EXPECT_GT(verifyPose(*view, knowing, T_true, tolerance, {}), 0.9);
}
