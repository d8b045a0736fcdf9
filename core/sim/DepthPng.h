#pragma once
/// @file DepthPng.h
/// A depth picture of an organized scan, for people: 8-bit grey PNG, near = bright.

#include "core/cloud/PointCloud.h"

#include <string>

namespace scanpick::core {

/// Encodes the organized cloud's depth (z) as an 8-bit greyscale PNG (libpng): the nearest valid
/// point is 255, the farthest 20, missing points 0. Throws Error for an unorganized cloud.
std::string depthPngBytes(const PointCloud& organized_cloud_mm);

} // namespace scanpick::core
