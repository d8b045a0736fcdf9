#pragma once
/// @file Downsample.h
/// Voxel-grid downsampling (not in the thesis: bounds the cost of dense PhoXi scans).

#include "core/cloud/PointCloud.h"

namespace scanpick::core {

/// Replaces the valid points of each cubic voxel of edge `voxel_mm` by their centroid (normals
/// are averaged and renormalized, colours averaged, other channels dropped). The output is
/// unorganized, ordered by voxel (deterministic). `voxel_mm <= 0` returns a copy of the input
/// (organization kept). Throws Error for an inconsistent cloud.
PointCloud voxelDownsample(const PointCloud& cloud_mm, double voxel_mm);

} // namespace scanpick::core
