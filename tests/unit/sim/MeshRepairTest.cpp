// Closing the holes of open meshes: caps that make a closed, consistently oriented solid of the
// right volume, also over a non-convex hole; clear errors where a hole cannot be capped.
#include "core/sim/MeshRepair.h"

#include "core/common/Error.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/MeshIo.h"
#include "tests/support/TempDir.h"

#include <algorithm>
#include <gtest/gtest.h>

using namespace scanpick::core;

namespace {

/// `mesh` without the triangles whose three vertices all lie at height `z_mm`.
TriangleMesh withoutFaceAt(const TriangleMesh& mesh, double z_mm) {
  TriangleMesh out = mesh;
  std::erase_if(out.triangles, [&](const Eigen::Vector3i& t) {
    return std::all_of(t.data(), t.data() + 3,
                       [&](int v) { return std::abs(mesh.vertices_mm[v].z() - z_mm) < 1e-9; });
  });
  return out;
}

} // namespace

TEST(MeshRepair, OpenBoxIsClosedWithItsVolume) {
  TriangleMesh box = withoutFaceAt(boxMesh({0, 0, 0}, {10, 20, 30}), 30);
  ASSERT_GT(openEdgeCount(box), 0u);
  const HoleFilling report = closeHoles(box);
  EXPECT_EQ(report.holes, 1u);
  EXPECT_EQ(report.triangles, 2u);
  EXPECT_NEAR(report.largest_hole_mm, std::hypot(10.0, 20.0), 1e-9);
  EXPECT_EQ(openEdgeCount(box), 0u);
  EXPECT_NEAR(signedVolume(box), 6000.0, 1e-9); // the cap faces outwards like the rest
}

TEST(MeshRepair, NonConvexHoleIsCappedWithoutOverlap) {
  // An L-shaped plate (a 3 × 3 grid of 10 mm cells without one corner cell), open on top: its
  // border has a reflex corner, where a fan from the centre would fold over itself.
  auto cells = rectangleCells(0, 30, 0, 30, 3, 3, 2);
  cells.pop_back();
  TriangleMesh plate = withoutFaceAt(extrudeCells(cells, 0, 5, 16), 5);
  ASSERT_GT(openEdgeCount(plate), 0u);
  const HoleFilling report = closeHoles(plate);
  EXPECT_EQ(report.holes, 1u);
  EXPECT_EQ(openEdgeCount(plate), 0u);
  EXPECT_NEAR(signedVolume(plate), 800.0 * 5, 1e-6);
  EXPECT_NEAR(surfaceArea(plate), 2 * 800.0 + 5 * 120.0, 1e-6); // no cap triangle overlaps
}

TEST(MeshRepair, ClosedMeshIsLeftAlone) {
  TriangleMesh box = boxMesh({0, 0, 0}, {1, 1, 1});
  const std::size_t triangles = box.triangles.size();
  EXPECT_EQ(closeHoles(box).holes, 0u);
  EXPECT_EQ(box.triangles.size(), triangles);
}

TEST(MeshRepair, HolesSharingAVertexAreRefusedAndTheMeshKept) {
  // Two triangles meeting at one vertex: their borders pass through it twice.
  TriangleMesh bowtie;
  bowtie.vertices_mm = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
  const TriangleMesh before = bowtie;
  EXPECT_THROW(closeHoles(bowtie), Error);
  EXPECT_EQ(bowtie.triangles, before.triangles);
}

TEST(MeshRepair, ScannedRabbitBecomesASolid) {
  const auto file = scanpick::test::sharedData("pcl/tum_rabbit.vtk");
  if (file.empty())
    GTEST_SKIP()
        << "../shared/data/pcl/tum_rabbit.vtk is absent (the real scanned mesh lives beside "
           "the project, not in it)";
  TriangleMesh rabbit = loadMesh(file);
  ASSERT_GT(openEdgeCount(rabbit), 0u); // its base is open: 141 border edges
  const HoleFilling report = closeHoles(rabbit);
  EXPECT_EQ(report.holes, 1u);
  EXPECT_EQ(report.triangles, 139u); // a 141-gon in 139 triangles, no vertex added
  EXPECT_EQ(openEdgeCount(rabbit), 0u);
  EXPECT_GT(std::abs(signedVolume(rabbit)), 1e5); // a solid of a few hundred cm³
}
