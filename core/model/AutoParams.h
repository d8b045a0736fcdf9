#pragma once
/// @file AutoParams.h
/// Recognition parameters derived at teach time from the part and from the scan, so that a part
/// nobody has tuned for is recognized with no preset: every length comes from the scan's point
/// spacing and depth noise (measured in the scan, not taken from a sensor's name) or from the
/// part's size, each with the reason for its value.

#include "core/cloud/PointCloud.h"
#include "core/params/Parameters.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace scanpick::core {

/// What a teach scan shows of its sensor, measured around the cropped part.
struct ScanMeasures {
  double spacing_mm = 0.0; ///< median distance from a point to its nearest neighbour
  double noise_mm = 0.0;   ///< median RMS distance of a point's neighbours to their plane
  /// Height of the part's lowest face above the plane it rests on (mm; 0 = not measured): a thin
  /// part lying flat must stand above the floor distance.
  double part_layer_mm = 0.0;
};

/// The part's size, from its cropped points (flying pixels left out).
struct PartMeasures {
  double diameter_mm = 0.0;                            ///< largest distance between two points
  Eigen::Vector3d extent_mm = Eigen::Vector3d::Zero(); ///< along its principal axes, largest first
  std::size_t points = 0;                              ///< points of the crop
};

/// One derived parameter: its key in the metadata table, its value and why.
struct DerivedValue {
  std::string key;
  double value = 0.0;
  std::string reason;
};

/// Parameters derived for one part and scan, and the reasons.
struct AutoParams {
  RecognitionParams params;
  std::vector<DerivedValue> values; ///< in the order derived; only the values set
  ScanMeasures scan;
  PartMeasures part;
};

/// Spacing and noise of the valid points of `cloud_mm` (at most 4000 of them, evenly strided,
/// are examined: deterministic). Throws Error when fewer than 10 points are valid.
ScanMeasures measureScan(const PointCloud& cloud_mm);

/// Size of the part in `part_mm` (valid points; a point farther than 5 x `spacing_mm` from its
/// third-nearest neighbour is a flying pixel and left out). Throws Error for fewer than 10 points.
PartMeasures measurePart(const PointCloud& part_mm, double spacing_mm);

/// The scan-dependent values only (floor removal and object counting), for the stages that run
/// before the part is cut out: `base` with them set.
AutoParams deriveScanParams(const ScanMeasures& scan, RecognitionParams base = {});

/// Every value derived from the scan and the part: deriveScanParams, then keypoints, features,
/// matching (point-level verification and surface voting on) and refinement (ICP on), each
/// from the spacing, the noise or the part's size.
AutoParams deriveParams(const ScanMeasures& scan, const PartMeasures& part,
                        RecognitionParams base = {});

} // namespace scanpick::core
