#include "core/preprocess/SceneSplit.h"

#include "core/common/Error.h"
#include "core/common/Log.h"
#include "core/preprocess/KMeans.h"

#include <algorithm>
#include <limits>
#include <nanoflann.hpp>
#include <numeric>

namespace scanpick::core {
namespace {

/// nanoflann adaptor over the x, y of chosen projected points.
struct Projected2d {
  const std::vector<Eigen::Vector3f>* points;
  std::vector<int> ids;
  std::size_t kdtree_get_point_count() const { return ids.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*points)[static_cast<std::size_t>(ids[i])][static_cast<Eigen::Index>(dim)];
  }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};
using Tree2d = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Projected2d>,
                                                   Projected2d, 2>;

constexpr int kMaxKMeansRuns = 10;

/// One cloud per label (0 .. objects-1) from the input's points; organized inputs give each
/// object its bounding pixel window.
std::vector<PointCloud> buildObjects(const PointCloud& scene, const std::vector<int>& labels,
                                     int objects) {
  std::vector<PointCloud> out(static_cast<std::size_t>(objects));
  const auto copyChannels = [&](PointCloud& dst, std::size_t to, std::size_t from) {
    dst.points_mm[to] = scene.points_mm[from];
    if (!scene.normals.empty())
      dst.normals[to] = scene.normals[from];
    if (!scene.colors.empty())
      dst.colors[to] = scene.colors[from];
    if (!scene.intensity.empty())
      dst.intensity[to] = scene.intensity[from];
    if (!scene.confidence.empty())
      dst.confidence[to] = scene.confidence[from];
  };
  const auto allocate = [&](PointCloud& dst, std::uint32_t w, std::uint32_t h, bool fill_nan) {
    dst.width = w;
    dst.height = h;
    const std::size_t n = static_cast<std::size_t>(w) * h;
    dst.points_mm.assign(n, fill_nan ? invalidPoint() : Eigen::Vector3f::Zero());
    if (!scene.normals.empty())
      dst.normals.assign(n, invalidPoint());
    if (!scene.colors.empty())
      dst.colors.assign(n, {0, 0, 0});
    if (!scene.intensity.empty())
      dst.intensity.assign(n, 0.0f);
    if (!scene.confidence.empty())
      dst.confidence.assign(n, 0);
  };
  if (scene.isOrganized()) {
    struct Window {
      std::uint32_t r0 = UINT32_MAX, r1 = 0, c0 = UINT32_MAX, c1 = 0;
    };
    std::vector<Window> win(out.size());
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (labels[i] >= 0) {
        auto& w = win[static_cast<std::size_t>(labels[i])];
        const auto r = static_cast<std::uint32_t>(i / scene.width),
                   c = static_cast<std::uint32_t>(i % scene.width);
        w.r0 = std::min(w.r0, r), w.r1 = std::max(w.r1, r), w.c0 = std::min(w.c0, c),
        w.c1 = std::max(w.c1, c);
      }
    for (std::size_t o = 0; o < out.size(); ++o)
      allocate(out[o], win[o].c1 - win[o].c0 + 1, win[o].r1 - win[o].r0 + 1, true);
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (labels[i] >= 0) {
        const auto o = static_cast<std::size_t>(labels[i]);
        const std::size_t r = i / scene.width - win[o].r0, c = i % scene.width - win[o].c0;
        copyChannels(out[o], r * out[o].width + c, i);
      }
  } else {
    std::vector<std::uint32_t> sizes(out.size(), 0), filled(out.size(), 0);
    for (int l : labels)
      if (l >= 0)
        ++sizes[static_cast<std::size_t>(l)];
    for (std::size_t o = 0; o < out.size(); ++o)
      allocate(out[o], sizes[o], 1, false);
    for (std::size_t i = 0; i < labels.size(); ++i)
      if (labels[i] >= 0) {
        const auto o = static_cast<std::size_t>(labels[i]);
        copyChannels(out[o], filled[o]++, i);
      }
  }
  return out;
}

/// Renumbers labels so that object 0 is the largest (ties: the lower old label).
int relabelBySize(std::vector<int>& labels, int objects) {
  std::vector<std::size_t> size(static_cast<std::size_t>(objects), 0);
  for (int l : labels)
    if (l >= 0)
      ++size[static_cast<std::size_t>(l)];
  std::vector<int> order(static_cast<std::size_t>(objects));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return size[static_cast<std::size_t>(a)] > size[static_cast<std::size_t>(b)];
  });
  std::vector<int> new_label(static_cast<std::size_t>(objects), -1);
  int kept = 0;
  for (int old : order)
    if (size[static_cast<std::size_t>(old)] > 0)
      new_label[static_cast<std::size_t>(old)] = kept++;
  for (int& l : labels)
    if (l >= 0)
      l = new_label[static_cast<std::size_t>(l)];
  return kept;
}

/// Fragments (clusters below the count's minimum) join the object whose projected point is
/// nearest to the fragment's projected centroid.
void assignFragments(const ObjectCount& count, std::vector<int>& labels) {
  if (static_cast<std::size_t>(count.count) >= count.clusters.size())
    return;
  // Every 4th object point is dense enough to find the nearest object (points lie ~1 mm apart)
  // and makes the tree 4x cheaper.
  Projected2d big{&count.projected_mm, {}};
  for (int c = 0; c < count.count; ++c) {
    const auto& members = count.clusters[static_cast<std::size_t>(c)];
    for (std::size_t m = 0; m < members.size(); m += 4)
      big.ids.push_back(members[m]);
  }
  Tree2d tree(2, big, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  for (std::size_t c = static_cast<std::size_t>(count.count); c < count.clusters.size(); ++c) {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int j : count.clusters[c])
      centroid += count.projected_mm[static_cast<std::size_t>(j)].head<2>().cast<double>();
    const Eigen::Vector2f query =
        (centroid / static_cast<double>(count.clusters[c].size())).cast<float>();
    std::uint32_t nearest = 0;
    float dist_sq = 0;
    tree.knnSearch(query.data(), 1, &nearest, &dist_sq);
    const int object = labels[static_cast<std::size_t>(big.ids[nearest])];
    for (int j : count.clusters[c])
      labels[static_cast<std::size_t>(j)] = object;
  }
}

} // namespace

SceneSplit splitIntoObjects(const PointCloud& scene_mm, const SensorModel& sensor,
                            const ClusteringParams& params, std::uint64_t seed,
                            const ProgressFn& progress) {
  scene_mm.validate();
  SceneSplit split;
  split.point_labels.assign(scene_mm.size(), -1);
  if (!params.enabled) {
    for (std::size_t i = 0; i < scene_mm.size(); ++i)
      if (isValid(scene_mm.points_mm[i]))
        split.point_labels[i] = 0;
    if (scene_mm.hasValidPoint())
      split.objects.push_back(scene_mm);
    return split;
  }

  split.count = countObjects(scene_mm, sensor, params, subProgress(progress, 0.0, 0.4));
  const ObjectCount& count = split.count;
  if (count.count == 0) {
    logger()->info("object count found no cluster of {} points or more: no object",
                   params.count_min_points);
    return split;
  }
  const std::size_t n = count.source_indices.size();
  std::vector<int> labels(n, -1); // per valid point

  if (params.method == ClusteringParams::Method::KMeans) {
    // §3.3: k-means on the 3D points; clusters of fewer than min_cluster_points are outliers,
    // removed before clustering again from the beginning.
    std::vector<int> active(n);
    std::iota(active.begin(), active.end(), 0);
    for (int run = 0; run < kMaxKMeansRuns && !active.empty(); ++run) {
      std::vector<Eigen::Vector3f> points(active.size());
      for (std::size_t a = 0; a < active.size(); ++a)
        points[a] = scene_mm.points_mm[static_cast<std::size_t>(
            count.source_indices[static_cast<std::size_t>(active[a])])];
      const KMeansResult km =
          kmeans(points, count.count, params, seed + static_cast<std::uint64_t>(run),
                 subProgress(progress, 0.4 + 0.5 * run / kMaxKMeansRuns,
                             0.4 + 0.5 * (run + 1) / kMaxKMeansRuns));
      ++split.kmeans_runs;
      std::vector<int> size(km.centres.size(), 0);
      for (int l : km.labels)
        ++size[static_cast<std::size_t>(l)];
      const bool small = std::any_of(size.begin(), size.end(),
                                     [&](int s) { return s > 0 && s < params.min_cluster_points; });
      std::fill(labels.begin(), labels.end(), -1);
      std::vector<int> still_active;
      for (std::size_t a = 0; a < active.size(); ++a) {
        const int l = km.labels[a];
        if (size[static_cast<std::size_t>(l)] >= params.min_cluster_points) {
          labels[static_cast<std::size_t>(active[a])] = l;
          still_active.push_back(active[a]);
        }
      }
      active.swap(still_active);
      if (!small)
        break;
    }
  } else {
    // Beyond the thesis: the projected clusters are the objects.
    for (int c = 0; c < count.count; ++c)
      for (int j : count.clusters[static_cast<std::size_t>(c)])
        labels[static_cast<std::size_t>(j)] = c;
    assignFragments(count, labels);
  }

  const int objects = relabelBySize(labels, count.count);
  for (std::size_t j = 0; j < n; ++j)
    split.point_labels[static_cast<std::size_t>(count.source_indices[j])] = labels[j];
  split.objects = buildObjects(scene_mm, split.point_labels, objects);
  reportProgress(progress, 1.0);
  return split;
}

} // namespace scanpick::core
