#include "core/sim/MeshBuilder.h"

#include "core/common/Error.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace scanpick::core {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Points from a to b (a included, b excluded), `n` segments.
void appendSegment(std::vector<Eigen::Vector2d>& out, const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b, int n) {
  for (int k = 0; k < n; ++k)
    out.push_back(a + (b - a) * (static_cast<double>(k) / n));
}

Eigen::Vector2d polar(double r, double a) {
  return {r * std::cos(a), r * std::sin(a)};
}

double angleAround(const Eigen::Vector2d& p, const Eigen::Vector2d& c) {
  double a = std::atan2(p.y() - c.y(), p.x() - c.x());
  return a < 0 ? a + kTwoPi : a;
}

/// Triangulates one cell into `top` (2D, counter-clockwise).
void triangulateCell(const PlateCell& cell, int hole_segments, std::vector<Eigen::Vector2d>& pts,
                     std::vector<Eigen::Vector3i>& tris) {
  const int m = static_cast<int>(cell.boundary_mm.size());
  const int base_b = static_cast<int>(pts.size());
  for (const auto& p : cell.boundary_mm)
    pts.push_back(p);
  if (cell.hole_radius_mm <= 0) {
    const int c = static_cast<int>(pts.size());
    pts.push_back(cell.center_mm);
    for (int j = 0; j < m; ++j)
      tris.emplace_back(c, base_b + j, base_b + (j + 1) % m);
    return;
  }
  // Zipper between the hole circle and the boundary, both ordered by angle around the centre.
  const int n = hole_segments;
  const int base_h = static_cast<int>(pts.size());
  for (int i = 0; i < n; ++i)
    pts.push_back(cell.center_mm + polar(cell.hole_radius_mm, kTwoPi * i / n));
  int start = 0;
  for (int j = 1; j < m; ++j)
    if (angleAround(cell.boundary_mm[j], cell.center_mm) <
        angleAround(cell.boundary_mm[start], cell.center_mm))
      start = j;
  const double a0 = angleAround(cell.boundary_mm[start], cell.center_mm);
  auto boundaryAngle = [&](int j) { // unwrapped, increasing from a0
    if (j == m)
      return a0 + kTwoPi;
    double a = angleAround(cell.boundary_mm[(start + j) % m], cell.center_mm);
    return a < a0 ? a + kTwoPi : a;
  };
  auto hole = [&](int i) { return base_h + i % n; };
  auto bnd = [&](int j) { return base_b + (start + j) % m; };
  int i = 0, j = 0;
  while (i < n || j < m) {
    const double next_hole = kTwoPi * (i + 1) / n;
    if (j == m || (i < n && next_hole <= boundaryAngle(j + 1))) {
      tris.emplace_back(hole(i + 1), hole(i), bnd(j));
      ++i;
    } else {
      tris.emplace_back(bnd(j), bnd(j + 1), hole(i));
      ++j;
    }
  }
}

} // namespace

void orientOutwards(TriangleMesh& mesh) {
  if (signedVolume(mesh) < 0)
    for (auto& t : mesh.triangles)
      std::swap(t[1], t[2]);
}

TriangleMesh boxMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices_mm.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                               k & 4 ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  orientOutwards(m);
  return m;
}

TriangleMesh revolveProfile(const std::vector<Eigen::Vector2d>& profile_rz, int segments) {
  if (profile_rz.size() < 3 || segments < 3)
    throw Error("revolveProfile needs a profile of at least 3 points and 3 segments");
  TriangleMesh m;
  // Ring index per profile vertex: a single pole vertex for points on the axis.
  std::vector<int> first(profile_rz.size());
  std::vector<bool> pole(profile_rz.size());
  for (std::size_t k = 0; k < profile_rz.size(); ++k) {
    first[k] = static_cast<int>(m.vertices_mm.size());
    pole[k] = profile_rz[k].x() <= 1e-12;
    const int count = pole[k] ? 1 : segments;
    for (int s = 0; s < count; ++s) {
      const Eigen::Vector2d xy = polar(profile_rz[k].x(), kTwoPi * s / segments);
      m.vertices_mm.emplace_back(xy.x(), xy.y(), profile_rz[k].y());
    }
  }
  auto at = [&](std::size_t k, int s) { return pole[k] ? first[k] : first[k] + s % segments; };
  for (std::size_t k = 0; k < profile_rz.size(); ++k) {
    const std::size_t l = (k + 1) % profile_rz.size();
    if (pole[k] && pole[l])
      continue;
    for (int s = 0; s < segments; ++s) {
      const int a = at(k, s), b = at(l, s), c = at(l, s + 1), d = at(k, s + 1);
      if (!pole[l])
        m.triangles.emplace_back(a, b, c);
      if (!pole[k])
        m.triangles.emplace_back(a, c, d);
    }
  }
  orientOutwards(m);
  return m;
}

std::vector<PlateCell> rectangleCells(double x0, double x1, double y0, double y1, int nx, int ny,
                                      int per_side) {
  std::vector<PlateCell> cells;
  for (int iy = 0; iy < ny; ++iy)
    for (int ix = 0; ix < nx; ++ix) {
      const double ax = x0 + (x1 - x0) * ix / nx, bx = x0 + (x1 - x0) * (ix + 1) / nx;
      const double ay = y0 + (y1 - y0) * iy / ny, by = y0 + (y1 - y0) * (iy + 1) / ny;
      PlateCell c;
      appendSegment(c.boundary_mm, {ax, ay}, {bx, ay}, per_side);
      appendSegment(c.boundary_mm, {bx, ay}, {bx, by}, per_side);
      appendSegment(c.boundary_mm, {bx, by}, {ax, by}, per_side);
      appendSegment(c.boundary_mm, {ax, by}, {ax, ay}, per_side);
      c.center_mm = {(ax + bx) / 2, (ay + by) / 2};
      cells.push_back(c);
    }
  return cells;
}

std::vector<PlateCell> sectorCells(double r_in_mm, double r_out_mm, int sectors, int arc_segments,
                                   double start_rad, double center_radius_mm) {
  std::vector<PlateCell> cells;
  const int total = sectors * arc_segments;
  auto angle = [&](int k) { return start_rad + kTwoPi * k / total; };
  const int radial = std::max(2, static_cast<int>(std::lround((r_out_mm - r_in_mm) / 4.0)));
  for (int s = 0; s < sectors; ++s) {
    const int k0 = s * arc_segments, k1 = (s + 1) * arc_segments;
    PlateCell c;
    appendSegment(c.boundary_mm, polar(r_in_mm, angle(k0)), polar(r_out_mm, angle(k0)), radial);
    for (int k = k0; k < k1; ++k)
      c.boundary_mm.push_back(polar(r_out_mm, angle(k)));
    appendSegment(c.boundary_mm, polar(r_out_mm, angle(k1)), polar(r_in_mm, angle(k1)), radial);
    for (int k = k1; k > k0; --k)
      c.boundary_mm.push_back(polar(r_in_mm, angle(k)));
    c.center_mm = polar(center_radius_mm, (angle(k0) + angle(k1)) / 2);
    cells.push_back(c);
  }
  return cells;
}

TriangleMesh extrudeCells(const std::vector<PlateCell>& cells, double z0_mm, double z1_mm,
                          int hole_segments) {
  std::vector<Eigen::Vector2d> pts;
  std::vector<Eigen::Vector3i> tris;
  for (const auto& c : cells)
    triangulateCell(c, hole_segments, pts, tris);
  TriangleMesh top;
  for (const auto& p : pts)
    top.vertices_mm.emplace_back(p.x(), p.y(), z1_mm);
  top.triangles = tris;
  top = welded(top, 1e-6);
  // Directed boundary edges: those whose reverse is not in the triangulation.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : top.triangles)
    for (int k = 0; k < 3; ++k)
      ++directed[{t[k], t[(k + 1) % 3]}];
  const int n = static_cast<int>(top.vertices_mm.size());
  TriangleMesh m = top;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d v = top.vertices_mm[i];
    v.z() = z0_mm;
    m.vertices_mm.push_back(v);
  }
  for (const auto& t : top.triangles)
    m.triangles.emplace_back(t[0] + n, t[2] + n, t[1] + n);
  for (const auto& [edge, count] : directed) {
    if (directed.count({edge.second, edge.first}))
      continue;
    const int a = edge.first, b = edge.second;
    m.triangles.emplace_back(a + n, b + n, b);
    m.triangles.emplace_back(a + n, b, a);
  }
  orientOutwards(m);
  return m;
}

TriangleMesh bentBar(const Eigen::Vector3d& center_mm, const Eigen::Vector3d& u,
                     const Eigen::Vector3d& v, double arc_radius_mm, double bar_radius_mm,
                     double angle0_rad, double angle1_rad, int arc_segments, int bar_segments) {
  TriangleMesh m;
  const Eigen::Vector3d w = u.cross(v).normalized();
  for (int i = 0; i <= arc_segments; ++i) {
    const double a = angle0_rad + (angle1_rad - angle0_rad) * i / arc_segments;
    const Eigen::Vector3d radial = std::cos(a) * u + std::sin(a) * v;
    const Eigen::Vector3d axis_point = center_mm + arc_radius_mm * radial;
    for (int j = 0; j < bar_segments; ++j) {
      const double b = kTwoPi * j / bar_segments;
      m.vertices_mm.push_back(axis_point +
                              bar_radius_mm * (std::cos(b) * radial + std::sin(b) * w));
    }
  }
  for (int i = 0; i < arc_segments; ++i)
    for (int j = 0; j < bar_segments; ++j) {
      const int a = i * bar_segments + j, b = i * bar_segments + (j + 1) % bar_segments;
      m.triangles.emplace_back(a, b, b + bar_segments);
      m.triangles.emplace_back(a, b + bar_segments, a + bar_segments);
    }
  for (int end = 0; end < 2; ++end) {
    const int ring = end == 0 ? 0 : arc_segments * bar_segments;
    const double a = end == 0 ? angle0_rad : angle1_rad;
    const int c = static_cast<int>(m.vertices_mm.size());
    m.vertices_mm.push_back(center_mm + arc_radius_mm * (std::cos(a) * u + std::sin(a) * v));
    for (int j = 0; j < bar_segments; ++j) {
      const int p = ring + j, q = ring + (j + 1) % bar_segments;
      if (end == 0)
        m.triangles.emplace_back(c, q, p);
      else
        m.triangles.emplace_back(c, p, q);
    }
  }
  orientOutwards(m);
  return m;
}

} // namespace scanpick::core
