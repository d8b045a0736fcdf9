#pragma once
/// @file SurfaceEnds.h
/// Beyond the thesis: the pose's error along a direction ICP hardly pins, read from where the
/// part's surface ends along it. Point-to-plane ICP lets a cup or a pipe lying on its side slide
/// along its axis, a plate seen face-on in its own plane, a bar seen from the side along its
/// length: only the few points on end faces and outline walls, seen edge-on, hold them there, and
/// a pose stays a few tenths of a millimetre off (docs/design-notes-refinement.md).
///
/// Where the surface ends, the scan does not say to within a pixel: the last point lies up to a
/// pixel short of the edge. But it does so at both ends alike, so the middle between the two ends
/// is where the part's middle is, to a few hundredths of a millimetre when each end is seen over
/// many cells across the direction. A taught view, scanned the same way, holds its ends the same
/// way: the shift that puts the scene's ends on the view's is the pose's error along the direction.
/// Cells where a neighbour hides the part's end, or where the two cameras see a different part of
/// the surface, disagree with the others and are left out.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace scanpick::core {

/// How findAxialEnds reads the ends from the points.
struct AxialEndsOptions {
  double band_inside_mm = 1.5;  ///< the wall band reaches this far inside the outer radius
  double band_outside_mm = 0.5; ///< and this far outside it
  double bin_deg = 10.0;        ///< the turns about the axis are read in bins this wide
  /// A bin's last point counts for its end when it lies this close to the median of all bins'
  /// (the others end where something hides the wall: a neighbour, the part's own detail).
  double agreement_mm = 0.5;
  int min_bins = 6; ///< fewer agreeing bins: the end is not seen
  /// The line of sight to the axis's point must be within asin(this) of square to the axis (44°):
  /// an end seen face-on shows its face, not where its wall ends.
  double max_sight_cos = 0.7;
  /// With normals: a point counts only when its normal lies within acos(this) of pointing away
  /// from the axis (60°), on the wall. An end face seen at an angle would otherwise end that side
  /// with the face's noisy depths instead of the wall's last pixel.
  double min_radial_normal = 0.5;
};

/// The two ends of a surface of revolution's outer wall along its axis, as heights (mm) along the
/// axis's direction from its point; unset where the points do not show that end cleanly.
struct AxialEnds {
  std::optional<double> low_mm, high_mm;
};

/// The outer radius of a surface of revolution: the 99th percentile of the points' distances from
/// the axis (point `axis_point_mm`, unit `axis_direction`); 0 without points.
double outerRadius(const std::vector<Eigen::Vector3f>& points_mm,
                   const Eigen::Vector3d& axis_point_mm, const Eigen::Vector3d& axis_direction);

/// The ends of the wall at `radius_mm` about the axis among `points_mm` (the axis in their frame),
/// seen from `viewpoint_mm`: of the points within the wall band at heights in [min_height_mm,
/// max_height_mm] (and, given `normals` (one per point; NaN: none), facing away from the axis),
/// the lowest and the highest of each bin of turns, averaged over the bins that agree. Nothing when
/// the line of sight is too close to the axis (AxialEndsOptions).
AxialEnds findAxialEnds(const std::vector<Eigen::Vector3f>& points_mm,
                        const Eigen::Vector3d& axis_point_mm, const Eigen::Vector3d& axis_direction,
                        double radius_mm, const Eigen::Vector3d& viewpoint_mm, double min_height_mm,
                        double max_height_mm, const AxialEndsOptions& options = {},
                        const std::vector<Eigen::Vector3f>& normals = {});

/// The shift along the axis (mm, towards its direction) that puts the scene's ends on the view's.
/// An end counts when both see it and its difference is at most `max_shift_mm` (else the scene's
/// "end" is something else: a neighbour, or the other end where the wall is hidden); the mean of
/// both ends' differences when both count and they differ by at most `max_disagreement_mm`, else
/// the one that counts; nothing when none does or the two disagree.
std::optional<double> axialShift(const AxialEnds& view, const AxialEnds& scene, double max_shift_mm,
                                 double max_disagreement_mm);

/// How outlineShift compares the ends.
struct OutlineShiftOptions {
  double cell_mm = 3.0;             ///< the cells across the direction
  double agreement_mm = 0.5;        ///< a cell counts when its end lies this close to the median's
  int min_cells = 6;                ///< fewer agreeing cells: that side does not count
  double max_shift_mm = 2.0;        ///< a side's shift beyond this is something else's end
  double max_disagreement_mm = 0.5; ///< both sides count only when their shifts agree this well
  double confirm_mm = 1.0;          ///< how far the other views may reach beyond a view's end
};

/// The shift (mm) along the unit `direction` that puts the ends of `view_mm` (the taught view's
/// points) on those of `scene_mm` (the scene's points on the part, in the same frame): per cell
/// across the direction, the lowest and the highest point of each; the mean of both sides' median-
/// agreeing cells when both shifts are within max_shift_mm and agree within max_disagreement_mm,
/// nothing otherwise: one side alone would keep the difference between the two scans' pixel
/// shortfalls, which a flat face seen at another angle changes. With `other_views_mm` (the points
/// of the part's other views, in the same frame), a view's end counts only where they reach no
/// farther than options.confirm_mm beyond it: a view cut from a cluttered scan ends where a
/// neighbour hid it, and the other views see past that.
std::optional<double>
outlineShift(const std::vector<Eigen::Vector3f>& view_mm,
             const std::vector<Eigen::Vector3f>& scene_mm, const Eigen::Vector3d& direction,
             const std::vector<const std::vector<Eigen::Vector3f>*>& other_views_mm = {},
             const OutlineShiftOptions& options = {});

} // namespace scanpick::core
