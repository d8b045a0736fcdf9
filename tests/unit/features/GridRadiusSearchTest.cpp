#include "core/features/GridRadiusSearch.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numeric>
#include <pcl/exceptions.h>
#include <pcl/search/kdtree.h>
#include <random>

using namespace scanpick::core;

namespace {
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// Asks PCL's sorted kd-tree and the grid, over the same cloud and indices, for the neighbours
/// of every query point within `radius`, and expects the same indices and distances in the
/// same order. Returns how many neighbours were found in all.
std::size_t expectSameAnswers(const pcl::search::KdTree<pcl::PointXYZ>& tree,
                              const GridRadiusSearch& grid, double radius, const Cloud& queries,
                              unsigned int max_nn = 0) {
  std::size_t found = 0;
  for (const auto& q : queries) {
    pcl::Indices tree_ids, grid_ids;
    std::vector<float> tree_d, grid_d;
    const int n = tree.radiusSearch(q, radius, tree_ids, tree_d, max_nn);
    EXPECT_EQ(grid.radiusSearch(q, radius, grid_ids, grid_d, max_nn), n);
    EXPECT_EQ(grid_ids, tree_ids);
    EXPECT_EQ(grid_d, tree_d);
    found += static_cast<std::size_t>(n);
  }
  return found;
}

std::size_t expectSameAsKdTree(const Cloud::Ptr& cloud, const pcl::IndicesPtr& indices,
                               double cell_mm, double radius, const Cloud& queries,
                               unsigned int max_nn = 0) {
  pcl::search::KdTree<pcl::PointXYZ> tree(true);
  tree.setInputCloud(cloud, indices);
  GridRadiusSearch grid(cell_mm);
  grid.setInputCloud(cloud, indices);
  return expectSameAnswers(tree, grid, radius, queries, max_nn);
}

Cloud::Ptr scattered(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> box(-80.0f, 80.0f);
  auto cloud = std::make_shared<Cloud>();
  for (std::size_t i = 0; i < n; ++i)
    cloud->push_back({box(rng), box(rng), 600.0f + 0.3f * box(rng)});
  return cloud;
}
} // namespace

TEST(GridRadiusSearch, FindsWhatPclsSortedKdTreeFindsInTheSameOrder) {
  const auto cloud = scattered(4000, 1);
  // Every third point, as a round of feature extraction searches a subset of the keypoints.
  auto indices = std::make_shared<pcl::Indices>();
  for (int i = 0; i < static_cast<int>(cloud->size()); i += 3)
    indices->push_back(i);
  Cloud queries;
  for (std::size_t i = 0; i < cloud->size(); i += 7)
    queries.push_back((*cloud)[i]);
  EXPECT_GT(expectSameAsKdTree(cloud, indices, 10.0, 10.0, queries), queries.size());
  // A radius beyond the cell edge, and one well inside it.
  EXPECT_GT(expectSameAsKdTree(cloud, indices, 4.0, 10.0, queries), queries.size());
  EXPECT_GT(expectSameAsKdTree(cloud, indices, 10.0, 3.0, queries), 0u);
}

// Feature extraction bins its keypoints once and lays out another subset of them each round.
TEST(GridRadiusSearch, AnswersForEachNewSubsetAsATreeOverThatSubset) {
  auto cloud = scattered(4000, 6);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < cloud->size(); i += 9)
    (*cloud)[i].z = nan;
  cloud->is_dense = false;
  Cloud queries; // points of the cloud (in a subset or not), and points between them
  for (std::size_t i = 1; i < cloud->size(); i += 13)
    if (std::isfinite((*cloud)[i].z))
      queries.push_back((*cloud)[i]);
  queries.push_back({0.5f, -0.25f, 601.0f});
  queries.push_back({500.0f, 500.0f, 0.0f}); // no occupied cell near
  GridRadiusSearch grid(10.0);
  std::mt19937_64 rng(7);
  for (int round = 0; round < 4; ++round) {
    // Like a round's candidates: a seeded sample (in the cloud's order), then shuffled once.
    auto subset = std::make_shared<pcl::Indices>();
    for (int i = 0; i < static_cast<int>(cloud->size()); ++i)
      if (rng() % 3 == 0)
        subset->push_back(i);
    if (round == 2)
      std::shuffle(subset->begin(), subset->end(), rng);
    if (round == 0)
      grid.setInputCloud(cloud, subset);
    else
      grid.setIndices(subset);
    pcl::search::KdTree<pcl::PointXYZ> tree(true);
    tree.setInputCloud(cloud, subset);
    EXPECT_GT(expectSameAnswers(tree, grid, 10.0, queries), queries.size()) << "round " << round;
    EXPECT_GT(expectSameAnswers(tree, grid, 25.0, queries), queries.size()) << "round " << round;
  }
}

// Cells spanning more than 64 bits can number (two clusters 30 km apart in every axis, 10 mm
// cells) are sorted as arrays instead of as one number each: the same answers.
TEST(GridRadiusSearch, AnswersTheSameWhenTheCellsSpanMoreThanANumberHolds) {
  const auto near = scattered(2000, 3);
  auto cloud = std::make_shared<Cloud>(*near);
  for (const auto& p : *near)
    cloud->push_back({p.x + 3e7f, p.y + 3e7f, p.z + 3e7f});
  auto indices = std::make_shared<pcl::Indices>(cloud->size());
  std::iota(indices->begin(), indices->end(), 0);
  Cloud queries;
  for (std::size_t i = 0; i < cloud->size(); i += 11)
    queries.push_back((*cloud)[i]);
  EXPECT_GT(expectSameAsKdTree(cloud, indices, 10.0, 10.0, queries), queries.size());
}

TEST(GridRadiusSearch, BreaksTiesInTheOrderOfTheIndices) {
  // A lattice: many neighbours at exactly equal distances, and the indices not ascending.
  auto cloud = std::make_shared<Cloud>();
  for (int x = 0; x < 12; ++x)
    for (int y = 0; y < 12; ++y)
      for (int z = 0; z < 3; ++z)
        cloud->push_back({2.0f * float(x), 2.0f * float(y), 500.0f + 2.0f * float(z)});
  auto indices = std::make_shared<pcl::Indices>(cloud->size());
  std::iota(indices->begin(), indices->end(), 0);
  std::shuffle(indices->begin(), indices->end(), std::mt19937_64(5));
  Cloud queries;
  for (std::size_t i = 0; i < cloud->size(); i += 5)
    queries.push_back((*cloud)[i]);
  EXPECT_GT(expectSameAsKdTree(cloud, indices, 5.0, 4.5, queries), 10 * queries.size());
}

TEST(GridRadiusSearch, KeepsTheNearestWhenAskedForAtMostSome) {
  const auto cloud = scattered(3000, 4); // no ties, where FLANN keeps whichever it met first
  Cloud queries;
  for (std::size_t i = 0; i < cloud->size(); i += 11)
    queries.push_back((*cloud)[i]);
  EXPECT_GT(expectSameAsKdTree(cloud, nullptr, 10.0, 10.0, queries, 3), queries.size());
}

TEST(GridRadiusSearch, SkipsPointsThatAreNotFinite) {
  auto cloud = scattered(500, 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < cloud->size(); i += 4)
    (*cloud)[i].x = nan;
  cloud->is_dense = false;
  Cloud queries;
  for (std::size_t i = 1; i < cloud->size(); i += 4)
    queries.push_back((*cloud)[i]);
  EXPECT_GT(expectSameAsKdTree(cloud, nullptr, 20.0, 20.0, queries), queries.size());
}

TEST(GridRadiusSearch, RefusesANonPositiveCellNearestKSearchAndNonFiniteQueries) {
  EXPECT_THROW(GridRadiusSearch(0.0), pcl::PCLException);
  GridRadiusSearch grid(1.0);
  grid.setInputCloud(scattered(10, 3));
  pcl::Indices ids;
  std::vector<float> d;
  EXPECT_THROW(grid.nearestKSearch(pcl::PointXYZ(0, 0, 0), 1, ids, d), pcl::PCLException);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(grid.radiusSearch(pcl::PointXYZ(nan, 0, 0), 100.0, ids, d), 0);
  EXPECT_TRUE(ids.empty());
  EXPECT_EQ(grid.radiusSearch(pcl::PointXYZ(0, 0, 600), 120.0, ids, d), 10); // all within 115 mm
}
