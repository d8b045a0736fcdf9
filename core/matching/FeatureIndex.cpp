#include "core/matching/FeatureIndex.h"

#include <algorithm>
#include <nanoflann.hpp>

namespace scanpick::core {

namespace {
/// nanoflann's dataset adaptor over the feature centres.
struct CentreSource {
  const FeatureList* features = nullptr;
  [[nodiscard]] std::size_t kdtree_get_point_count() const { return features->size(); }
  [[nodiscard]] float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*features)[i].centre_mm[static_cast<Eigen::Index>(dim)];
  }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};
using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CentreSource>,
                                        CentreSource, 3, std::size_t>;
} // namespace

struct FeatureIndex::Tree {
  CentreSource source;
  KdTree tree;
  explicit Tree(const FeatureList* features)
      : source{features}, tree(3, source, nanoflann::KDTreeSingleIndexAdaptorParams(8)) {
    tree.buildIndex();
  }
};

FeatureIndex::FeatureIndex(const FeatureList& features) : m_features(features) {
  if (!m_features.empty())
    m_tree = std::make_unique<Tree>(&m_features);
}

FeatureIndex::~FeatureIndex() = default;

std::vector<int> FeatureIndex::within(const Eigen::Vector3f& centre_mm, float radius_mm) const {
  std::vector<int> out;
  if (!m_tree || !(radius_mm >= 0.0f))
    return out;
  std::vector<std::pair<std::size_t, float>> hits;
  nanoflann::SearchParams search(32, 0.0f, false);
  // nanoflann's L2_Simple works on squared distances.
  m_tree->tree.radiusSearch(centre_mm.data(), radius_mm * radius_mm, hits, search);
  out.reserve(hits.size());
  for (const auto& hit : hits)
    out.push_back(static_cast<int>(hit.first));
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace scanpick::core
