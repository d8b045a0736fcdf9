// Detection among several part types (thesis §5.2): a scatter of all four built-in parts seen by
// the virtual PhoXi; a model taught from a support alone reports supports only.
#include "core/pipeline/Recognizer.h"
#include "tests/integration/SynthTeach.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::core;

TEST(MixedParts, OnlyTheTaughtTypeIsReported) {
  const RecognitionParams params = test::bundledPreset("phoxi-bin");
  const test::SynthTeach taught = test::teachFromSynth("support", 5, params);

  // Two of each part scattered on a table (round robin over the four types).
  SynthRequest request;
  request.parts = {"support", "cup", "pump-connector", "coat-rack"};
  request.layout = LayoutKind::Scatter;
  request.count = 8;
  request.seed = 11;
  const SynthScene mixed = synthesize(request);
  Recognizer recognizer(taught.model);
  const RecognitionResult result = recognizer.recognize(mixed.render.cloud, mixed.sensor, params);

  const double diameter = mixed.scene.parts.at(0).diameter_mm();
  int supports_found = 0;
  for (const auto& d : result.detections) {
    const test::NearestInstance nearest = test::nearestInstance(d, taught, mixed.scene);
    std::printf("detection score %.3f: nearest instance is a %s at %.2f mm\n", d.score,
                nearest.part.c_str(), nearest.distance_mm);
    EXPECT_EQ(nearest.part, "support") << "a detection lies on another part type";
    EXPECT_LT(nearest.distance_mm, 0.1 * diameter) << "a detection is not on any instance";
    if (nearest.part == "support" && nearest.distance_mm < 0.1 * diameter)
      ++supports_found;
  }
  EXPECT_GE(supports_found, 1);
  EXPECT_LE(result.detections.size(), 2u);
}
