// Real data: a mug taught from PCL's stereo scan of a mug on a table
// (table_scene_mug_stereo_textured.pcd, 640x480, metres) with an operator's crop box and the
// table removed, every parameter derived from the scan and the part, is found once in that scan
// at the pose it was taught in. Beyond the table's edge the camera sees the room, behind the
// table's plane: the table is still the plane the mug rests on.
#include "core/cloud/CloudIo.h"
#include "core/model/TaughtModel.h"
#include "core/pipeline/Recognizer.h"
#include "tests/integration/TaughtPoseError.h"

#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

using namespace scanpick::core;
namespace fs = std::filesystem;
namespace test = scanpick::test;

TEST(RealMug, TaughtWithTheTableRemovedAndFoundWhereItStands) {
  const fs::path file =
      fs::path(SCANPICK_SHARED_DATA_DIR) / "pcl" / "table_scene_mug_stereo_textured.pcd";
  if (!fs::exists(file))
    GTEST_SKIP() << "real scan " << file
                 << " is absent (it lives in ../shared/data/pcl beside the project)";
  const PointCloud scan = loadCloud(file, LengthUnit::Metres).cloud;
  TeachOptions options;
  options.name = "mug";
  // The box an operator draws around the mug (scan frame, mm): the table inside it goes.
  options.crop_box_mm =
      Eigen::AlignedBox3f(Eigen::Vector3f(-20, 0, 680), Eigen::Vector3f(185, 125, 900));
  options.remove_floor = true;
  options.source_units = LengthUnit::Metres;
  const AutoParams derived = autoTeachParams(scan, options);
  std::printf("mug: spacing %.2f mm, noise %.2f mm, diameter %.1f mm, %zu points\n",
              derived.scan.spacing_mm, derived.scan.noise_mm, derived.part.diameter_mm,
              derived.part.points);
  // A mug and its handle, about 0.13 x 0.1 x 0.1 m; with the table's rest in the box, 0.28 m.
  EXPECT_LT(derived.part.diameter_mm, 220.0) << "the table was not removed";

  auto model = std::make_shared<TaughtModel>(teach(scan, options, derived.params));
  Recognizer recognizer(model);
  const RecognitionResult result = recognizer.recognize(scan, SensorModel{}, derived.params);
  ASSERT_EQ(result.detections.size(), 1u) << "the mug must be found exactly once";
  const test::TaughtPoseError off =
      test::taughtPoseError(result.detections[0].T_scene_model, *model);
  std::printf("mug: score %.3f, pose error %.3f mm, %.3f deg\n", result.detections[0].score,
              off.translation_mm, off.rotation_deg);
  EXPECT_LT(off.translation_mm, 0.5);
  EXPECT_LT(off.rotation_deg, 0.2);
}
