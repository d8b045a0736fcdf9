#pragma once
/// @file RevolutionAxis.h
/// Beyond the thesis, for near-symmetric parts: the axis about which a taught view's surface is a
/// surface of revolution, such as a pipe with flanges seen from the side, whose bolt holes face
/// away from the camera. Turned about that axis the view matches itself, so nothing in it tells
/// the part's turn about the axis: the recognizer reports that axis with each detection made by
/// such a view (Detection::free_turn_axis), and the turn it reports is only one of many.
///
/// A view that is a surface of revolution but for a detail (a cup whose handle shows) fits an axis
/// with fewer of its normals; the detail (detailPoints) then tells the turn where a scan sees it.
///
/// The fit is the line-geometry one (Pottmann and Wallner, "Computational Line Geometry"): on a
/// surface of revolution every normal line meets the axis, i.e. ((p − c) × n) · a = 0 for each
/// point p with normal n, axis point c and direction a. That is linear in (a, c × a); the
/// direction is the smallest eigenvector of the Schur complement of the 6 × 6 normal matrix. It is
/// repeated twice on the inliers of the previous fit, so a detail does not pull the axis off.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

namespace scanpick::core {

/// An axis in the model frame.
struct RevolutionAxis {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();   ///< on the axis, nearest the centroid
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ(); ///< unit
  /// Share of the points that can tell (with a normal, off the axis, and not facing along it as
  /// a flat end face does) whose normal lies within the angle tolerance of the plane through the
  /// axis and the point.
  double inlier_share = 0.0;

  /// The turn by `angle_rad` about this axis (model frame → model frame).
  [[nodiscard]] Eigen::Isometry3d turn(double angle_rad) const {
    return Eigen::Translation3d(point_mm) * Eigen::AngleAxisd(angle_rad, direction) *
           Eigen::Translation3d(-point_mm);
  }
};

/// Fits the axis of revolution of `points_mm` with unit `normals` (entries with a non-finite
/// normal are skipped). Returns nothing when fewer than 20 points have normals or can tell, when
/// the normals do not pin down an axis (a single plane, whose every normal is an axis), or when
/// fewer than `min_inlier_share` of the points agree within `angle_tolerance_rad`. The defaults
/// (10°, 98 %) accept a flanged pipe seen from the side (100 %) and reject a cup whose handle
/// shows (93–95 %) and a plate with a hook (≤ 48 %).
std::optional<RevolutionAxis> fitRevolutionAxis(const std::vector<Eigen::Vector3f>& points_mm,
                                                const std::vector<Eigen::Vector3f>& normals,
                                                double angle_tolerance_rad = 0.17,
                                                double min_inlier_share = 0.98);

/// `axis` moved to where the points of the surface of revolution lie best on one: fitted on the
/// normals alone, a view's axis sits a few tenths of a millimetre and degree off (the normals are
/// estimated over a radius from noisy points), which a turn about it moves the part by. Of the
/// points facing away from the axis (normals within 60° of radial; `excluded` left out, such as a
/// cup's handle), each at its height should lie as far from the axis as its neighbours at that
/// height (a wall): Gauss-Newton on those differences over the axis's direction and place, each
/// step's outliers (beyond 3 robust standard deviations) left out. Returns `axis` unchanged when
/// fewer than 20 points can tell or a step does not lower the spread; the point stays the one
/// nearest the points' centroid, the inlier share as it was.
RevolutionAxis refineRevolutionAxis(const std::vector<Eigen::Vector3f>& points_mm,
                                    const std::vector<Eigen::Vector3f>& normals,
                                    const RevolutionAxis& axis,
                                    const std::vector<std::uint32_t>& excluded = {});

/// The points off the surface of revolution about `axis` (indices into `points_mm`): those in a
/// cell of height along and distance from the axis (`cell_mm` each) whose points span less than
/// `max_span_deg` about it. The body of a cup seen from the side spans about 180° at every height
/// and distance, its handle about 15°.
std::vector<std::uint32_t> detailPoints(const std::vector<Eigen::Vector3f>& points_mm,
                                        const RevolutionAxis& axis, double cell_mm,
                                        double max_span_deg = 45.0);

/// The body a view of a surface of revolution stands for: the view's surface turned through the
/// full turn about its axis, held as the cells of height along and distance from the axis that its
/// points occupy (each widened by a cell). A view sees only part of its surface of revolution (the
/// inside of an upright cup and its rim, not the outside of the near wall); the body tells which
/// points the part itself hides from the camera or the projector at a pose, as the wall of an
/// upright cup leaves part of its inside in the projector's shadow.
class RevolvedBody {
public:
  /// The body of `points_mm` (model frame) about `axis`, in cells of `cell_mm` (> 0), leaving out
  /// the points listed in `excluded` (a detail off the surface, such as a cup's handle).
  RevolvedBody(const std::vector<Eigen::Vector3f>& points_mm, const RevolutionAxis& axis,
               double cell_mm, const std::vector<std::uint32_t>& excluded = {});

  /// Whether the straight path from `from_mm`, a point of the body's surface, to `to_mm` (both in
  /// the model frame, mm) passes through the body once it has left the cells it starts in.
  [[nodiscard]] bool blocks(const Eigen::Vector3f& from_mm, const Eigen::Vector3f& to_mm) const;

  /// Whether `p_mm` (model frame) lies in a cell of the body: on its surface, turned to any angle
  /// about the axis, within about a cell.
  [[nodiscard]] bool contains(const Eigen::Vector3f& p_mm) const;

private:
  [[nodiscard]] bool occupied(float h, float r) const;

  Eigen::Vector3f m_origin, m_along; ///< a point on the axis and its unit direction
  float m_cell = 1.0f;
  float m_h_min = 0.0f;              ///< height of the first row of cells
  int m_rows = 0, m_columns = 0;     ///< cells along (height) and away from (distance) the axis
  std::vector<std::uint8_t> m_cells; ///< rows × columns, 1 where occupied
};

} // namespace scanpick::core
