// Procedural parts: closed, outward, sized like the thesis objects, and truly symmetric.
#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/PartCatalog.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace scanpick::core;

TEST(Mesh, BoxIsClosedWithTheRightVolume) {
  const TriangleMesh box = boxMesh({0, 0, 0}, {10, 20, 30});
  EXPECT_EQ(openEdgeCount(box), 0u);
  EXPECT_NEAR(signedVolume(box), 6000.0, 1e-9);
  EXPECT_NEAR(surfaceArea(box), 2 * (200 + 300 + 600), 1e-9);
}

TEST(Mesh, PlateWithHolesIsClosedAndLosesTheHoleVolume) {
  auto cells = rectangleCells(0, 80, 0, 40, 2, 1, 6);
  cells[0].hole_radius_mm = 10;
  const TriangleMesh plate = extrudeCells(cells, 0, 5, 64);
  EXPECT_EQ(openEdgeCount(plate), 0u);
  // 80 × 40 × 5 minus a Ø20 hole (a 64-gon: area 0.5·64·r²·sin(2π/64)).
  const double hole = 0.5 * 64 * 100 * std::sin(2 * std::numbers::pi / 64);
  EXPECT_NEAR(signedVolume(plate), (3200 - hole) * 5, 1e-6);
  EXPECT_EQ(connectedComponents(plate).size(), 1u);
}

TEST(Mesh, RevolvedProfileAndBentBarAreClosed) {
  const TriangleMesh cup =
      revolveProfile({{0, 0}, {40, 0}, {40, 95}, {37, 95}, {37, 6}, {0, 6}}, 64);
  EXPECT_EQ(openEdgeCount(cup), 0u);
  EXPECT_GT(signedVolume(cup), 0);
  const TriangleMesh bar = bentBar({0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                   20, 4, -1.5, 1.5, 20, 12);
  EXPECT_EQ(openEdgeCount(bar), 0u);
  // Pappus: volume = area of the section × path length of its centre (polygon section).
  const double section = 0.5 * 12 * 16 * std::sin(2 * std::numbers::pi / 12);
  EXPECT_NEAR(signedVolume(bar), section * 20 * 3.0, 0.05 * section * 60);
}

TEST(Mesh, OpenMeshIsDetected) {
  TriangleMesh box = boxMesh({0, 0, 0}, {1, 1, 1});
  box.triangles.pop_back();
  EXPECT_GT(openEdgeCount(box), 0u);
}

TEST(Mesh, PointTriangleDistance) {
  const Eigen::Vector3d a(0, 0, 0), b(10, 0, 0), c(0, 10, 0);
  EXPECT_NEAR(std::sqrt(pointTriangleDistanceSquared({2, 2, 3}, a, b, c)), 3.0,
              1e-12); // above the face
  EXPECT_NEAR(std::sqrt(pointTriangleDistanceSquared({-3, -4, 0}, a, b, c)), 5.0,
              1e-12); // vertex region
  EXPECT_NEAR(std::sqrt(pointTriangleDistanceSquared({5, -2, 0}, a, b, c)), 2.0,
              1e-12); // edge region
}

class BuiltInPart : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltInPart, ComponentsAreClosedAndOutward) {
  const Part p = builtInPart(GetParam());
  ASSERT_FALSE(p.components.empty());
  for (const auto& c : p.components) {
    EXPECT_EQ(openEdgeCount(c), 0u);
    EXPECT_GT(signedVolume(c), 0);
  }
  EXPECT_FALSE(p.grip_points.empty());
}

TEST_P(BuiltInPart, SizeMatchesTheThesisObject) {
  const Part p = builtInPart(GetParam());
  const Eigen::Vector3d extent = boundingBox(p.mesh()).sizes();
  const double largest = extent.maxCoeff();
  if (GetParam() == "coat-rack")
    EXPECT_NEAR(largest, 60, 5);
  else
    EXPECT_TRUE(largest >= 80 && largest <= 120) << largest;
}

TEST_P(BuiltInPart, DeclaredSymmetriesMapTheSurfaceOntoItself) {
  const Part p = builtInPart(GetParam());
  const TriangleMesh mesh = p.mesh();
  std::vector<Eigen::Vector3d> pts, normals;
  sampleSurface(mesh, 300, 5, pts, normals);
  for (const auto& S : p.symmetry.discrete) {
    double worst = 0;
    for (const auto& q : pts)
      worst = std::max(worst, pointMeshDistance(S * q, mesh));
    // Facets map onto facets; the only slack is in the overlap of components.
    EXPECT_LT(worst, 0.01) << GetParam();
  }
  // The cup's handle breaks every symmetry: make sure a wrong one would be caught.
  if (GetParam() == "cup") {
    const Eigen::Isometry3d half_turn(
        Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()));
    double worst = 0;
    for (const auto& q : pts)
      worst = std::max(worst, pointMeshDistance(half_turn * q, mesh));
    EXPECT_GT(worst, 10.0);
  }
}

static std::string partTestName(const ::testing::TestParamInfo<std::string>& param) {
  std::string n = param.param;
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

INSTANTIATE_TEST_SUITE_P(Parts, BuiltInPart, ::testing::ValuesIn(builtInPartNames()), partTestName);

TEST(PartCatalog, UnknownPartNamesTheKnownOnes) {
  try {
    builtInPart("teapot");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pump-connector"), std::string::npos);
  }
}
