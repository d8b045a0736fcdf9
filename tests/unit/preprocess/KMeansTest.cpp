#include "core/preprocess/KMeans.h"

#include "core/common/Error.h"

#include <gtest/gtest.h>
#include <random>
#include <set>

using namespace scanpick;

namespace {
// `per_blob` Gaussian points (sigma 2 mm) around each centre, fixed seed.
std::vector<Eigen::Vector3f> blobs(const std::vector<Eigen::Vector3f>& centres, int per_blob,
                                   std::vector<int>* truth = nullptr) {
  std::mt19937_64 rng(5);
  std::normal_distribution<float> n(0.0f, 2.0f);
  std::vector<Eigen::Vector3f> pts;
  for (std::size_t c = 0; c < centres.size(); ++c)
    for (int i = 0; i < per_blob; ++i) {
      pts.push_back(centres[c] + Eigen::Vector3f(n(rng), n(rng), n(rng)));
      if (truth)
        truth->push_back(static_cast<int>(c));
    }
  return pts;
}
const std::vector<Eigen::Vector3f> kCentres{
    {0, 0, 1000}, {100, 0, 1000}, {0, 100, 1000}, {100, 100, 950}};
} // namespace

TEST(FarthestFirstTraversal, PicksOnePointPerFarBlob) {
  std::vector<int> truth;
  const auto pts = blobs(kCentres, 50, &truth);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto picked = core::farthestFirstTraversal(pts, 4, seed);
    ASSERT_EQ(picked.size(), 4u);
    std::set<int> blobs_hit;
    for (int i : picked)
      blobs_hit.insert(truth[static_cast<std::size_t>(i)]);
    EXPECT_EQ(blobs_hit.size(), 4u) << "blobs are 100 mm apart, their spread ~10 mm";
    for (std::size_t a = 0; a < picked.size(); ++a)
      for (std::size_t b = a + 1; b < picked.size(); ++b)
        EXPECT_GT(
            (pts[static_cast<std::size_t>(picked[a])] - pts[static_cast<std::size_t>(picked[b])])
                .norm(),
            70.0f);
  }
  EXPECT_EQ(core::farthestFirstTraversal(pts, 4, 11), core::farthestFirstTraversal(pts, 4, 11));
  EXPECT_EQ(core::farthestFirstTraversal(pts, 1000, 1).size(), pts.size());
}

TEST(KMeans, RecoversWellSeparatedBlobsWithBothSeedings) {
  std::vector<int> truth;
  const auto pts = blobs(kCentres, 300, &truth);
  for (auto init : {core::ClusteringParams::Init::FarthestFirst,
                    core::ClusteringParams::Init::KMeansPlusPlus}) {
    core::ClusteringParams params;
    params.init = init;
    const auto result = core::kmeans(pts, 4, params, 42);
    ASSERT_EQ(result.centres.size(), 4u);
    ASSERT_EQ(result.labels.size(), pts.size());
    // Every blob maps to one label, and each label's centre is within 0.5 mm of its blob centre
    // (300 samples of sigma 2 mm: the mean's error is ~0.12 mm per axis).
    for (std::size_t c = 0; c < kCentres.size(); ++c) {
      const int label = result.labels[c * 300];
      for (std::size_t i = c * 300; i < (c + 1) * 300; ++i)
        ASSERT_EQ(result.labels[i], label);
      EXPECT_LT((result.centres[static_cast<std::size_t>(label)] - kCentres[c]).norm(), 0.5f);
    }
    EXPECT_GE(result.iterations, 1);
    EXPECT_LT(result.objective, 1200.0 * 3 * 4 * 2); // ~ n * 3 sigma^2 = 14400, with slack
    const auto again = core::kmeans(pts, 4, params, 42);
    EXPECT_EQ(again.labels, result.labels);
    EXPECT_EQ(again.centres, result.centres);
  }
  EXPECT_THROW(core::kmeans(pts, 0, {}, 1), core::Error);
}
