// Shape variation between instances (core/sim/PartDeformation.h): bounded, seeded, closed meshes,
// and a ground truth that keeps the part as designed.
#include "core/sim/PartDeformation.h"

#include "core/common/Error.h"
#include "core/sim/Mesh.h"
#include "core/sim/PartCatalog.h"
#include "core/sim/Synth.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace scanpick::core;

namespace {

/// Largest vertex displacement between two parts with the same mesh topology, mm.
double largestDisplacement(const Part& a, const Part& b) {
  double largest = 0.0;
  for (std::size_t c = 0; c < a.components.size(); ++c)
    for (std::size_t v = 0; v < a.components[c].vertices_mm.size(); ++v)
      largest = std::max(largest,
                         (a.components[c].vertices_mm[v] - b.components[c].vertices_mm[v]).norm());
  return largest;
}

} // namespace

TEST(PartDeformation, BoundedSeededAndClosed) {
  const Part support = builtInPart("support");
  const double diameter = support.diameter_mm();

  EXPECT_EQ(largestDisplacement(support, deformedPart(support, 0.0, 7)), 0.0);

  const Part a = deformedPart(support, 0.05, 7);
  const double moved = largestDisplacement(support, a);
  // Stretch 5 %, shear 2.5 % per axis pair and a bend of 5 % of the half length, from the centre:
  // well below a fifth of the diameter, and more than noise.
  EXPECT_GT(moved, 0.5);
  EXPECT_LT(moved, 0.2 * diameter);
  EXPECT_LT((boundingBox(a.mesh()).center() - boundingBox(support.mesh()).center()).norm(),
            0.05 * diameter);
  for (const auto& component : a.components)
    EXPECT_EQ(openEdgeCount(component), 0u);
  EXPECT_EQ(a.grip_points.size(), support.grip_points.size());
  EXPECT_EQ(a.grip_points[0].position_mm, support.grip_points[0].position_mm);

  EXPECT_EQ(largestDisplacement(a, deformedPart(support, 0.05, 7)), 0.0) << "same seed, same shape";
  EXPECT_GT(largestDisplacement(a, deformedPart(support, 0.05, 8)), 0.1) << "another seed, another";
  EXPECT_GT(largestDisplacement(support, deformedPart(support, 0.2, 7)), moved);

  EXPECT_THROW(deformedPart(support, -0.01, 7), Error);
  EXPECT_THROW(deformedPart(support, 0.31, 7), Error);
}

TEST(PartDeformation, SynthDeformsEachInstanceAndKeepsTheDesignInTheGroundTruth) {
  SynthRequest r;
  r.parts = {"support"};
  r.layout = LayoutKind::Scatter;
  r.count = 3;
  r.sensor = "kinect-v1"; // the smallest scan keeps the test fast
  r.seed = 4;
  const SynthScene plain = synthesize(r);
  r.deformation = 0.1;
  const SynthScene varied = synthesize(r);

  ASSERT_EQ(varied.scene.instances.size(), 3u);
  ASSERT_EQ(varied.scene.parts.size(), 3u) << "one deformed copy per instance";
  EXPECT_GT(largestDisplacement(varied.scene.parts[0], varied.scene.parts[1]), 0.1);
  EXPECT_NE(plain.render.cloud.points_mm, varied.render.cloud.points_mm);

  const auto gt = nlohmann::json::parse(groundTruthJson(varied, "v.pcd", "v.png"));
  ASSERT_EQ(gt["parts"].size(), 1u);
  EXPECT_DOUBLE_EQ(gt["parts"]["support"]["diameter_mm"].get<double>(),
                   builtInPart("support").diameter_mm());

  r.deformation = 0.5;
  EXPECT_THROW(validateRequest(r), Error);
}
