#pragma once
/// @file ProgressShares.h
/// The shares of progress that the stages of one recognize call report, in one table.
///
/// Contract: each share is a [begin, end) range of fractions of one Recognizer::recognize (or
/// Recognizer::detect) call, the stages in the order they run, each beginning where the one
/// before ends, never decreasing, the last ending at 1 (checked at compile time below). A stage
/// reports through subProgress into its share; a stage with an empty share (begin = end) reports
/// nothing new but still checks for a cancel. recognizeViews gives each view's call an equal share
/// of its own progress, in which these ranges apply.

#include "core/common/Progress.h"

#include <array>

namespace scanpick::core {

/// One stage's share of a recognize call's progress: [begin, end).
struct ProgressShare {
  double begin = 0.0;
  double end = 0.0;
};

/// The stages' shares, in the order the stages run.
struct ProgressShares {
  ProgressShare preprocess{0.0, 0.1};        ///< floor removal and downsampling
  ProgressShare split{0.1, 0.3};             ///< the split into objects
  ProgressShare keypoints{0.3, 0.55};        ///< each object's keypoints
  ProgressShare features{0.55, 0.8};         ///< each object's features
  ProgressShare scene_pairing{0.8, 0.8};     ///< the scene paired for surface voting (no share)
  ProgressShare feature_matching{0.8, 0.95}; ///< feature matching in each object
  ProgressShare surface_voting{0.95, 0.98};  ///< surface point pair voting over the whole scene
  /// The rotations matching cannot tell apart, refinement and placing: reported done at the end.
  ProgressShare after_matching{0.98, 1.0};
};

inline constexpr ProgressShares kProgressShares{};

/// `progress` mapped into `share` of it (subProgress).
inline ProgressFn subProgress(const ProgressFn& progress, const ProgressShare& share) {
  return subProgress(progress, share.begin, share.end);
}

namespace progress_shares_check {
constexpr bool contiguousToOne(const ProgressShares& s) {
  const std::array<ProgressShare, 8> order{s.preprocess,     s.split,         s.keypoints,
                                           s.features,       s.scene_pairing, s.feature_matching,
                                           s.surface_voting, s.after_matching};
  double at = 0.0;
  for (const ProgressShare& share : order) {
    if (share.begin != at || share.end < share.begin)
      return false;
    at = share.end;
  }
  return at == 1.0;
}
} // namespace progress_shares_check

static_assert(progress_shares_check::contiguousToOne(kProgressShares),
              "progress shares must run from 0 to 1, each beginning where the one before ends");

} // namespace scanpick::core
