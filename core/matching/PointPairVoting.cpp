#include "core/matching/PointPairVoting.h"

#include "core/common/Error.h"
#include "core/common/ParallelProgress.h"
#include "core/common/Rounding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <type_traits>

namespace scanpick::core {
namespace {

constexpr float kTwoPi = 6.28318530717958647692f;
/// Cells of [-1, 1] for PairQuantizer's first guess of a cosine's bin (bin() corrects any guess;
/// a close one saves it steps).
constexpr int kGuessCells = 512;

/// The frame in which `p` is the origin and `n` the +x axis.
Eigen::Isometry3f localFrame(const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = Eigen::Quaternionf::FromTwoVectors(n, Eigen::Vector3f::UnitX()).toRotationMatrix();
  T.translation() = -(T.linear() * p);
  return T;
}

/// Rotation about x that brings a point given in a local frame into the half plane z = 0, y > 0,
/// in turns of 2π / 65536: the difference of two such angles, taken as a uint16, is their
/// difference modulo 2π.
std::uint16_t planeAngle(const Eigen::Vector3f& local) {
  const float radians = std::atan2(-local.z(), local.y());
  return static_cast<std::uint16_t>(roundHalfAway(radians * (65536.0f / kTwoPi)) & 0xFFFF);
}

/// The sampled scene's points sorted into cubic cells a little wider than the pairing radius, so
/// that a point's neighbours within the radius lie in the 27 cells around its own, with their
/// coordinates and normals in arrays padded for PairQuantizer::keysWithin.
class PairingGrid {
public:
  PairingGrid(const OrientedPoints& scene, double radius_mm)
      : m_cell_mm(radius_mm * (1.0 + 1e-5)) { // float sums may put a neighbour a hair past it
    if (!(m_cell_mm > 0.0))
      return; // nothing lies within a radius of 0
    std::vector<std::pair<Cell, std::uint32_t>> sorted;
    for (std::size_t i = 0; i < scene.points.size(); ++i)
      if (scene.points[i].allFinite())
        sorted.push_back({cellOf(scene.points[i]), static_cast<std::uint32_t>(i)});
    std::sort(sorted.begin(), sorted.end());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (auto* values : {&m_x, &m_y, &m_z, &m_nx, &m_ny, &m_nz})
      values->assign(sorted.size() + kPadding, nan);
    for (std::size_t at = 0; at < sorted.size(); ++at) {
      const std::uint32_t i = sorted[at].second;
      const Eigen::Vector3f &p = scene.points[i], &n = scene.normals[i];
      m_x[at] = p.x(), m_y[at] = p.y(), m_z[at] = p.z();
      m_nx[at] = n.x(), m_ny[at] = n.y(), m_nz[at] = n.z();
      m_ids.push_back(i);
      if (m_cells.empty() || m_cells.back().cell != sorted[at].first)
        m_cells.push_back({sorted[at].first, static_cast<std::uint32_t>(at), 0});
      m_cells.back().end = static_cast<std::uint32_t>(at + 1);
    }
  }

  /// visit(begin, end) for the points of each non-empty cell around `p` (none for a non-finite
  /// `p`): positions in arrays().
  template <typename Visit> void forEachCellNear(const Eigen::Vector3f& p, Visit&& visit) const {
    if (!p.allFinite())
      return;
    const Cell centre = cellOf(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const Cell cell{centre[0] + dx, centre[1] + dy, centre[2] + dz};
          const auto found = std::lower_bound(
              m_cells.begin(), m_cells.end(), cell,
              [](const CellRange& range, const Cell& c) { return range.cell < c; });
          if (found != m_cells.end() && found->cell == cell)
            visit(std::size_t{found->begin}, std::size_t{found->end});
        }
  }
  [[nodiscard]] PairQuantizer::PointArrays arrays() const {
    return {m_x.data(), m_y.data(), m_z.data(), m_nx.data(), m_ny.data(), m_nz.data()};
  }
  /// The scene index of the point at position `at` of arrays().
  [[nodiscard]] std::uint32_t sceneIndex(std::uint32_t at) const { return m_ids[at]; }

private:
  using Cell = std::array<std::int64_t, 3>;
  struct CellRange {
    Cell cell;
    std::uint32_t begin, end;
  };
  static constexpr std::size_t kPadding = 8;

  [[nodiscard]] Cell cellOf(const Eigen::Vector3f& p) const {
    const auto index = [&](float v) {
      return static_cast<std::int64_t>(std::clamp(std::floor(double(v) / m_cell_mm), -1e15, 1e15));
    };
    return {index(p.x()), index(p.y()), index(p.z())};
  }

  double m_cell_mm;
  std::vector<float> m_x, m_y, m_z, m_nx, m_ny, m_nz;
  std::vector<std::uint32_t> m_ids;
  std::vector<CellRange> m_cells; ///< sorted by cell
};

/// The pairs of reference point `s` with its neighbours within `radius_sq` (mm²) in `grid`, in
/// the reference's local frame `to_local`, appended to `out`: those whose key `wanted(key)` takes
/// (their angle is computed only for those). The votes are counts: the order in which the
/// neighbours are visited does not matter.
template <typename Wanted>
void pairReference(const OrientedPoints& scene, const PairingGrid& grid, std::size_t s,
                   const Eigen::Isometry3f& to_local, const PairQuantizer& quantizer,
                   float radius_sq, Wanted&& wanted, std::vector<ScenePairs::Pair>& out) {
  const Eigen::Vector3f& p = scene.points[s];
  const Eigen::Vector3f& n = scene.normals[s];
  thread_local std::vector<PairQuantizer::KeyedPoint> keyed; // no allocation per reference
  grid.forEachCellNear(p, [&](std::size_t begin, std::size_t end) {
    keyed.resize(std::max(keyed.size(), end - begin));
    const std::size_t found =
        quantizer.keysWithin(grid.arrays(), begin, end, p, n, radius_sq, keyed.data());
    for (std::size_t k = 0; k < found; ++k) {
      const std::uint32_t i = grid.sceneIndex(keyed[k].at);
      if (i != s && wanted(keyed[k].key))
        out.push_back({keyed[k].key, planeAngle(to_local * scene.points[i]), keyed[k].distance_sq});
    }
  });
}

/// PairQuantizer::keysWithin's work, eight points at a time (see there); `bounds` are the
/// quantizer's decreasing bin bounds.
[[gnu::target_clones("avx2", "default")]] std::size_t
keysWithinRange(const PairQuantizer::PointArrays& points, std::size_t begin, std::size_t end,
                const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, float radius_sq,
                float step_mm, std::uint32_t half, const std::vector<float>& bounds,
                PairQuantizer::KeyedPoint* out) {
  using Floats = float __attribute__((vector_size(32)));
  using Ints = std::int32_t __attribute__((vector_size(32)));
  using Units = std::uint32_t __attribute__((vector_size(32)));
  const Ints lane = {0, 1, 2, 3, 4, 5, 6, 7};
  const float half_step = 0.5f * step_mm;
  const auto across = static_cast<std::int32_t>(half / 2);
  // (Vectors by reference: by value they would change the ABI of the default clone.)
  const auto load = [](const float* values, std::size_t at, Floats& v) {
    std::memcpy(&v, values + at, sizeof v);
  };
  // Eight correctly rounded square roots, as std::sqrt gives each (two SSE instructions).
  const auto sqrt8 = [](Floats& v) {
    using Floats4 = float __attribute__((vector_size(16)));
    Floats4 low, high;
    std::memcpy(&low, &v, sizeof low);
    std::memcpy(&high, reinterpret_cast<const char*>(&v) + sizeof low, sizeof high);
    low = __builtin_ia32_sqrtps(low);
    high = __builtin_ia32_sqrtps(high);
    std::memcpy(&v, &low, sizeof low);
    std::memcpy(reinterpret_cast<char*>(&v) + sizeof low, &high, sizeof high);
  };
  const auto any = [](const Ints& flags) {
    std::uint64_t words[4];
    std::memcpy(words, &flags, sizeof words);
    return (words[0] | words[1] | words[2] | words[3]) != 0;
  };
  std::size_t found = 0;
  for (std::size_t at = begin; at < end; at += 8) {
    Floats x, y, z;
    load(points.x, at, x);
    load(points.y, at, y);
    load(points.z, at, z);
    const Floats dx = x - p1.x(), dy = y - p1.y(), dz = z - p1.z();
    // The kd-tree's metric: x, then y, then z (the signs of the differences square away).
    Floats metric_sq = dx * dx;
    metric_sq += dy * dy;
    metric_sq += dz * dz;
    Ints take = (metric_sq < radius_sq) & (lane < static_cast<std::int32_t>(end - at));
    if (!any(take))
      continue;
    // key()'s terms, each sum as Eigen's three-term sums: x + (y + z).
    Floats distance = dx * dx + (dy * dy + dz * dz);
    sqrt8(distance);
    const Floats ux = dx / distance, uy = dy / distance, uz = dz / distance;
    Floats nx, ny, nz;
    load(points.nx, at, nx);
    load(points.ny, at, ny);
    load(points.nz, at, nz);
    const Floats c1 = n1.x() * ux + (n1.y() * uy + n1.z() * uz);
    const Floats c2 = nx * ux + (ny * uy + nz * uz);
    const Floats c3 = n1.x() * nx + (n1.y() * ny + n1.z() * nz);
    // A bin is the number of bounds its cosine does not exceed (PairQuantizer::bin; NaN: 0).
    Ints a1 = {}, a2 = {}, a3 = {};
    for (const float bound : bounds) {
      a1 -= c1 <= bound;
      a2 -= c2 <= bound;
      a3 -= c3 <= bound;
    }
    take &= ~(distance < half_step);
    take &= ~((a3 == 0) & (a1 == across) & (a2 == across));
    if (!any(take))
      continue;
    const Units d_bin =
        __builtin_convertvector(__builtin_convertvector(distance / step_mm, Ints), Units);
    const Units key = ((d_bin * half + Units(a1)) * half + Units(a2)) * half + Units(a3);
    for (int k = 0; k < 8; ++k)
      if (take[k])
        out[found++] = {static_cast<std::uint32_t>(at) + static_cast<std::uint32_t>(k), key[k],
                        metric_sq[k]};
  }
  return found;
}

/// The accumulator cells (model point · bins + angle bin) that the `count` table entries from
/// `entries` vote for with a scene pair at `pair_alpha`, written to `cells`: the angle bin of
/// the entry's rotation less the pair's, modulo 2π. A loop the compiler vectorizes, also built for
/// AVX2.
[[gnu::target_clones("avx2", "default")]] void voteCells(const std::uint32_t* entries,
                                                         std::size_t count,
                                                         std::uint16_t pair_alpha,
                                                         std::uint32_t bins, std::uint32_t* cells) {
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t alpha = ((entries[k] >> 16) - pair_alpha) & 0xFFFF;
    cells[k] = (entries[k] & 0xFFFF) * bins + ((alpha * bins) >> 16);
  }
}

} // namespace

OrientedPoints sampleOriented(const std::vector<Eigen::Vector3f>& points_mm,
                              const std::vector<Eigen::Vector3f>& normals, double voxel_mm) {
  if (points_mm.size() != normals.size())
    throw Error("sampleOriented: points and normals differ in count");
  if (!(voxel_mm > 0.0))
    throw Error("sampleOriented: the voxel size must be positive");
  struct Sum {
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    int count = 0;
  };
  // A voxel may hold both faces of a thin wall: its points are grouped by normal direction
  // (within 90° of a group's first normal), one sample per group.
  std::map<std::tuple<long, long, long>, std::vector<Sum>> voxels;
  for (std::size_t i = 0; i < points_mm.size(); ++i) {
    const Eigen::Vector3f& p = points_mm[i];
    const Eigen::Vector3f& n = normals[i];
    if (!p.allFinite() || !n.allFinite())
      continue;
    auto& groups = voxels[{std::lround(std::floor(p.x() / voxel_mm)),
                           std::lround(std::floor(p.y() / voxel_mm)),
                           std::lround(std::floor(p.z() / voxel_mm))}];
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const Sum& s) { return s.n.dot(n.cast<double>()) > 0.0; });
    if (group == groups.end())
      group = groups.insert(groups.end(), Sum{});
    group->p += p.cast<double>();
    group->n += n.cast<double>();
    ++group->count;
  }
  OrientedPoints out;
  for (const auto& [key, groups] : voxels)
    for (const auto& s : groups) {
      if (s.n.norm() < 1e-6 * s.count)
        continue;
      out.points.push_back((s.p / s.count).cast<float>());
      out.normals.push_back(s.n.normalized().cast<float>());
    }
  return out;
}

PairQuantizer::PairQuantizer(double distance_step_mm, int angle_bins)
    : m_distance_step_mm(distance_step_mm), m_angle_bins(angle_bins) {
  if (!(distance_step_mm > 0.0) || angle_bins < 4 || angle_bins > 360)
    throw Error("point pair model: distance step must be > 0 and angle bins in [4, 360]");
  const int half = m_angle_bins / 2;
  for (int k = 1; k < half; ++k)
    m_bin_cosines.push_back(std::cos(float(k) * float(M_PI) / float(half)));
  m_bin_guess.resize(kGuessCells);
  for (int i = 0; i < kGuessCells; ++i) {
    const float centre = -1.0f + (float(i) + 0.5f) * 2.0f / float(kGuessCells);
    m_bin_guess[std::size_t(i)] = std::uint8_t(std::count_if(
        m_bin_cosines.begin(), m_bin_cosines.end(), [&](float bound) { return centre <= bound; }));
  }
}

[[gnu::always_inline]] inline int PairQuantizer::bin(float cosine) const {
  if (std::isnan(cosine))
    return 0;
  const int cell =
      std::clamp(int((cosine + 1.0f) * (0.5f * float(kGuessCells))), 0, kGuessCells - 1);
  // The bounds decrease: the cosine does not exceed exactly the first `b` of them.
  int b = m_bin_guess[std::size_t(cell)];
  const int bounds = int(m_bin_cosines.size());
  while (b < bounds && cosine <= m_bin_cosines[std::size_t(b)])
    ++b;
  while (b > 0 && cosine > m_bin_cosines[std::size_t(b - 1)])
    --b;
  return b;
}

std::uint32_t PairQuantizer::key(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1,
                                 const Eigen::Vector3f& p2, const Eigen::Vector3f& n2,
                                 bool* valid) const {
  const Eigen::Vector3f d = p2 - p1;
  const float distance = d.norm();
  *valid = false;
  if (distance < 0.5f * float(m_distance_step_mm))
    return 0;
  const Eigen::Vector3f u = d / distance;
  const int half = m_angle_bins / 2;
  const int a1 = bin(n1.dot(u)), a2 = bin(n2.dot(u)), a3 = bin(n1.dot(n2));
  // Two points of one plane (normals parallel, both across the joining line) tell nothing but
  // their distance, and flat parts have very many of them: such pairs are not used.
  const int across = half / 2;
  if (a3 == 0 && a1 == across && a2 == across)
    return 0;
  const auto d_bin = static_cast<std::uint32_t>(distance / float(m_distance_step_mm));
  *valid = true;
  return ((d_bin * half + a1) * half + a2) * half + a3;
}

std::size_t PairQuantizer::keysWithin(const PointArrays& points, std::size_t begin, std::size_t end,
                                      const Eigen::Vector3f& p1, const Eigen::Vector3f& n1,
                                      float radius_sq, KeyedPoint* out) const {
  return keysWithinRange(points, begin, end, p1, n1, radius_sq, float(m_distance_step_mm),
                         static_cast<std::uint32_t>(m_angle_bins / 2), m_bin_cosines, out);
}

void PairKeySet::add(const PointPairModel& model) {
  const std::uint32_t end = model.keyEnd();
  if (m_bits.size() < (end + 63) / 64)
    m_bits.resize((end + 63) / 64, 0);
  for (std::uint32_t key = 0; key < end; ++key)
    if (model.inTable(key))
      m_bits[key >> 6] |= std::uint64_t{1} << (key & 63);
}

void PairKeySet::add(const PairKeySet& other) {
  if (m_bits.size() < other.m_bits.size())
    m_bits.resize(other.m_bits.size(), 0);
  for (std::size_t i = 0; i < other.m_bits.size(); ++i)
    m_bits[i] |= other.m_bits[i];
}

bool PairKeySet::within(const PairKeySet& other) const {
  for (std::size_t i = 0; i < m_bits.size(); ++i)
    if ((m_bits[i] & ~(i < other.m_bits.size() ? other.m_bits[i] : 0)) != 0)
      return false;
  return true;
}

bool PairKeySet::covers(const PointPairModel& model) const {
  for (std::uint32_t key = 0; key < model.keyEnd(); ++key)
    if (model.inTable(key) && !contains(key))
      return false;
  return true;
}

ScenePairs::ScenePairs(const OrientedPoints& scene, const PairQuantizer& quantizer,
                       int reference_stride, double radius_mm, std::optional<PairKeySet> keys,
                       const ProgressFn& progress)
    : m_quantizer(quantizer), m_radius_mm(radius_mm), m_keys(std::move(keys)) {
  const std::size_t n_scene = scene.points.size();
  if (scene.normals.size() != n_scene)
    throw Error("scene pairs: points and normals differ in count");
  const auto stride = static_cast<std::size_t>(std::max(1, reference_stride));
  const std::size_t n_refs = n_scene < 2 ? 0 : (n_scene + stride - 1) / stride;
  if (n_refs == 0)
    return;
  const PairingGrid grid(scene, radius_mm);
  const auto radius_sq = static_cast<float>(radius_mm * radius_mm);
  m_reference_points.resize(n_refs);
  m_to_local.resize(n_refs);
  m_pairs.resize(n_refs);
  parallelForWithProgress(
      n_refs, progress,
      [&](std::size_t r) {
        const std::size_t s = r * stride;
        m_reference_points[r] = scene.points[s];
        m_to_local[r] = localFrame(scene.points[s], scene.normals[s]);
        pairReference(
            scene, grid, s, m_to_local[r], m_quantizer, radius_sq,
            [&](std::uint32_t k) { return !m_keys || m_keys->contains(k); }, m_pairs[r]);
      },
      64);
}

PointPairModel::PointPairModel(OrientedPoints model, double distance_step_mm, int angle_bins)
    : m_model(std::move(model)), m_quantizer(distance_step_mm, angle_bins) {
  const std::size_t n = m_model.points.size();
  if (n < 3 || m_model.normals.size() != n)
    throw Error("point pair model: fewer than 3 oriented model points (widen the crop or lower "
                "the surface sampling)");
  if (n > 0xFFFF)
    throw Error("point pair model: " + std::to_string(n) +
                " oriented model points, at most 65535 (raise the surface sampling)");
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      m_diameter_mm =
          std::max(m_diameter_mm, double((m_model.points[i] - m_model.points[j]).norm()));
  m_to_local.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    m_to_local.push_back(localFrame(m_model.points[i], m_model.normals[i]));
  std::vector<std::pair<std::uint32_t, Entry>> keyed;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j)
        continue;
      bool valid = false;
      const std::uint32_t k = m_quantizer.key(m_model.points[i], m_model.normals[i],
                                              m_model.points[j], m_model.normals[j], &valid);
      if (valid)
        keyed.push_back(
            {k, Entry{static_cast<std::uint32_t>(i) |
                      std::uint32_t{planeAngle(m_to_local[i] * m_model.points[j])} << 16}});
    }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  // Dense offsets: the entries of key k are m_table[m_offsets[k], m_offsets[k + 1]).
  const std::uint32_t keys = keyed.empty() ? 0 : keyed.back().first + 1;
  m_offsets.assign(keys + 1, 0);
  m_table.reserve(keyed.size());
  for (const auto& [k, e] : keyed) {
    ++m_offsets[k + 1];
    m_table.push_back(e);
  }
  for (std::uint32_t k = 0; k < keys; ++k)
    m_offsets[k + 1] += m_offsets[k];
}

std::vector<VotedPose> PointPairModel::vote(const OrientedPoints& scene,
                                            const VotingOptions& options,
                                            const ProgressFn& progress) const {
  const std::size_t n_scene = scene.points.size();
  if (n_scene < 2)
    return {};
  // Each reference is paired as it votes, with its pairs of keys in the table only: without a
  // second view to share them (ScenePairs), most of a sparse table's pairs need no angle.
  const auto stride = static_cast<std::size_t>(std::max(1, options.reference_stride));
  const PairingGrid grid(scene, m_diameter_mm);
  const auto radius_sq = static_cast<float>(m_diameter_mm * m_diameter_mm);
  std::vector<ReferencePeak> peaks((n_scene + stride - 1) / stride);
  parallelForWithProgress(
      peaks.size(), progress,
      [&](std::size_t r) {
        const std::size_t s = r * stride;
        const Eigen::Isometry3f to_local = localFrame(scene.points[s], scene.normals[s]);
        thread_local std::vector<ScenePairs::Pair> pairs; // no allocation per reference
        pairs.clear();
        pairReference(
            scene, grid, s, to_local, m_quantizer, radius_sq,
            [&](std::uint32_t k) { return inTable(k); }, pairs);
        peaks[r] =
            peakOf(pairs.data(), pairs.data() + pairs.size(), scene.points[s], to_local, options);
      },
      64);
  return clustered(std::move(peaks), options);
}

std::vector<VotedPose> PointPairModel::vote(const ScenePairs& scene, const VotingOptions& options,
                                            const ProgressFn& progress) const {
  if (!scene.covers(*this))
    throw Error("point pair voting: the scene was paired with another quantization, within a "
                "smaller radius than the model's diameter or for other keys");
  std::vector<ReferencePeak> peaks(scene.referenceCount());
  parallelForWithProgress(
      peaks.size(), progress,
      [&](std::size_t r) {
        peaks[r] = peakOf(scene.pairsBegin(r), scene.pairsEnd(r), scene.referencePoint(r),
                          scene.toLocal(r), options);
      },
      64);
  return clustered(std::move(peaks), options);
}

bool ScenePairs::covers(const PointPairModel& model) const {
  return m_quantizer == model.quantizer() && m_radius_mm >= model.diameter() &&
         (!m_keys || m_keys->covers(model));
}

PointPairModel::ReferencePeak PointPairModel::peakOf(const ScenePairs::Pair* begin,
                                                     const ScenePairs::Pair* end,
                                                     const Eigen::Vector3f& reference,
                                                     const Eigen::Isometry3f& to_local,
                                                     const VotingOptions& options) const {
  const auto n_model = m_model.points.size();
  const auto radius_sq = static_cast<float>(m_diameter_mm * m_diameter_mm);
  // Self-voting: the model points near the reference, found once instead of per table entry.
  // Scratch of each thread, as large as the largest model it voted for: no allocation per
  // reference point.
  thread_local std::vector<std::uint8_t> excluded;
  excluded.clear();
  if (options.exclude_self_mm > 0) {
    const auto exclude_sq = static_cast<float>(options.exclude_self_mm * options.exclude_self_mm);
    excluded.resize(n_model);
    for (std::size_t m = 0; m < n_model; ++m)
      excluded[m] = (m_model.points[m] - reference).squaredNorm() < exclude_sq;
  }
  // Strictly within the diameter, as the radius search finds them.
  const auto voting = [&](const ScenePairs::Pair& pair) {
    return pair.distance_sq < radius_sq && inTable(pair.key);
  };
  // Counters that hold every vote the reference casts, so the loop never checks them: 16 bits
  // while they do (they stay in the first-level cache), 32 bits otherwise.
  std::size_t votes_cast = 0;
  for (const ScenePairs::Pair* pair = begin; pair != end; ++pair)
    if (voting(*pair))
      votes_cast += m_offsets[pair->key + 1] - m_offsets[pair->key];
  if (votes_cast > std::size_t{std::numeric_limits<std::int32_t>::max()})
    throw Error("point pair voting: one reference point casts more than 2^31 votes (raise the "
                "surface sampling)");
  const auto tally = [&](auto counter, auto excluding) {
    using Count = decltype(counter);
    const auto bins = static_cast<std::size_t>(m_quantizer.angleBins());
    thread_local std::vector<Count> accumulator;
    accumulator.assign(n_model * bins, 0);
    thread_local std::vector<std::uint32_t> cells; // of one pair's votes
    for (const ScenePairs::Pair* pair = begin; pair != end; ++pair) {
      if (!voting(*pair))
        continue;
      const std::size_t first = m_offsets[pair->key], count = m_offsets[pair->key + 1] - first;
      cells.resize(std::max(cells.size(), count));
      voteCells(m_table.data() + first, count, pair->alpha, static_cast<std::uint32_t>(bins),
                cells.data());
#pragma GCC unroll 4
      for (std::size_t k = 0; k < count; ++k) {
        if constexpr (excluding)
          if (excluded[cells[k] / bins])
            continue;
        ++accumulator[cells[k]];
      }
    }
    // The most votes (a loop the compiler vectorizes), then the first cell holding them.
    Count most = 0;
    for (const Count votes : accumulator)
      most = std::max(most, votes);
    ReferencePeak out;
    out.votes = static_cast<int>(most);
    if (out.votes == 0)
      return out;
    const auto cell = static_cast<std::size_t>(
        std::find(accumulator.begin(), accumulator.end(), most) - accumulator.begin());
    const std::size_t m = cell / bins;
    const float alpha = (float(cell % bins) + 0.5f) * (kTwoPi / float(bins));
    out.T = to_local.inverse() * Eigen::AngleAxisf(alpha, Eigen::Vector3f::UnitX()) * m_to_local[m];
    return out;
  };
  const bool narrow = votes_cast <= 0xFFFF;
  if (excluded.empty())
    return narrow ? tally(std::uint16_t{}, std::false_type{})
                  : tally(std::uint32_t{}, std::false_type{});
  return narrow ? tally(std::uint16_t{}, std::true_type{})
                : tally(std::uint32_t{}, std::true_type{});
}

std::vector<VotedPose> PointPairModel::clustered(std::vector<ReferencePeak> raw,
                                                 const VotingOptions& options) {
  // Pose clustering: most votes first; each pose joins the first cluster whose seed pose is close.
  std::stable_sort(raw.begin(), raw.end(), [](const ReferencePeak& a, const ReferencePeak& b) {
    return a.votes > b.votes;
  });
  struct Cluster {
    Eigen::Isometry3f seed;
    Eigen::Vector3d t_sum = Eigen::Vector3d::Zero();
    Eigen::Vector4d q_sum = Eigen::Vector4d::Zero();
    int votes = 0;
  };
  std::vector<Cluster> clusters;
  const auto max_t = static_cast<float>(options.cluster_distance_mm);
  const auto max_angle = static_cast<float>(options.cluster_angle_rad);
  for (const auto& pose : raw) {
    if (pose.votes == 0)
      break;
    Cluster* home = nullptr;
    for (auto& c : clusters)
      if ((c.seed.translation() - pose.T.translation()).norm() <= max_t &&
          Eigen::AngleAxisf(c.seed.linear().transpose() * pose.T.linear()).angle() <= max_angle) {
        home = &c;
        break;
      }
    if (!home) {
      clusters.push_back({pose.T});
      home = &clusters.back();
    }
    const Eigen::Quaternionf seed_q(home->seed.linear());
    Eigen::Quaternionf q(pose.T.linear());
    if (q.dot(seed_q) < 0)
      q.coeffs() = -q.coeffs();
    home->t_sum += double(pose.votes) * pose.T.translation().cast<double>();
    home->q_sum += double(pose.votes) * q.coeffs().cast<double>();
    home->votes += pose.votes;
  }
  std::stable_sort(clusters.begin(), clusters.end(),
                   [](const Cluster& a, const Cluster& b) { return a.votes > b.votes; });
  if (clusters.size() > static_cast<std::size_t>(std::max(0, options.max_poses)))
    clusters.resize(static_cast<std::size_t>(std::max(0, options.max_poses)));
  std::vector<VotedPose> out;
  out.reserve(clusters.size());
  for (const auto& c : clusters) {
    VotedPose v;
    v.votes = c.votes;
    v.T_scene_model.linear() = Eigen::Quaterniond(c.q_sum).normalized().toRotationMatrix();
    v.T_scene_model.translation() = c.t_sum / double(c.votes);
    out.push_back(v);
  }
  return out;
}

} // namespace scanpick::core
