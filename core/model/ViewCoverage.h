#pragma once
/// @file ViewCoverage.h
/// Which directions a part can be seen from are covered by its taught views: the operator's check
/// that no side of the part is missing from the model.

#include "core/model/TaughtModel.h"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace scanpick::core {

/// How far a taught view reaches.
struct ViewCoverageOptions {
  /// A view recognizes the part seen up to this angle from its own viewing direction (degrees).
  /// The default is where recall, measured against that angle on the random-parts suite, starts
  /// to fall (docs/user-guide.md, "View coverage").
  double tolerance_deg = 60.0;
  /// Viewing directions sampled evenly over the sphere (a part in a bin may lie any way up).
  int directions = 2000;
  /// At most this many directions to suggest for the next views.
  int suggestions = 3;
};

/// The taught views' coverage of the directions the part can be seen from (part frame).
struct ViewCoverage {
  /// From the part towards each placed view's camera, unit, part frame (TaughtModel::T_part_model;
  /// a single view's own model frame when it is the only one).
  std::vector<Eigen::Vector3d> view_directions_part;
  std::size_t unplaced = 0; ///< views left out: they do not know their place in the part
  double covered = 0.0;     ///< share of directions within the tolerance of a placed view
  /// Directions to teach next, most isolated first: each is the uncovered direction farthest from
  /// every view and earlier suggestion; together they cover what the views leave out, or most of
  /// it.
  std::vector<Eigen::Vector3d> missing_part;
};

/// The coverage of `views` (the views of one part). Views that know their place in the part
/// (T_part_model) are placed in its frame; with no such view the first view alone is counted. A
/// view of the part seen from every side (TaughtModel::all_around) covers every direction.
/// Deterministic. Throws Error when `views` is empty or the options are out of range.
ViewCoverage viewCoverage(const std::vector<std::shared_ptr<const TaughtModel>>& views,
                          const ViewCoverageOptions& options = {});

} // namespace scanpick::core
