#include "core/sim/RandomPart.h"

#include "core/sim/MeshBuilder.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

namespace scanpick::core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kRoundSegments = 32;

/// Uniform numbers from mt19937_64, whose sequence the standard fixes (the standard
/// distributions' are not), so a seed gives the same part with any standard library.
class Draw {
public:
  explicit Draw(std::uint64_t seed) : m_engine(seed ^ 0x5CA2F1C7u) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(m_engine() >> 11) * 0x1.0p-53;
  }
  int integer(int lo, int hi) { // inclusive
    return lo + static_cast<int>(uniform(0, 1) * (hi - lo + 1) * (1 - 1e-12));
  }
  bool chance(double p) { return uniform(0, 1) < p; }
  /// Log-uniform: sizes spread evenly over scales.
  double scale(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }

private:
  std::mt19937_64 m_engine;
};

Eigen::Isometry3d rotationAbout(const Eigen::Vector3d& point, const Eigen::Vector3d& dir,
                                double angle) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, dir.normalized()).toRotationMatrix();
  T.translation() = point - T.linear() * point;
  return T;
}

/// `part` scaled by `factor` about the origin: its meshes, grip points and symmetries.
Part scaled(Part part, double factor) {
  for (auto& c : part.components)
    for (auto& v : c.vertices_mm)
      v *= factor;
  for (auto& g : part.grip_points)
    g.position_mm *= factor;
  for (auto& S : part.symmetry.discrete)
    S.translation() *= factor;
  if (part.symmetry.continuous_axis)
    part.symmetry.continuous_axis->point_mm *= factor;
  return part;
}

/// A plate of nx x ny cells (nx != ny proportions) with holes in some cells, centred on the
/// origin in xy, z in [0, t]; optionally a rib along x on top. Its half turns about x, y and z
/// through the plate's centre are symmetries exactly when they map the hole pattern (and rib)
/// onto itself.
Part plate(Draw& draw, double size) {
  const int nx = draw.integer(2, 4), ny = draw.integer(1, 3);
  const double length = size, width = size * draw.uniform(0.35, 0.75);
  const double t = std::max(1.5, size * draw.uniform(0.04, 0.1));
  auto cells = rectangleCells(-length / 2, length / 2, -width / 2, width / 2, nx, ny, 4);
  const double cell_side = std::min(length / nx, width / ny);
  std::vector<bool> hole(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    hole[i] = draw.chance(0.6);
    if (hole[i])
      cells[i].hole_radius_mm = cell_side * draw.uniform(0.15, 0.3);
  }
  // All holes of one plate share one radius, so the pattern alone decides the symmetry.
  double radius = 0;
  for (const auto& c : cells)
    radius = std::max(radius, c.hole_radius_mm);
  for (std::size_t i = 0; i < cells.size(); ++i)
    cells[i].hole_radius_mm = hole[i] ? radius : 0.0;
  Part p;
  p.components.push_back(extrudeCells(cells, 0, t, kRoundSegments));
  const bool rib = draw.chance(0.4);
  if (rib) // a rib along x on top
    p.components.push_back(boxMesh({-length / 2 + 0.01, -t / 2, t - 0.01},
                                   {length / 2 - 0.01, t / 2, t + size * draw.uniform(0.1, 0.2)}));
  const auto at = [&](int ix, int iy) { return hole[static_cast<std::size_t>(iy * nx + ix)]; };
  const auto invariant = [&](bool flip_x, bool flip_y) {
    for (int iy = 0; iy < ny; ++iy)
      for (int ix = 0; ix < nx; ++ix)
        if (at(ix, iy) != at(flip_x ? nx - 1 - ix : ix, flip_y ? ny - 1 - iy : iy))
          return false;
    return true;
  };
  const Eigen::Vector3d mid(0, 0, t / 2);
  if (invariant(true, true)) // about z: x -> -x, y -> -y
    p.symmetry.discrete.push_back(rotationAbout(mid, Eigen::Vector3d::UnitZ(), kPi));
  if (!rib && invariant(false, true)) // about x: y -> -y, z flipped
    p.symmetry.discrete.push_back(rotationAbout(mid, Eigen::Vector3d::UnitX(), kPi));
  if (!rib && invariant(true, false)) // about y: x -> -x, z flipped
    p.symmetry.discrete.push_back(rotationAbout(mid, Eigen::Vector3d::UnitY(), kPi));
  p.grip_points = {{"top", {0, 0, rib ? boundingBox(p.mesh()).max().z() : t}}};
  return p;
}

/// An angle: a base leg along x and an upright leg along z, extruded along y. Equal legs make
/// the half turn about the bisector of the angle a symmetry.
Part lBracket(Draw& draw, double size) {
  const double width = size * draw.uniform(0.3, 0.8),
               t = std::max(1.5, size * draw.uniform(0.05, 0.1));
  const double a = size, b = draw.chance(0.4) ? size : size * draw.uniform(0.4, 0.85);
  Part p;
  p.components.push_back(boxMesh({0, 0, 0}, {a, width, t}));
  p.components.push_back(boxMesh({0.01, 0.01, 0.01}, {t, width - 0.01, b}));
  if (a == b)
    p.symmetry.discrete.push_back(rotationAbout({0, width / 2, 0}, Eigen::Vector3d(1, 0, 1), kPi));
  p.grip_points = {{"base", {a * 0.6, width / 2, t}}};
  return p;
}

/// A T: a flange along x centred on a stem along z, extruded along y; the half turn about the
/// stem's axis is a symmetry.
Part tBracket(Draw& draw, double size) {
  const double width = size * draw.uniform(0.25, 0.6),
               t = std::max(1.5, size * draw.uniform(0.05, 0.1));
  const double height = size * draw.uniform(0.4, 0.9);
  Part p;
  p.components.push_back(boxMesh({-size / 2, 0, 0}, {size / 2, width, t}));
  p.components.push_back(boxMesh({-t / 2, 0.01, t - 0.01}, {t / 2, width - 0.01, height}));
  p.symmetry.discrete.push_back(rotationAbout({0, width / 2, 0}, Eigen::Vector3d::UnitZ(), kPi));
  p.grip_points = {{"flange", {size / 4, width / 2, t}}};
  return p;
}

/// A U channel: a base along x with two walls, extruded along y; symmetric under the half turn
/// about the vertical axis through its middle.
Part uChannel(Draw& draw, double size) {
  const double width = size * draw.uniform(0.3, 1.0),
               t = std::max(1.5, size * draw.uniform(0.05, 0.1));
  const double height = size * draw.uniform(0.25, 0.7);
  Part p;
  p.components.push_back(boxMesh({-size / 2, 0, 0}, {size / 2, width, t}));
  p.components.push_back(
      boxMesh({-size / 2 + 0.01, 0.01, 0.01}, {-size / 2 + t, width - 0.01, height}));
  p.components.push_back(
      boxMesh({size / 2 - t, 0.01, 0.01}, {size / 2 - 0.01, width - 0.01, height}));
  p.symmetry.discrete.push_back(rotationAbout({0, width / 2, 0}, Eigen::Vector3d::UnitZ(), kPi));
  p.grip_points = {{"base", {0, width / 2, t}}};
  return p;
}

/// A regular n-sided prism along z (a hex bar, a nut), with a round bore and, sometimes, a round
/// shaft on top (a bolt). Symmetries: the n turns about z, and without a shaft the n half turns
/// that flip it end over end.
Part prism(Draw& draw, double size) {
  const int n = draw.integer(3, 8);
  const bool shaft = draw.chance(0.5);
  const double radius = shaft ? size * draw.uniform(0.15, 0.3) : size / 2;
  const double height = shaft ? radius * draw.uniform(0.5, 1.0) : size * draw.uniform(0.15, 1.0);
  PlateCell cell;
  for (int k = 0; k < n; ++k)
    for (int s = 0; s < 4; ++s) { // each side in four segments, for the hole's fan
      const double a0 = 2 * kPi * k / n, a1 = 2 * kPi * (k + 1) / n;
      const Eigen::Vector2d p0(std::cos(a0), std::sin(a0)), p1(std::cos(a1), std::sin(a1));
      cell.boundary_mm.push_back(radius * (p0 + (p1 - p0) * s / 4.0));
    }
  const bool bore = !shaft && draw.chance(0.6);
  if (bore)
    cell.hole_radius_mm = radius * std::cos(kPi / n) * draw.uniform(0.3, 0.6);
  Part p;
  p.components.push_back(extrudeCells({cell}, 0, height, kRoundSegments));
  double top = height;
  if (shaft) {
    const double r = radius * draw.uniform(0.35, 0.6) * std::cos(kPi / n);
    top = size;
    p.components.push_back(
        revolveProfile({{0, height - 0.5}, {r, height - 0.5}, {r, top}, {0, top}}, kRoundSegments));
  }
  const Eigen::Vector3d mid(0, 0, height / 2);
  for (int k = 1; k < n; ++k)
    p.symmetry.discrete.push_back(rotationAbout(mid, Eigen::Vector3d::UnitZ(), 2 * kPi * k / n));
  if (!shaft)
    for (int k = 0; k < n; ++k) // flips about the axes through corners and through side middles
      p.symmetry.discrete.push_back(rotationAbout(
          mid, Eigen::Vector3d(std::cos(kPi * k / n), std::sin(kPi * k / n), 0), kPi));
  p.grip_points = {{"top", {bore ? radius * 0.7 : 0.0, 0, top}}};
  return p;
}

/// A stepped bushing: a surface of revolution about z from a random profile of two to four
/// steps with a bore, widest at the bottom so that no flip maps it onto itself.
Part bushing(Draw& draw, double size) {
  const int steps = draw.integer(2, 4);
  const double height = size * draw.uniform(0.3, 1.0);
  double radius = size / 2;
  const double bore = radius * draw.uniform(0.0, 0.5);
  std::vector<Eigen::Vector2d> profile{{bore, 0}};
  double z = 0;
  for (int s = 0; s < steps; ++s) {
    profile.emplace_back(radius, z);
    z += height / steps * draw.uniform(0.6, 1.4);
    profile.emplace_back(radius, z);
    radius *= draw.uniform(0.45, 0.8);
    if (radius <= bore + 1.0)
      break;
  }
  profile.emplace_back(bore, z);
  Part p;
  p.components.push_back(revolveProfile(profile, 2 * kRoundSegments));
  p.symmetry.continuous_axis = SymmetryAxis{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()};
  p.grip_points = {{"top", {(bore + profile[profile.size() - 2].x()) / 2, 0, z}}};
  return p;
}

/// A round flange with n bolt holes and a hub on one side: the n turns about z.
Part flange(Draw& draw, double size) {
  const int n = draw.integer(3, 8);
  const double r_out = size / 2, r_in = r_out * draw.uniform(0.2, 0.4);
  const double t = std::max(1.5, size * draw.uniform(0.05, 0.12));
  auto cells = sectorCells(r_in, r_out, n, 8, 0, (r_in + r_out) / 2);
  const double hole = std::min((r_out - r_in) * 0.25, kPi * (r_in + r_out) / (2 * n) * 0.3);
  for (auto& c : cells)
    c.hole_radius_mm = hole;
  Part p;
  p.components.push_back(extrudeCells(cells, 0, t, kRoundSegments));
  const double hub = r_in * draw.uniform(1.3, 1.8), hub_top = t + size * draw.uniform(0.15, 0.5);
  p.components.push_back(revolveProfile(
      {{r_in * 0.999, t - 0.5}, {hub, t - 0.5}, {hub, hub_top}, {r_in * 0.999, hub_top}},
      2 * kRoundSegments));
  for (int k = 1; k < n; ++k)
    p.symmetry.discrete.push_back(
        rotationAbout(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 2 * kPi * k / n));
  p.grip_points = {{"hub", {(r_in + hub) / 2, 0, hub_top}}};
  return p;
}

/// A bar of a random star-shaped profile extruded along z: no symmetry.
Part extrusion(Draw& draw, double size) {
  const int corners = draw.integer(5, 9);
  PlateCell cell;
  std::vector<double> angles;
  for (int k = 0; k < corners; ++k)
    angles.push_back(2 * kPi * (k + draw.uniform(0.1, 0.9)) / corners);
  for (int k = 0; k < corners; ++k) {
    const double r = size / 2 * draw.uniform(0.45, 1.0);
    const Eigen::Vector2d a(r * std::cos(angles[k]), r * std::sin(angles[k]));
    cell.boundary_mm.push_back(a);
  }
  // Each side in four segments, for the fan the extrusion builds from the centre.
  std::vector<Eigen::Vector2d> boundary;
  for (std::size_t k = 0; k < cell.boundary_mm.size(); ++k) {
    const Eigen::Vector2d& a = cell.boundary_mm[k];
    const Eigen::Vector2d& b = cell.boundary_mm[(k + 1) % cell.boundary_mm.size()];
    for (int s = 0; s < 4; ++s)
      boundary.push_back(a + (b - a) * s / 4.0);
  }
  cell.boundary_mm = boundary;
  const double height = size * draw.uniform(0.1, 0.6);
  Part p;
  p.components.push_back(extrudeCells({cell}, 0, height, kRoundSegments));
  p.grip_points = {{"top", {0, 0, height}}};
  return p;
}

} // namespace

RandomPartFamily randomPartFamily(std::uint64_t seed) {
  Draw draw(seed);
  return static_cast<RandomPartFamily>(draw.integer(0, kRandomPartFamilies - 1));
}

Part randomPart(std::uint64_t seed) {
  Draw draw(seed);
  const auto family = static_cast<RandomPartFamily>(draw.integer(0, kRandomPartFamilies - 1));
  const double size = draw.scale(20, 300);
  Part p;
  switch (family) {
  case RandomPartFamily::Plate:
    p = plate(draw, size);
    break;
  case RandomPartFamily::LBracket:
    p = lBracket(draw, size);
    break;
  case RandomPartFamily::TBracket:
    p = tBracket(draw, size);
    break;
  case RandomPartFamily::UChannel:
    p = uChannel(draw, size);
    break;
  case RandomPartFamily::Prism:
    p = prism(draw, size);
    break;
  case RandomPartFamily::Bushing:
    p = bushing(draw, size);
    break;
  case RandomPartFamily::Flange:
    p = flange(draw, size);
    break;
  case RandomPartFamily::Extrusion:
    p = extrusion(draw, size);
    break;
  }
  for (auto& c : p.components)
    orientOutwards(c);
  p.name = "random-" + std::to_string(seed);
  return scaled(p, size / boundingBox(p.mesh()).sizes().maxCoeff());
}

std::string toString(RandomPartFamily family) {
  static const char* const kNames[] = {"plate", "l-bracket", "t-bracket", "u-channel",
                                       "prism", "bushing",   "flange",    "extrusion"};
  return kNames[static_cast<int>(family)];
}

std::optional<std::uint64_t> randomPartSeed(const std::string& name) {
  constexpr std::string_view kPrefix = "random-";
  if (name.size() <= kPrefix.size() || name.compare(0, kPrefix.size(), kPrefix) != 0)
    return std::nullopt;
  std::uint64_t seed = 0;
  for (std::size_t i = kPrefix.size(); i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9' || seed > (UINT64_MAX - 9) / 10)
      return std::nullopt;
    seed = seed * 10 + static_cast<std::uint64_t>(name[i] - '0');
  }
  return seed;
}

} // namespace scanpick::core
