// The random parts: deterministic, closed, 20-300 mm, every family drawn, and their declared
// symmetries exactly the ones they have among the candidate turns.
#include "core/sim/RandomPart.h"

#include "core/sim/Mesh.h"
#include "core/sim/PartCatalog.h"

#include <gtest/gtest.h>
#include <set>

using namespace scanpick::core;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Whether `S` maps the part's surface onto itself: every sampled surface point, moved by S, lies
/// within `tolerance_mm` of the surface (of some component).
bool mapsOntoItself(const Part& part, const std::vector<Eigen::Vector3d>& samples,
                    const Eigen::Isometry3d& S, double tolerance_mm) {
  const TriangleMesh mesh = part.mesh();
  return std::all_of(samples.begin(), samples.end(), [&](const Eigen::Vector3d& p) {
    return pointMeshDistance(S * p, mesh) <= tolerance_mm;
  });
}

std::vector<Eigen::Vector3d> surfaceSamples(const Part& part, std::size_t count) {
  std::vector<Eigen::Vector3d> points, normals;
  sampleSurface(part.mesh(), count, 11, points, normals);
  return points;
}

/// The 24 turns of a cube and the turns about z by 2π/k (k = 2..8), about `centre`.
std::vector<Eigen::Isometry3d> candidateTurns(const Eigen::Vector3d& centre) {
  std::vector<Eigen::Matrix3d> rotations;
  const Eigen::Vector3d axes[] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                  Eigen::Vector3d::UnitZ()};
  for (const auto& a : axes)
    for (int q = 1; q < 4; ++q)
      rotations.push_back(Eigen::AngleAxisd(q * kPi / 2, a).toRotationMatrix());
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, -1, 0), Eigen::Vector3d(1, 0, 1),
        Eigen::Vector3d(1, 0, -1), Eigen::Vector3d(0, 1, 1), Eigen::Vector3d(0, 1, -1)})
    rotations.push_back(Eigen::AngleAxisd(kPi, d.normalized()).toRotationMatrix());
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1, -1),
                                   Eigen::Vector3d(1, -1, 1), Eigen::Vector3d(-1, 1, 1)})
    for (int q = 1; q < 3; ++q)
      rotations.push_back(Eigen::AngleAxisd(q * 2 * kPi / 3, d.normalized()).toRotationMatrix());
  for (int k = 3; k <= 8; ++k)
    rotations.push_back(
        Eigen::AngleAxisd(2 * kPi / k, Eigen::Vector3d::UnitZ()).toRotationMatrix());
  std::vector<Eigen::Isometry3d> turns;
  for (const auto& R : rotations) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = centre - R * centre;
    turns.push_back(T);
  }
  return turns;
}

bool declared(const Part& part, const Eigen::Isometry3d& S) {
  if (part.symmetry.continuous_axis) {
    const Eigen::Vector3d axis = part.symmetry.continuous_axis->direction;
    const Eigen::AngleAxisd aa(S.linear());
    if ((aa.axis().cross(axis)).norm() < 1e-6 &&
        (S * part.symmetry.continuous_axis->point_mm - part.symmetry.continuous_axis->point_mm)
                .norm() < 1e-6)
      return true;
  }
  return std::any_of(part.symmetry.discrete.begin(), part.symmetry.discrete.end(),
                     [&](const Eigen::Isometry3d& D) { return D.isApprox(S, 1e-6); });
}

} // namespace

TEST(RandomPart, TheSameSeedGivesTheSamePart) {
  const Part a = randomPart(42), b = randomPart(42);
  EXPECT_EQ(a.name, "random-42");
  ASSERT_EQ(a.components.size(), b.components.size());
  for (std::size_t c = 0; c < a.components.size(); ++c)
    EXPECT_EQ(a.components[c].vertices_mm, b.components[c].vertices_mm);
  EXPECT_EQ(builtInPart("random-42").mesh().vertices_mm, a.mesh().vertices_mm);
  EXPECT_EQ(randomPartSeed("random-x"), std::nullopt);
  EXPECT_EQ(randomPartSeed("support"), std::nullopt);
}

TEST(RandomPart, PartsAreClosedSolidsOf20To300MmFromEveryFamily) {
  std::set<RandomPartFamily> families;
  for (std::uint64_t seed = 0; seed < 120; ++seed) {
    SCOPED_TRACE(seed);
    const Part part = randomPart(seed);
    families.insert(randomPartFamily(seed));
    for (const auto& c : part.components) {
      EXPECT_EQ(openEdgeCount(c), 0u);
      EXPECT_GT(signedVolume(c), 0.0);
    }
    const double longest = boundingBox(part.mesh()).sizes().maxCoeff();
    EXPECT_GE(longest, 20.0 - 1e-9);
    EXPECT_LE(longest, 300.0 + 1e-9);
    EXPECT_FALSE(part.grip_points.empty());
  }
  EXPECT_EQ(families.size(), static_cast<std::size_t>(kRandomPartFamilies));
}

TEST(RandomPart, DeclaredSymmetriesAreExactlyThePartsOwnAmongTheCandidateTurns) {
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    SCOPED_TRACE(seed);
    const Part part = randomPart(seed);
    SCOPED_TRACE(toString(randomPartFamily(seed)));
    const auto samples = surfaceSamples(part, 400);
    const double size = boundingBox(part.mesh()).sizes().maxCoeff();
    // The round walls are polygons of 32 or 64 sides: a turn of the true shape misses them by
    // under 0.5 % of the part's size; a turn that is not a symmetry misses by a wall's thickness.
    const double tolerance = 0.005 * size;
    for (const auto& S : part.symmetry.discrete)
      EXPECT_TRUE(mapsOntoItself(part, samples, S, tolerance)) << "a declared turn is not one";
    const Eigen::Vector3d centre = boundingBox(part.mesh()).center();
    for (const auto& S : candidateTurns(centre)) {
      if (mapsOntoItself(part, samples, S, tolerance)) {
        EXPECT_TRUE(declared(part, S)) << "an undeclared symmetry:\n" << S.matrix();
      }
    }
  }
}
