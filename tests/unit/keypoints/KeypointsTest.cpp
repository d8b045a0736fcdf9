#include "core/keypoints/Keypoints.h"

#include "core/common/Error.h"
#include "core/keypoints/Neighbourhoods.h"
#include "tests/support/RaycastScene.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

using namespace scanpick;

namespace {
// The surface of a 40 mm cube centred at (0, 0, 500), a point every 0.5 mm on each face.
std::vector<Eigen::Vector3f> cubeSurface() {
  std::vector<Eigen::Vector3f> pts;
  const float h = 20.0f;
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-h, h})
      for (float u = -h; u <= h + 1e-3f; u += 0.5f)
        for (float v = -h; v <= h + 1e-3f; v += 0.5f) {
          Eigen::Vector3f p;
          p[axis] = side;
          p[(axis + 1) % 3] = u;
          p[(axis + 2) % 3] = v;
          pts.push_back(p + Eigen::Vector3f(0, 0, 500));
        }
  return pts;
}
bool contains(const core::Keypoints& k, int index) {
  return std::binary_search(k.source_indices.begin(), k.source_indices.end(), index);
}
// Distance from a point of the cube to its nearest edge (two coordinates at +-20).
float edgeDistance(const Eigen::Vector3f& p) {
  Eigen::Vector3f q = p - Eigen::Vector3f(0, 0, 500);
  std::array<float, 3> d{20 - std::abs(q.x()), 20 - std::abs(q.y()), 20 - std::abs(q.z())};
  std::sort(d.begin(), d.end());
  return d[1]; // d[0] is 0: the point's own face
}
// A box and a cylinder on a floor 700 mm from the camera.
test::RaycastScene boxAndCylinder() {
  test::RaycastScene scene;
  scene.floor_z_mm = 700;
  scene.boxes.emplace_back(Eigen::Vector3d(-40, -30, 660), Eigen::Vector3d(20, 30, 700));
  scene.cylinders.push_back({Eigen::Vector2d(50, 0), 15.0, 670.0, 700.0});
  return scene;
}
} // namespace

TEST(NeighbourhoodAnalysis, MarksTheCubeEdgesNotTheFaceCentres) {
  const auto pts = cubeSurface();
  core::KeypointParams params; // r = 3 mm, range 0.6 mm
  const auto k = core::neighbourhoodAnalysis(core::PointCloud::fromPoints(pts), params);
  ASSERT_FALSE(k.source_indices.empty());
  EXPECT_TRUE(std::is_sorted(k.source_indices.begin(), k.source_indices.end()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const float e = edgeDistance(pts[i]);
    // On an edge the neighbourhood is two perpendicular half discs: their centroid lies
    // 4r/(3 pi) / sqrt(2) * ... = 0.3 r = 0.9 mm inwards (>= 0.6). A point 3 mm or more from every
    // edge has a full, symmetric disc.
    if (e < 0.01f) {
      EXPECT_TRUE(contains(k, static_cast<int>(i))) << "edge point " << pts[i].transpose();
    }
    if (e >= 3.0f) {
      EXPECT_FALSE(contains(k, static_cast<int>(i))) << "face point " << pts[i].transpose();
    }
  }
  params.position_range_mm = -1; // the thesis's "keep everything"
  EXPECT_EQ(core::neighbourhoodAnalysis(core::PointCloud::fromPoints(pts), params).points_mm.size(),
            pts.size());
}

TEST(NeighbourhoodAnalysis, PixelWindowsGiveTheSameKeypointsAsTheKdTree) {
  // A box seen from above, rendered organized; the same points unorganized must give exactly the
  // same keypoints (the pixel window is sized to hold the whole radius ball).
  test::RaycastScene scene = boxAndCylinder();
  const auto organized = scene.render(240, 180, 650 / 0.66 / 2, {300, 0, 0}, 0.05, 2);
  core::PointCloud flat = core::dropInvalid(organized);
  std::vector<int> to_organized;
  for (std::size_t i = 0; i < organized.size(); ++i)
    if (core::isValid(organized.points_mm[i]))
      to_organized.push_back(static_cast<int>(i));
  core::KeypointParams params;
  EXPECT_TRUE(core::detail::Neighbourhoods(organized, params.neighbourhood_radius_mm).organized());
  EXPECT_FALSE(core::detail::Neighbourhoods(flat, params.neighbourhood_radius_mm).organized());
  const auto a = core::neighbourhoodAnalysis(organized, params);
  const auto b = core::neighbourhoodAnalysis(flat, params);
  ASSERT_GT(a.source_indices.size(), 100u);
  ASSERT_EQ(a.source_indices.size(), b.source_indices.size());
  for (std::size_t j = 0; j < b.source_indices.size(); ++j)
    ASSERT_EQ(a.source_indices[j], to_organized[static_cast<std::size_t>(b.source_indices[j])]);
  // The box's top border is found and its centre is not.
  const auto pixelOf = [&](double x, double y, double z) {
    const double f = 650 / 0.66 / 2;
    const int c = static_cast<int>(std::lround(x / z * f + 119.5)),
              r = static_cast<int>(std::lround(y / z * f + 89.5));
    return r * 240 + c;
  };
  EXPECT_FALSE(contains(a, pixelOf(-10, 0, 660)));
  EXPECT_EQ(core::neighbourhoodAnalysis(organized, params).source_indices, a.source_indices);
}

TEST(NeighbourhoodAnalysis, PixelWindowsSumTheSameOffsetsAsTheKdTree) {
  // Eight pixels at a time: windows cut by the image border and rows not a multiple of eight wide
  // (199 columns), against the kd-tree's neighbours one by one.
  test::RaycastScene scene = boxAndCylinder();
  const auto organized = scene.render(199, 150, 650 / 0.66 / 2, {300, 0, 0}, 0.05, 3);
  const core::PointCloud flat = core::dropInvalid(organized);
  const double radius_mm = 3.0;
  const core::detail::Neighbourhoods pixels(organized, radius_mm), tree(flat, radius_mm);
  ASSERT_TRUE(pixels.organized());
  ASSERT_FALSE(tree.organized());
  const auto& valid = pixels.validIndices();
  ASSERT_EQ(valid.size(), flat.size());
  std::size_t border = 0;
  for (std::size_t j = 0; j < valid.size(); ++j) {
    const auto [sum_a, found_a] = pixels.offsetSum(valid[j], radius_mm);
    const auto [sum_b, found_b] = tree.offsetSum(static_cast<int>(j), radius_mm);
    ASSERT_EQ(found_a, found_b) << "point " << j;
    ASSERT_GE(found_a, 1u);                   // itself
    ASSERT_EQ(sum_a, sum_b) << "point " << j; // exact: no rounding in either sum
    const int column = valid[j] % 199;
    border += column < 3 || column > 195 ? 1 : 0;
  }
  EXPECT_GT(border, 100u);
}

TEST(NormalsGradient, FindsTheCreaseOfAFoldedSheetAndNothingOnAPlane) {
  // A sheet folded along x = 0 (z = 500 + 0.8 |x|: a 77° fold) and a flat sheet, 0.5 mm grid.
  std::vector<Eigen::Vector3f> folded, flat;
  for (float x = -20; x <= 20.001f; x += 0.5f)
    for (float y = -20; y <= 20.001f; y += 0.5f) {
      folded.emplace_back(x, y, 500 + 0.8f * std::abs(x));
      flat.emplace_back(x, y, 500);
    }
  core::KeypointParams params;
  params.method = core::KeypointParams::Method::NormalsGradient;
  // Normals from a 1 mm radius blur the fold over +-1 mm only, so neighbours 0.5-1 mm apart
  // across it turn by more than s = 0.35 rad; far from it they turn by nothing.
  params.normal_radius_mm = 1.0;
  const auto crease = core::normalsGradientAnalysis(core::PointCloud::fromPoints(folded), params);
  ASSERT_GT(crease.points_mm.size(), 20u) << "about one peak per row along the 40 mm crease";
  for (const auto& p : crease.points_mm)
    EXPECT_LE(std::abs(p.x()), 1.0f) << "peaks lie on the crease, got " << p.transpose();
  EXPECT_TRUE(
      core::normalsGradientAnalysis(core::PointCloud::fromPoints(flat), params).points_mm.empty());

  // Both = the union of the two extractors.
  params.method = core::KeypointParams::Method::Both;
  const auto both = core::extractKeypoints(core::PointCloud::fromPoints(folded), params);
  const auto edges = core::neighbourhoodAnalysis(core::PointCloud::fromPoints(folded), params);
  EXPECT_GE(both.source_indices.size(),
            std::max(edges.source_indices.size(), crease.source_indices.size()));
  EXPECT_LE(both.source_indices.size(), edges.source_indices.size() + crease.source_indices.size());
  for (int i : crease.source_indices)
    EXPECT_TRUE(contains(both, i));
}

TEST(NormalsGradient, OwnNormalsAreUsedAndBadParametersAreRejected) {
  // A flat sheet whose stored normals tilt abruptly along x = 0: only those normals make a peak.
  core::PointCloud sheet;
  for (float x = -10; x <= 10.001f; x += 0.5f)
    for (float y = -10; y <= 10.001f; y += 0.5f) {
      sheet.points_mm.emplace_back(x, y, 500);
      sheet.normals.push_back(x < 0 ? Eigen::Vector3f(0, 0, -1) : Eigen::Vector3f(0.6f, 0, -0.8f));
    }
  sheet.width = static_cast<std::uint32_t>(sheet.points_mm.size());
  core::KeypointParams params;
  const auto k = core::normalsGradientAnalysis(sheet, params);
  ASSERT_FALSE(k.points_mm.empty());
  for (const auto& p : k.points_mm)
    EXPECT_LE(std::abs(p.x()), 1.0f);
  params.gradient_neighbours = 0;
  EXPECT_THROW(core::normalsGradientAnalysis(sheet, params), core::Error);
  params = {};
  params.neighbourhood_radius_mm = 0;
  EXPECT_THROW(core::neighbourhoodAnalysis(sheet, params), core::Error);
}
