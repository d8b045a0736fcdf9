#include "core/matching/PointPairVoting.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <vector>

using namespace scanpick::core;

namespace {

/// Oriented points on the outside of an axis-aligned box [lo, hi] (mm), one every `step` mm,
/// outward normals; faces listed in `faces` (0..5 = -x, +x, -y, +y, -z, +z) only.
void addBox(OrientedPoints& out, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float step,
            std::initializer_list<int> faces) {
  for (int face : faces) {
    const int axis = face / 2;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Eigen::Vector3f n = Eigen::Vector3f::Zero();
    n[axis] = face % 2 ? 1.0f : -1.0f;
    for (float a = lo[u]; a <= hi[u] + 1e-4f; a += step)
      for (float b = lo[v]; b <= hi[v] + 1e-4f; b += step) {
        Eigen::Vector3f p;
        p[axis] = face % 2 ? hi[axis] : lo[axis];
        p[u] = a;
        p[v] = b;
        out.points.push_back(p);
        out.normals.push_back(n);
      }
  }
}

/// An asymmetric bracket as a camera above it sees it: an L of two plates and a block on one leg,
/// upward and sideways faces only.
OrientedPoints bracket(float step) {
  OrientedPoints part;
  addBox(part, {0, 0, 0}, {60, 30, 5}, step, {1, 3, 5});         // leg on the floor
  addBox(part, {0, 0, 5}, {5, 30, 45}, step, {0, 1, 3, 5});      // upright leg
  addBox(part, {35, 5, 5}, {50, 15, 15}, step, {0, 1, 2, 3, 5}); // block
  return part;
}

OrientedPoints transformed(const OrientedPoints& in, const Eigen::Isometry3f& T) {
  OrientedPoints out;
  for (std::size_t i = 0; i < in.points.size(); ++i) {
    out.points.push_back(T * in.points[i]);
    out.normals.push_back(T.linear() * in.normals[i]);
  }
  return out;
}

Eigen::Isometry3f pose(float angle, const Eigen::Vector3f& axis, const Eigen::Vector3f& t) {
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = Eigen::AngleAxisf(angle, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

double translationError(const Eigen::Isometry3d& a, const Eigen::Isometry3f& b) {
  return (a.translation() - b.translation().cast<double>()).norm();
}
double rotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3f& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear().cast<double>()).angle();
}

constexpr float kSampling = 3.0f;

} // namespace

TEST(PointPairVoting, SamplingAveragesEachVoxelAndKeepsBothFacesOfAThinWall) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Eigen::Vector3f tilted = Eigen::Vector3f(0, 1, 1).normalized();
  const std::vector<Eigen::Vector3f> points = {
      {0.1f, 0.1f, 0.1f},
      {0.9f, 0.9f, 0.9f}, // one voxel, normals 45° apart: one sample
      {5.0f, 0.0f, 0.0f},
      {5.5f, 0.0f, 0.0f},  // one voxel, opposite normals: two samples
      {9.0f, 9.0f, 9.0f}}; // no normal: dropped
  const std::vector<Eigen::Vector3f> normals = {
      {0, 0, 1}, tilted, {1, 0, 0}, {-1, 0, 0}, {nan, 0, 0}};
  const OrientedPoints s = sampleOriented(points, normals, 2.0);
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_TRUE(s.points[0].isApprox(Eigen::Vector3f(0.5f, 0.5f, 0.5f)));
  EXPECT_TRUE(s.normals[0].isApprox((Eigen::Vector3f(0, 0, 1) + tilted).normalized()));
  EXPECT_TRUE(s.normals[1].isApprox(Eigen::Vector3f(1, 0, 0)));
  EXPECT_TRUE(s.normals[2].isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_FLOAT_EQ(s.points[2].x(), 5.5f);
  EXPECT_THROW(sampleOriented(points, {}, 2.0), Error);
  EXPECT_THROW(sampleOriented(points, normals, 0.0), Error);
}

TEST(PointPairVoting, FindsAnInstanceAtItsPose) {
  const OrientedPoints part =
      sampleOriented(bracket(1.0f).points, bracket(1.0f).normals, kSampling);
  const PointPairModel model(part, kSampling);
  EXPECT_GT(model.pairCount(), 1000u);
  EXPECT_NEAR(model.diameter(), 80.8, 4.0); // the box diagonal of the L
  const Eigen::Isometry3f truth = pose(1.1f, {0.3f, -0.5f, 0.8f}, {120, -40, 600});
  const OrientedPoints raw = transformed(bracket(1.0f), truth);
  const OrientedPoints scene = sampleOriented(raw.points, raw.normals, kSampling);
  VotingOptions options;
  options.reference_stride = 3;
  const auto poses = model.vote(scene, options);
  ASSERT_FALSE(poses.empty());
  // Within a few sampling steps and about one angle bin (12°).
  EXPECT_LT(translationError(poses.front().T_scene_model, truth), 2.0 * kSampling);
  EXPECT_LT(rotationError(poses.front().T_scene_model, truth), 0.2);
}

TEST(PointPairVoting, VotingAgainstItselfWithoutItsOwnNeighbourhoodFindsTheSymmetry) {
  // A plate with a block at each end, the same when turned 180° about its normal (z) through its
  // centre. Voted against itself, the identity wins; with each point's own neighbourhood left
  // out, the half turn does.
  OrientedPoints raw;
  addBox(raw, {-40, -15, 0}, {40, 15, 5}, 1.0f, {0, 1, 2, 3, 5});
  addBox(raw, {-35, -5, 5}, {-25, 5, 15}, 1.0f, {0, 1, 2, 3, 5});
  addBox(raw, {25, -5, 5}, {35, 5, 15}, 1.0f, {0, 1, 2, 3, 5});
  const OrientedPoints part = sampleOriented(raw.points, raw.normals, kSampling);
  const PointPairModel model(part, kSampling);
  VotingOptions options;
  options.reference_stride = 1;
  options.max_poses = 3;
  const auto with_self = model.vote(part, options);
  ASSERT_FALSE(with_self.empty());
  EXPECT_LT(rotationError(with_self.front().T_scene_model, Eigen::Isometry3f::Identity()), 0.2);
  options.exclude_self_mm = 10.0;
  const auto without_self = model.vote(part, options);
  ASSERT_FALSE(without_self.empty());
  const Eigen::Isometry3f half_turn = pose(float(M_PI), {0, 0, 1}, {0, 0, 0});
  EXPECT_LT(rotationError(without_self.front().T_scene_model, half_turn), 0.2);
  EXPECT_LT(translationError(without_self.front().T_scene_model, half_turn), 2.0 * kSampling);
}

namespace {

/// Three brackets at `truths` above a floor-like plane with noisy normals, sampled.
OrientedPoints bracketsOnAPlane(const std::vector<Eigen::Isometry3f>& truths) {
  OrientedPoints raw;
  for (const auto& T : truths) {
    const OrientedPoints one = transformed(bracket(1.0f), T);
    raw.points.insert(raw.points.end(), one.points.begin(), one.points.end());
    raw.normals.insert(raw.normals.end(), one.normals.begin(), one.normals.end());
  }
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  for (float x = -150; x <= 300; x += 2)
    for (float y = -150; y <= 300; y += 2) {
      raw.points.emplace_back(x, y, 700);
      raw.normals.push_back(Eigen::Vector3f(noise(rng), noise(rng), -1).normalized());
    }
  return sampleOriented(raw.points, raw.normals, kSampling);
}

const std::vector<Eigen::Isometry3f> kTruths = {pose(0.4f, {0, 0, 1}, {0, 0, 500}),
                                                pose(2.5f, {1, 1, 0}, {150, 20, 520}),
                                                pose(-1.2f, {0, 1, 1}, {-40, 160, 480})};

} // namespace

TEST(PointPairVoting, FindsEveryInstanceOfASceneAndIsRepeatable) {
  const OrientedPoints part =
      sampleOriented(bracket(1.0f).points, bracket(1.0f).normals, kSampling);
  const PointPairModel model(part, kSampling);
  const std::vector<Eigen::Isometry3f>& truths = kTruths;
  const OrientedPoints scene = bracketsOnAPlane(truths);
  VotingOptions options;
  options.reference_stride = 2;
  options.max_poses = 30;
  const auto poses = model.vote(scene, options);
  for (const auto& truth : truths) {
    const bool found = std::any_of(poses.begin(), poses.end(), [&](const VotedPose& v) {
      return translationError(v.T_scene_model, truth) < 2.0 * kSampling &&
             rotationError(v.T_scene_model, truth) < 0.2;
    });
    EXPECT_TRUE(found) << "instance at " << truth.translation().transpose();
  }
  const auto again = model.vote(scene, options);
  ASSERT_EQ(again.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(again[i].votes, poses[i].votes);
    EXPECT_TRUE(again[i].T_scene_model.isApprox(poses[i].T_scene_model, 0.0));
  }
}

TEST(PointPairVoting, RejectsTooFewPointsAndStopsWhenCancelled) {
  OrientedPoints two;
  two.points = {{0, 0, 0}, {1, 0, 0}};
  two.normals = {{0, 0, 1}, {0, 0, 1}};
  EXPECT_THROW(PointPairModel(two, 1.0), Error);
  const OrientedPoints part =
      sampleOriented(bracket(1.0f).points, bracket(1.0f).normals, kSampling);
  const PointPairModel model(part, kSampling);
  EXPECT_THROW(model.vote(part, VotingOptions{1}, [](double) { return false; }), Cancelled);
  EXPECT_TRUE(model.vote(OrientedPoints{}, VotingOptions{}).empty());
}

TEST(PointPairVoting, ViewsSharingOnePairedSceneVoteAsWithTheSceneItself) {
  // Two views of different size: the scene is paired once, within more than either's diameter,
  // and each view keeps the pairs within its own.
  const OrientedPoints whole =
      sampleOriented(bracket(1.0f).points, bracket(1.0f).normals, kSampling);
  OrientedPoints leg_raw;
  addBox(leg_raw, {0, 0, 0}, {60, 30, 5}, 1.0f, {1, 3, 5});
  const OrientedPoints leg = sampleOriented(leg_raw.points, leg_raw.normals, kSampling);
  const PointPairModel large(whole, kSampling), small(leg, kSampling);
  ASSERT_LT(small.diameter(), large.diameter() - kSampling);
  const OrientedPoints scene = bracketsOnAPlane(kTruths);
  VotingOptions options;
  options.reference_stride = 3;
  options.max_poses = 20;
  // Each view votes with `pairs` exactly as with the scene itself.
  const auto expectVotesAsAlone = [&](const ScenePairs& pairs) {
    for (const PointPairModel* view : {&large, &small}) {
      ASSERT_TRUE(pairs.covers(*view));
      const auto alone = view->vote(scene, options);
      const auto shared = view->vote(pairs, options);
      ASSERT_FALSE(alone.empty());
      ASSERT_EQ(shared.size(), alone.size());
      for (std::size_t i = 0; i < alone.size(); ++i) {
        EXPECT_EQ(shared[i].votes, alone[i].votes);
        EXPECT_TRUE(shared[i].T_scene_model.isApprox(alone[i].T_scene_model, 0.0));
      }
    }
  };
  const ScenePairs paired(scene, large.quantizer(), options.reference_stride,
                          1.3 * large.diameter());
  expectVotesAsAlone(paired);
  // Paired for the views' keys only (most scene pairs have a key neither table holds): the same
  // poses again, with fewer pairs kept.
  PairKeySet both;
  both.add(large);
  both.add(small);
  const ScenePairs kept(scene, large.quantizer(), options.reference_stride, 1.3 * large.diameter(),
                        both);
  std::size_t all_pairs = 0, kept_pairs = 0;
  for (std::size_t r = 0; r < paired.referenceCount(); ++r) {
    all_pairs += std::size_t(paired.pairsEnd(r) - paired.pairsBegin(r));
    kept_pairs += std::size_t(kept.pairsEnd(r) - kept.pairsBegin(r));
  }
  EXPECT_LT(kept_pairs, all_pairs);
  expectVotesAsAlone(kept);
  // Paired for another view's keys, too narrowly, or with another quantization: refused, not
  // voted wrongly.
  PairKeySet small_only;
  small_only.add(small);
  EXPECT_TRUE(small_only.within(both));
  EXPECT_FALSE(both.within(small_only));
  const ScenePairs for_small(scene, large.quantizer(), options.reference_stride,
                             1.3 * large.diameter(), small_only);
  EXPECT_FALSE(for_small.covers(large));
  EXPECT_THROW((void)large.vote(for_small, options), Error);
  const ScenePairs narrow(scene, large.quantizer(), options.reference_stride,
                          0.9 * large.diameter());
  EXPECT_THROW((void)large.vote(narrow, options), Error);
  const ScenePairs coarser(scene, PairQuantizer(2.0 * kSampling, 30), options.reference_stride,
                           2.0 * large.diameter());
  EXPECT_THROW((void)large.vote(coarser, options), Error);
}

TEST(PairQuantizer, KeysBinTheDistanceAndTheAnglesOfAPair) {
  // The key against the angles' arccosines, away from the bin bounds (where rounding may go
  // either way): ((distance bin · h + angle 1) · h + angle 2) · h + angle between, h = bins / 2.
  for (const int bins : {30, 12, 90}) {
    const PairQuantizer quantizer(2.0, bins);
    const int half = bins / 2;
    const double width = M_PI / half;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coordinate(-40.0f, 40.0f);
    int checked = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::Vector3f p1(coordinate(rng), coordinate(rng), coordinate(rng));
      const Eigen::Vector3f p2(coordinate(rng), coordinate(rng), coordinate(rng));
      const Eigen::Vector3f n1 =
          Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
      const Eigen::Vector3f n2 =
          Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
      const Eigen::Vector3f u = (p2 - p1).normalized();
      const double angles[3] = {std::acos(double(n1.dot(u))), std::acos(double(n2.dot(u))),
                                std::acos(double(n1.dot(n2)))};
      int a[3];
      bool near_bound = false;
      for (int k = 0; k < 3; ++k) {
        const double in_bins = angles[k] / width;
        near_bound |= std::abs(in_bins - std::round(in_bins)) < 1e-3;
        a[k] = std::min(half - 1, int(in_bins));
      }
      if (near_bound || (a[2] == 0 && a[0] == half / 2 && a[1] == half / 2))
        continue;
      bool valid = false;
      const std::uint32_t key = quantizer.key(p1, n1, p2, n2, &valid);
      ASSERT_TRUE(valid);
      const auto d_bin = std::uint32_t((p2 - p1).norm() / 2.0f);
      EXPECT_EQ(key, ((d_bin * half + a[0]) * half + a[1]) * half + a[2]) << "bins " << bins;
      ++checked;
    }
    EXPECT_GT(checked, 1900);
  }
  bool valid = true;
  (void)PairQuantizer(2.0, 30).key({0, 0, 0}, {0, 0, 1}, {0.5f, 0, 0}, {0, 0, 1}, &valid);
  EXPECT_FALSE(valid) << "closer than half a step";
  EXPECT_THROW(PairQuantizer(0.0, 30), Error);
  EXPECT_THROW(PairQuantizer(1.0, 2), Error);
}

TEST(PairQuantizer, KeysWithinARadiusAreTheKeysOfEachPairToTheBit) {
  // Points around a reference, some on its plane and some at its place (invalid pairs), some
  // beyond the radius; the eight-at-a-time keys against key() and the kd-tree's metric, for ranges
  // of every length modulo 8.
  for (const int bins : {30, 12, 90}) {
    const PairQuantizer quantizer(3.0, bins);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> coordinate(-60.0f, 60.0f);
    const auto unit = [&] {
      return Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
    };
    const Eigen::Vector3f p1(1.5f, -2.25f, 700.0f);
    const Eigen::Vector3f n1 = unit();
    const std::size_t count = 1000;
    std::vector<float> x, y, z, nx, ny, nz;
    for (std::size_t i = 0; i < count; ++i) {
      Eigen::Vector3f p = p1 + Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng));
      Eigen::Vector3f n = unit();
      if (i % 7 == 0) { // on the reference's plane, facing as it does
        const Eigen::Vector3f along = n1.unitOrthogonal() * coordinate(rng);
        p = p1 + along;
        n = n1;
      }
      if (i % 50 == 0)
        p = p1;
      x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
      nx.push_back(n.x()), ny.push_back(n.y()), nz.push_back(n.z());
    }
    for (auto* values : {&x, &y, &z, &nx, &ny, &nz})
      values->resize(count + 8, std::numeric_limits<float>::quiet_NaN());
    const PairQuantizer::PointArrays arrays{x.data(),  y.data(),  z.data(),
                                            nx.data(), ny.data(), nz.data()};
    const float radius_sq = 70.0f * 70.0f;
    std::vector<PairQuantizer::KeyedPoint> out(count);
    std::size_t checked = 0, flat = 0;
    for (const std::size_t begin : {std::size_t{0}, std::size_t{3}}) {
      const std::size_t found =
          quantizer.keysWithin(arrays, begin, count, p1, n1, radius_sq, out.data());
      std::size_t k = 0;
      for (std::size_t i = begin; i < count; ++i) {
        const Eigen::Vector3f p2(x[i], y[i], z[i]), n2(nx[i], ny[i], nz[i]);
        float metric_sq = 0.0f; // as nanoflann's L2_Simple_Adaptor sums it
        for (int c = 0; c < 3; ++c)
          metric_sq += (p1[c] - p2[c]) * (p1[c] - p2[c]);
        bool valid = false;
        const std::uint32_t key = quantizer.key(p1, n1, p2, n2, &valid);
        flat += !valid && (p2 - p1).norm() > 2.0f;
        if (!(metric_sq < radius_sq) || !valid)
          continue;
        ASSERT_LT(k, found);
        EXPECT_EQ(out[k].at, i);
        EXPECT_EQ(out[k].key, key) << "point " << i << ", bins " << bins;
        EXPECT_EQ(out[k].distance_sq, metric_sq);
        ++k, ++checked;
      }
      EXPECT_EQ(k, found);
      // Ranges ending inside a group of eight: the same pairs, up to the range's end.
      for (std::size_t end = begin; end <= begin + 17; ++end) {
        const auto before_end = static_cast<std::size_t>(
            std::count_if(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(found),
                          [&](const PairQuantizer::KeyedPoint& keyed) { return keyed.at < end; }));
        std::vector<PairQuantizer::KeyedPoint> shorter(count);
        EXPECT_EQ(quantizer.keysWithin(arrays, begin, end, p1, n1, radius_sq, shorter.data()),
                  before_end);
      }
    }
    EXPECT_GT(checked, 500u);
    EXPECT_GT(flat, 20u) << "the points on the reference's plane make invalid pairs";
  }
}
