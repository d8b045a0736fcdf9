#include "core/ambiguity/ViewAmbiguities.h"

#include "core/ambiguity/NearSymmetry.h"
#include "core/params/ViewParams.h"

#include <Eigen/QR>
#include <cmath>
#include <spdlog/fmt/fmt.h>

namespace scanpick::core {
namespace {

/// The symmetry S as an angle, an axis and the axis's point nearest the model origin: S moves
/// the points p of its axis by nothing, so (I − R)·p = t; the minimum-norm solution is that point.
ViewSymmetry symmetryOf(const NearSymmetry& s, std::size_t view_points) {
  const Eigen::AngleAxisd rotation(s.S_model.linear());
  ViewSymmetry out;
  out.angle_deg = rotation.angle() * 180.0 / M_PI;
  out.axis = rotation.axis();
  const Eigen::Matrix3d fixed = Eigen::Matrix3d::Identity() - s.S_model.linear();
  out.point_mm = fixed.completeOrthogonalDecomposition().solve(s.S_model.translation());
  out.overlap = s.overlap;
  out.differing_share =
      view_points > 0
          ? double(std::max(s.differing.size(), s.differing_inverse.size())) / double(view_points)
          : 0.0;
  out.repeats_itself = repeatsItself(s, view_points);
  return out;
}

/// An axis in words, against the teach camera's line of sight (the model frame's z), then its
/// direction and a point on it.
std::string axisWords(const Eigen::Vector3d& direction, const Eigen::Vector3d& point_mm) {
  const double tilt_deg =
      std::acos(std::min(1.0, std::abs(direction.z()))) * 180.0 / M_PI; // from the line of sight
  const std::string where = tilt_deg < 15.0   ? "along the teach camera's line of sight"
                            : tilt_deg > 75.0 ? "across the teach camera's line of sight"
                                              : fmt::format("{:.0f}° from the teach camera's "
                                                            "line of sight",
                                                            tilt_deg);
  return fmt::format("an axis {} (direction {:.2f}, {:.2f}, {:.2f}, through {:.1f}, {:.1f}, "
                     "{:.1f} mm in the model frame)",
                     where, direction.x(), direction.y(), direction.z(), point_mm.x(), point_mm.y(),
                     point_mm.z());
}

} // namespace

ViewAmbiguities viewAmbiguities(const detail::ModelPrep& prep) {
  ViewAmbiguities out;
  out.revolution_axis = prep.axis;
  out.near_axis = prep.near_axis;
  const std::size_t view_points = prep.verify ? prep.verify->points.size() : 0;
  if (prep.near_axis && view_points > 0)
    out.asymmetric_share = double(prep.near_axis_asymmetry.size()) / double(view_points);
  out.symmetries_searched = prep.symmetry_key.has_value();
  if (prep.symmetry_key)
    out.symmetry_overlap = prep.symmetry_key->overlap;
  for (const NearSymmetry& s : prep.symmetries)
    out.symmetries.push_back(symmetryOf(s, view_points));
  return out;
}

ViewAmbiguities analyzeViewAmbiguities(const std::shared_ptr<const TaughtModel>& view,
                                       const RecognitionParams& params) {
  std::vector<std::shared_ptr<const detail::ModelPrep>> preps;
  RecognitionParams own = withViewParams(params, view->view_params);
  // The axes and the near symmetries do not depend on the surface pair table or on the joined
  // views' ICP model, which the preparation would otherwise build for matching and refinement.
  own.matching.surface_sampling_mm = 0.0;
  own.refine.enabled = false;
  return viewAmbiguities(*detail::prepareModel(preps, view, own));
}

std::vector<std::string> describeAmbiguities(const ViewAmbiguities& a) {
  std::vector<std::string> lines;
  if (a.revolution_axis)
    lines.push_back("a surface of revolution about " +
                    axisWords(a.revolution_axis->direction, a.revolution_axis->point_mm) +
                    ": no scan tells its rotation about that axis, and each detection reports the "
                    "axis as its free_turn_axis");
  if (a.near_axis)
    lines.push_back(fmt::format(
        "a surface of revolution about {} but for an asymmetric feature ({:.0f} % of its points): "
        "a detection whose scan does not show that feature reports the axis as its "
        "free_turn_axis",
        axisWords(a.near_axis->direction, a.near_axis->point_mm), 100.0 * a.asymmetric_share));
  for (const ViewSymmetry& s : a.symmetries) {
    const std::string rotation =
        fmt::format("rotated by {:.0f}° about {}", s.angle_deg, axisWords(s.axis, s.point_mm));
    lines.push_back(
        s.repeats_itself
            ? fmt::format("{}, the view falls back on itself ({:.0f} % on its surface, {:.1f} % of "
                          "its points differ): no scan tells the two poses apart, and each "
                          "detection reports the rotated pose among its alternative_poses",
                          rotation, 100.0 * s.overlap, 100.0 * s.differing_share)
            : fmt::format("{}, {:.0f} % of the view falls back on itself; the {:.0f} % of its "
                          "points that differ tell the two poses apart where a scan sees them, "
                          "and a detection whose scan does not reports the rotated pose among "
                          "its alternative_poses",
                          rotation, 100.0 * s.overlap, 100.0 * s.differing_share));
  }
  if (!a.symmetries_searched)
    lines.emplace_back("near symmetries were not searched (matching.symmetry_overlap = 0, or "
                       "verification off)");
  else if (lines.empty())
    lines.push_back(fmt::format("no rotation puts {:.0f} % of the view back on itself and it is no "
                                "surface of revolution: its surface pins every rotation",
                                100.0 * a.symmetry_overlap));
  return lines;
}

} // namespace scanpick::core
