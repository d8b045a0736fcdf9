#include "core/sim/PartCatalog.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/sim/MeshBuilder.h"
#include "core/sim/MeshIo.h"
#include "core/sim/MeshRepair.h"
#include "core/sim/RandomPart.h"

#include <cmath>
#include <numbers>

namespace scanpick::core {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kHoleSegments = 32;

Eigen::Isometry3d rotation(const Eigen::Matrix3d& R,
                           const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

/// Rotation by `angle` about the axis through `point` along `dir`.
Eigen::Isometry3d rotationAbout(const Eigen::Vector3d& point, const Eigen::Vector3d& dir,
                                double angle) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, dir.normalized()).toRotationMatrix();
  return rotation(R, point - R * point);
}

Part support() {
  Part p;
  p.name = "support";
  // Leg A lies in the xy plane; the 180° turn about the bisector (1,0,1) maps it onto leg B, which
  // is both the way leg B is built and the part's symmetry.
  // Leg A starts at x = 0.5 so that the legs overlap without sharing a vertex: an exported mesh
  // then splits back into the same closed components.
  std::vector<PlateCell> cells = rectangleCells(0.5, 80, -40, 40, 2, 2, 8);
  for (auto& c : cells)
    if (c.center_mm.x() > 40)
      c.hole_radius_mm = 6;
  for (auto& c : cells)
    c.center_mm.x() = c.center_mm.x() > 40 ? 60.0 : c.center_mm.x();
  const TriangleMesh leg_a = extrudeCells(cells, 0, 5, kHoleSegments);
  const Eigen::Isometry3d S = rotationAbout(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 1), kPi);
  p.components.push_back(leg_a);
  p.components.push_back(transformed(leg_a, S));
  // The gusset: a triangle in xz, 5 mm thick, sunk 1 mm into both legs.
  PlateCell gusset;
  gusset.boundary_mm = {{4, 4}, {45, 4}, {4, 45}};
  gusset.center_mm = {53.0 / 3, 53.0 / 3};
  Eigen::Matrix3d R_plane; // (a, b, c) -> (a, -c, b): the cell plane becomes xz
  R_plane << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  TriangleMesh g = transformed(extrudeCells({gusset}, -2.5, 2.5, kHoleSegments), rotation(R_plane));
  orientOutwards(g);
  p.components.push_back(g);
  p.grip_points = {{"leg-a", {60, 0, 5}}, {"leg-b", {5, 0, 60}}};
  p.symmetry.discrete = {S};
  return p;
}

Part cup() {
  Part p;
  p.name = "cup";
  p.components.push_back(
      revolveProfile({{0, 0}, {40, 0}, {40, 95}, {37, 95}, {37, 6}, {0, 6}}, 64));
  // Handle: a bent bar in the xz plane whose ends (±93°) are buried in the 3 mm wall.
  p.components.push_back(bentBar({40, 0, 50}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                 24, 4.5, -93.0 * kPi / 180, 93.0 * kPi / 180, 24, 16));
  p.grip_points = {{"rim", {-38.5, 0, 95}}, {"handle", {64, 0, 50}}};
  return p;
}

Part pumpConnector() {
  Part p;
  p.name = "pump-connector";
  std::vector<PlateCell> cells = sectorCells(12, 45, 4, 12, 0, 32);
  for (auto& c : cells)
    c.hole_radius_mm = 5;
  p.components.push_back(extrudeCells(cells, 0, 8, kHoleSegments));
  p.components.push_back(extrudeCells(cells, 92, 100, kHoleSegments));
  p.components.push_back(revolveProfile({{12, 7.5}, {20, 7.5}, {20, 92.5}, {12, 92.5}}, 48));
  p.grip_points = {{"pipe", {0, 0, 50}}, {"flange-a", {0, 0, 0}}, {"flange-b", {0, 0, 100}}};
  const Eigen::Vector3d mid(0, 0, 50);
  for (int k = 1; k < 4; ++k) // quarter turns about the axis (4 bolt holes)
    p.symmetry.discrete.push_back(rotationAbout(mid, Eigen::Vector3d::UnitZ(), k * kPi / 2));
  for (int k = 0; k < 4; ++k) // end-to-end flips about horizontal axes at 0°, 45°, 90°, 135°
    p.symmetry.discrete.push_back(
        rotationAbout(mid, Eigen::Vector3d(std::cos(k * kPi / 4), std::sin(k * kPi / 4), 0), kPi));
  return p;
}

Part coatRack() {
  Part p;
  p.name = "coat-rack";
  std::vector<PlateCell> cells = rectangleCells(-30, 30, -15, 15, 2, 1, 8);
  for (auto& c : cells)
    c.hole_radius_mm = 5;
  p.components.push_back(extrudeCells(cells, 0, 4, kHoleSegments));
  // Suction cup under the plate (solid; its stem is sunk into the plate).
  p.components.push_back(
      revolveProfile({{0, 1}, {7, 1}, {7, -2}, {20, -7}, {20, -8}, {0, -8}}, 48));
  // The hook: a stem out of the plate, an arm along +y and a lip.
  p.components.push_back(boxMesh({-4, -10, 3.5}, {4, -2, 23.5}));
  p.components.push_back(boxMesh({-4, -10, 20}, {4, 10, 24}));
  p.components.push_back(boxMesh({-4, 6, 23.5}, {4, 10, 30}));
  p.grip_points = {{"mark-a", {-20, 8, 4}}, {"mark-b", {20, 8, 4}}, {"hook", {0, 0, 22}}};
  return p;
}

} // namespace

double Part::diameter_mm() const {
  Eigen::AlignedBox3d box;
  for (const auto& c : components)
    box.extend(boundingBox(c));
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

Eigen::Vector3d Part::center_mm() const {
  Eigen::AlignedBox3d box;
  for (const auto& c : components)
    box.extend(boundingBox(c));
  return box.isEmpty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(box.center());
}

std::vector<std::string> builtInPartNames() {
  return {"support", "cup", "pump-connector", "coat-rack"};
}

Part builtInPart(const std::string& name) {
  if (name == "support")
    return support();
  if (name == "cup")
    return cup();
  if (name == "pump-connector")
    return pumpConnector();
  if (name == "coat-rack")
    return coatRack();
  if (const auto seed = randomPartSeed(name))
    return randomPart(*seed);
  std::string known;
  for (const auto& n : builtInPartNames())
    known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown part '" + name + "': the built-in parts are " + known +
              ", and random-<seed> for a generated one");
}

Part partFromMeshFile(const std::filesystem::path& path, bool close_holes) {
  TriangleMesh mesh = loadMesh(path);
  if (close_holes) {
    const HoleFilling filled = closeHoles(mesh);
    logger()->info("mesh '{}': {} hole(s) closed with {} triangles (the largest {:.1f} mm across)",
                   path.string(), filled.holes, filled.triangles, filled.largest_hole_mm);
  }
  Part p;
  p.name = path.stem().string();
  for (auto& c : connectedComponents(mesh)) {
    const std::size_t open = openEdgeCount(c);
    if (open > 0)
      throw Error("mesh '" + path.string() + "' is not closed (" + std::to_string(open) +
                  " open or non-manifold edges): the physics needs a watertight solid; close its "
                  "holes (--close-holes caps them; or MeshLab: Filters > Remeshing > Close Holes) "
                  "and retry");
    orientOutwards(c);
    if (std::abs(signedVolume(c)) < 1e-3)
      throw Error("mesh '" + path.string() + "' encloses no volume: export the part as a solid");
    p.components.push_back(std::move(c));
  }
  const double d = p.diameter_mm();
  if (d < 1.0 || d > 2000.0)
    throw Error("mesh '" + path.string() + "' is " + std::to_string(d) +
                " mm across: the file must be in millimetres (parts of 1-2000 mm)");
  p.grip_points = {{"center", p.center_mm()}};
  return p;
}

} // namespace scanpick::core
