#pragma once
/// @file PointKdTree.h
/// nanoflann's kd-tree over a vector of 3D points (mm), shared by the modules that search points
/// by radius or nearest neighbour. Include it only from sources of modules that link nanoflann.

#include <Eigen/Core>
#include <cstdint>
#include <nanoflann.hpp>
#include <vector>

namespace scanpick::core {

/// nanoflann's dataset adaptor over a vector of points (not owned).
struct PointVectorSource {
  const std::vector<Eigen::Vector3f>* points = nullptr;
  [[nodiscard]] std::size_t kdtree_get_point_count() const { return points->size(); }
  [[nodiscard]] float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*points)[i][static_cast<Eigen::Index>(dim)];
  }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};

/// Exact kd-tree over PointVectorSource, 32-bit indices.
using PointKdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointVectorSource>,
                                        PointVectorSource, 3, std::uint32_t>;

} // namespace scanpick::core
