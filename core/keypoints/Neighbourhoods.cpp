#include "core/keypoints/Neighbourhoods.h"

#include "core/common/Error.h"
#include "core/common/PixelRows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>

namespace scanpick::core::detail {
namespace {

/// Pixel windows wider than this (half size) are slower than a kd-tree.
constexpr int kMaxMedianHalfWindow = 10;
constexpr int kMaxHalfWindow = 40;

struct ValidPoints {
  const PointCloud* cloud;
  const std::vector<int>* valid;
  std::size_t kdtree_get_point_count() const { return valid->size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return cloud->points_mm[static_cast<std::size_t>((*valid)[i])][static_cast<Eigen::Index>(dim)];
  }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, ValidPoints>,
                                                   ValidPoints, 3>;

double rayAngle(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const double c = static_cast<double>(a.normalized().dot(b.normalized()));
  return std::acos(std::clamp(c, -1.0, 1.0));
}

/// The sum of q − p over the pixels q of `window` in the coordinate arrays `xs`, `ys`, `zs`
/// (`width` per row, 8 readable past the last pixel) within `r2` (squared mm) of p, and their
/// count. Eight pixels at a time (forEachPixelChunk; built also for AVX2): the squared distance
/// summed as Eigen sums it, so that a pixel is within exactly when forEachWithin finds it. The
/// float offsets are summed as doubles (exactly).
[[gnu::target_clones("avx2", "default")]] std::size_t
sumOffsetsInWindow(const float* xs, const float* ys, const float* zs, std::size_t width,
                   const PixelWindow& window, const Eigen::Vector3f& p, float r2, double sum[3]) {
  using Doubles = double __attribute__((vector_size(32)));
  Doubles sx{}, sy{}, sz{};
  Ints8 found{};
  const auto add = [](Doubles& total, Floats8 offsets) {
    total +=
        __builtin_convertvector(__builtin_shufflevector(offsets, offsets, 0, 1, 2, 3), Doubles);
    total +=
        __builtin_convertvector(__builtin_shufflevector(offsets, offsets, 4, 5, 6, 7), Doubles);
  };
  forEachPixelChunk(xs, ys, zs, width, window, p,
                    [&](std::size_t, const Floats8& dx, const Floats8& dy, const Floats8& dz,
                        const Floats8& d_sq, const Ints8& in_window) {
                      const Ints8 within = (d_sq <= r2) & in_window;
                      found -= within; // true lanes are -1
                      const Floats8 zero{};
                      add(sx, within ? dx : zero);
                      add(sy, within ? dy : zero);
                      add(sz, within ? dz : zero);
                    });
  sum[0] = sum[1] = sum[2] = 0.0;
  std::size_t n = 0;
  for (int k = 0; k < 4; ++k) {
    sum[0] += sx[k];
    sum[1] += sy[k];
    sum[2] += sz[k];
  }
  for (int k = 0; k < 8; ++k)
    n += std::size_t(found[k]);
  return n;
}

} // namespace

struct Neighbourhoods::Tree {
  ValidPoints adaptor;
  KdTree index;
  Tree(const PointCloud& cloud, const std::vector<int>& valid)
      : adaptor{&cloud, &valid}, index(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    index.buildIndex();
  }
};

Neighbourhoods::Neighbourhoods(const PointCloud& cloud, double max_radius_mm) : m_cloud(cloud) {
  cloud.validate();
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (isValid(cloud.points_mm[i]))
      m_valid.push_back(static_cast<int>(i));
  if (cloud.isOrganized() && m_valid.size() > 16) {
    // The angle between the rays of neighbouring pixels gives the window that holds a ball;
    // a low percentile is safe towards the image border, where pixels subtend less.
    std::vector<double> angles, depths;
    const std::uint32_t w = cloud.width, h = cloud.height;
    const std::uint32_t row_step = std::max<std::uint32_t>(1, h / 64);
    for (std::uint32_t r = 0; r + 1 < h; r += row_step)
      for (std::uint32_t c = 0; c + 1 < w; ++c) {
        const auto& p = cloud.points_mm[static_cast<std::size_t>(r) * w + c];
        if (!isValid(p))
          continue;
        const auto& right = cloud.points_mm[static_cast<std::size_t>(r) * w + c + 1];
        const auto& down = cloud.points_mm[static_cast<std::size_t>(r + 1) * w + c];
        if (isValid(right))
          angles.push_back(rayAngle(p, right));
        if (isValid(down))
          angles.push_back(rayAngle(p, down));
        depths.push_back(static_cast<double>(p.norm()));
      }
    if (angles.size() >= 32) {
      std::sort(angles.begin(), angles.end());
      m_pixel_angle = angles[angles.size() / 20];
      std::nth_element(depths.begin(), depths.begin() + static_cast<long>(depths.size() / 2),
                       depths.end());
      const double depth = depths[depths.size() / 2];
      if (m_pixel_angle > 1e-6 && depth > 2 * max_radius_mm &&
          std::asin(max_radius_mm / depth) / m_pixel_angle <= kMaxMedianHalfWindow)
        m_organized = true;
    }
  }
  if (!m_organized) {
    m_tree = std::make_unique<Tree>(m_cloud, m_valid);
    return;
  }
  m_pixels = PixelCoordinates(cloud.size());
  for (const int i : m_valid)
    m_pixels.set(static_cast<std::size_t>(i), cloud.points_mm[static_cast<std::size_t>(i)]);
}

std::pair<Eigen::Vector3d, std::size_t> Neighbourhoods::offsetSum(int index,
                                                                  double radius_mm) const {
  const Eigen::Vector3f p = m_cloud.points_mm[static_cast<std::size_t>(index)];
  if (!m_organized) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t found = 0;
    forEachWithin(index, radius_mm, [&](int j) {
      sum += (m_cloud.points_mm[static_cast<std::size_t>(j)] - p).cast<double>();
      ++found;
    });
    return {sum, found};
  }
  const int half = halfWindow(p, radius_mm);
  const int w = static_cast<int>(m_cloud.width), h = static_cast<int>(m_cloud.height);
  const int row = index / w, col = index % w;
  double sum[3];
  const PixelWindow window{std::max(0, col - half), std::min(w - 1, col + half),
                           std::max(0, row - half), std::min(h - 1, row + half)};
  const std::size_t found = sumOffsetsInWindow(
      m_pixels.x.data(), m_pixels.y.data(), m_pixels.z.data(), static_cast<std::size_t>(w), window,
      p, static_cast<float>(radius_mm * radius_mm), sum);
  return {Eigen::Vector3d(sum[0], sum[1], sum[2]), found};
}

Neighbourhoods::~Neighbourhoods() = default;

int Neighbourhoods::halfWindow(const Eigen::Vector3f& p, double radius_mm) const {
  const double depth = static_cast<double>(p.norm());
  return depth > radius_mm * 1.01
             ? std::min(kMaxHalfWindow,
                        static_cast<int>(std::ceil(std::asin(radius_mm / depth) / m_pixel_angle)))
             : kMaxHalfWindow;
}

void Neighbourhoods::radius(int index, double radius_mm, std::vector<int>& out) const {
  out.clear();
  if (m_organized) {
    forEachWithin(index, radius_mm, [&](int j) { out.push_back(j); });
    return;
  }
  const Eigen::Vector3f p = m_cloud.points_mm[static_cast<std::size_t>(index)];
  const float r2 = static_cast<float>(radius_mm * radius_mm);
  std::vector<std::pair<std::uint32_t, float>> matches;
  m_tree->index.radiusSearch(p.data(), r2, matches, nanoflann::SearchParams(32, 0, false));
  out.reserve(matches.size());
  for (const auto& m : matches)
    out.push_back(m_valid[m.first]);
  std::sort(out.begin(), out.end());
}

void Neighbourhoods::nearest(int index, int n, std::vector<int>& out) const {
  out.clear();
  if (n <= 0)
    return;
  const Eigen::Vector3f p = m_cloud.points_mm[static_cast<std::size_t>(index)];
  if (m_organized) {
    int half = 1;
    while ((2 * half + 1) * (2 * half + 1) - 1 < 2 * n)
      ++half;
    const int w = static_cast<int>(m_cloud.width), h = static_cast<int>(m_cloud.height);
    const int row = index / w, col = index % w;
    thread_local std::vector<std::pair<float, int>> candidates; // no allocation per query
    candidates.clear();
    for (int r = std::max(0, row - half); r <= std::min(h - 1, row + half); ++r)
      for (int c = std::max(0, col - half); c <= std::min(w - 1, col + half); ++c) {
        const int j = r * w + c;
        const auto& q = m_cloud.points_mm[static_cast<std::size_t>(j)];
        if (j != index && isValid(q))
          candidates.emplace_back((q - p).squaredNorm(), j);
      }
    const auto keep = std::min<std::size_t>(static_cast<std::size_t>(n), candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<long>(keep),
                      candidates.end());
    for (std::size_t k = 0; k < keep; ++k)
      out.push_back(candidates[k].second);
    return;
  }
  const std::size_t want = std::min(m_valid.size(), static_cast<std::size_t>(n) + 1);
  std::vector<std::uint32_t> ids(want);
  std::vector<float> dist(want);
  const std::size_t found = m_tree->index.knnSearch(p.data(), want, ids.data(), dist.data());
  for (std::size_t k = 0; k < found && static_cast<int>(out.size()) < n; ++k)
    if (m_valid[ids[k]] != index)
      out.push_back(m_valid[ids[k]]);
}

} // namespace scanpick::core::detail
