#pragma once
/// @file AllAround.h
/// Models that are not one view: a part scanned all around (merged scans, a laser scanner's
/// turntable, points sampled on a mesh). A camera sees only the side of a part that faces it, so a
/// single view's normals are turned towards its camera; a model seen from every side needs them
/// turned outward instead, or half of them point into the part.

#include "core/cloud/PointCloud.h"

#include <Eigen/Core>
#include <vector>

namespace scanpick::core {

/// Whether `cloud_mm` could be one scan taken from `camera_mm` (same frame, mm): the camera lies
/// outside the cloud's bounding box and, of the lines of sight through it (cells of twice
/// `spacing_mm` where they cross the cloud), fewer than half pass through two surfaces farther
/// apart than four point spacings. A scan shows one surface per line of sight but at its jump
/// edges; a part scanned all around shows its near and far sides on almost every one. (A part
/// thinner than four spacings scanned all around passes for one view.)
bool seenFromOneCamera(const PointCloud& cloud_mm, const Eigen::Vector3d& camera_mm,
                       double spacing_mm);

/// Unit normals of the valid points of `cloud_mm` (one per point, NaN for invalid points and
/// where fewer than 3 neighbours lie within `radius_mm`), turned to face out of the part: the
/// cloud's own normals when it has them for every valid point, else the plane fitted to the 12
/// nearest neighbours within `radius_mm`; their signs are then made consistent along a minimum
/// spanning tree of the graph of 10 nearest neighbours (Hoppe et al. 1992), where two normals
/// agree when one is the other mirrored half way between their points (a circular arc joins
/// them: smooth surfaces and sharp edges alike) and an edge costs the less the more its points lie
/// along their tangent planes (across a thin wall or a step the sign cannot be told); in each
/// connected piece the point farthest from the piece's centroid faces away from it.
/// Deterministic.
std::vector<Eigen::Vector3f> outwardNormals(const PointCloud& cloud_mm, double radius_mm);

} // namespace scanpick::core
