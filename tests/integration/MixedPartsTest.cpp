// Detection among several part types (thesis §5.2): a scatter of all four built-in parts seen by
// the virtual PhoXi; a model taught from a support alone reports supports only.
#include "core/cloud/Sensor.h"
#include "core/model/TaughtModel.h"
#include "core/params/ParamsJson.h"
#include "core/pipeline/Recognizer.h"
#include "core/sim/Synth.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

using namespace scanpick::core;

TEST(MixedParts, OnlyTheTaughtTypeIsReported) {
  const RecognitionParams params =
      loadPreset(std::filesystem::path(SCANPICK_SOURCE_DIR) / "resources/presets/phoxi-bin-support.json")
          .params;
  // The teach scan: one support on a table, cropped with the box an operator would draw.
  SynthRequest teach_request;
  teach_request.parts = {"support"};
  teach_request.layout = LayoutKind::Teach;
  teach_request.count = 1;
  teach_request.seed = 5;
  const SynthScene teach_scan = synthesize(teach_request);
  ASSERT_TRUE(teach_scan.scene.crop_box_world.has_value());
  TeachOptions options;
  options.name = "support";
  options.sensor = teach_scan.sensor;
  options.remove_floor = true;
  const Eigen::AlignedBox3d box = *teach_scan.scene.crop_box_world;
  OrientedBox crop;
  crop.T_scan_box = (teach_scan.scene.T_camera_world * Eigen::Translation3d(box.center())).cast<float>();
  crop.half_extents_mm = (0.5 * box.sizes()).cast<float>();
  options.crop_oriented = crop;
  auto model = std::make_shared<TaughtModel>(teach(teach_scan.render.cloud, options, params));
  const Eigen::Isometry3d T_teach_part =
      teach_scan.scene.T_scene_part(teach_scan.scene.instances.at(0));

  // Two of each part scattered on a table (round robin over the four types).
  SynthRequest request;
  request.parts = {"support", "cup", "pump-connector", "coat-rack"};
  request.layout = LayoutKind::Scatter;
  request.count = 8;
  request.seed = 11;
  const SynthScene mixed = synthesize(request);
  Recognizer recognizer(model);
  const RecognitionResult result = recognizer.recognize(mixed.render.cloud, mixed.sensor, params);

  const double diameter = mixed.scene.parts.at(0).diameter_mm();
  int supports_found = 0;
  for (const auto& d : result.detections) {
    // The detection's part pose, as scanpick-cli eval computes it.
    const Eigen::Isometry3d T_scene_part = d.T_scene_model * model->T_teach_model.inverse() * T_teach_part;
    double nearest = 1e9;
    std::string nearest_part;
    for (const auto& instance : mixed.scene.instances) {
      const double dist =
          (mixed.scene.T_scene_part(instance).translation() - T_scene_part.translation()).norm();
      if (dist < nearest) {
        nearest = dist;
        nearest_part = mixed.scene.parts.at(instance.part).name;
      }
    }
    std::printf("detection score %.3f: nearest instance is a %s at %.2f mm\n", d.score,
                nearest_part.c_str(), nearest);
    EXPECT_EQ(nearest_part, "support") << "a detection lies on another part type";
    EXPECT_LT(nearest, 0.1 * diameter) << "a detection is not on any instance";
    if (nearest_part == "support" && nearest < 0.1 * diameter)
      ++supports_found;
  }
  EXPECT_GE(supports_found, 1);
  EXPECT_LE(result.detections.size(), 2u);
}
