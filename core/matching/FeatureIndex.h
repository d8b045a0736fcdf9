#pragma once
/// @file FeatureIndex.h
/// A kd-tree over feature centres for the Δp look-ups of the matching (the thesis scans the whole
/// list for each look-up; this keeps the matching near-linear in the number of scene features).

#include "core/features/Feature.h"

#include <memory>
#include <vector>

namespace scanpick::core {

/// Immutable spatial index of the centres of a FeatureList. Thread-safe for concurrent queries.
class FeatureIndex {
public:
  /// Indexes the centres of `features` (the list is copied; an empty list is allowed).
  explicit FeatureIndex(const FeatureList& features);
  ~FeatureIndex();
  FeatureIndex(const FeatureIndex&) = delete;
  FeatureIndex& operator=(const FeatureIndex&) = delete;

  /// Indices of the features whose centre lies within `radius_mm` of `centre_mm`, ascending.
  [[nodiscard]] std::vector<int> within(const Eigen::Vector3f& centre_mm, float radius_mm) const;

  [[nodiscard]] const FeatureList& features() const { return m_features; }

private:
  struct Tree;
  FeatureList m_features;
  std::unique_ptr<Tree> m_tree;
};

} // namespace scanpick::core
