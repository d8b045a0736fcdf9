#pragma once
/// @file DepthOverlay.h
/// The result on the scan's own depth image: one pixel per cell of an organized scan, shaded by
/// depth (near light, far dark), each detection's visible points tinted in its colour, with the
/// pixels where its ID and its grip points go. The GUI's depth view draws it (and the IDs and grip
/// markers over it); the result picture (OverlayPicture.h) draws them into it.

#include "core/cloud/PointCloud.h"
#include "core/common/Detection.h"
#include "core/common/Progress.h"
#include "core/output/DetectionColours.h"
#include "core/params/Parameters.h"

#include <vector>

namespace scanpick::core {

/// Where one detection lies in a DepthOverlay (pixel coordinates: column, row; (-1, -1) when
/// there is no such pixel).
struct DepthOverlayMark {
  std::size_t pixels = 0; ///< pixels tinted: the scan points the posed model explains
  /// Where its ID goes: the tinted pixel nearest to the middle of its tinted pixels (so that it
  /// lies on the part), or, without any, the pixel looking most nearly towards its centre_mm.
  Eigen::Vector2d label_px{-1, -1};
  /// Its grip points (Detection::grip_points_scene order): the pixel looking most nearly towards
  /// each (the scan's camera is at the origin of the scan frame).
  std::vector<Eigen::Vector2d> grips_px;
};

/// An RGB image of `width` × `height` (row-major) and one mark per detection.
struct DepthOverlay {
  int width = 0, height = 0;
  std::vector<Rgb8> rgb;
  std::vector<DepthOverlayMark> marks;
};

/// Colour of cells without a measurement (NaN) in a DepthOverlay.
inline constexpr Rgb8 kNoDepthColour{22, 26, 40};

/// The distance (mm) within which a scan point counts as explained by a detection's posed model
/// in the depth image: as close as the pose verification and the refinement ask
/// (matching.verify_tolerance_mm, refine.inlier_distance_mm), and never below 1 mm.
double depthOverlayTolerance_mm(const RecognitionParams& params);

/// Renders `scan_mm` (organized: height > 1) as its depth image: each valid cell grey by depth,
/// from light (nearest, 2nd percentile of z) to dark (farthest, 98th percentile); cells without
/// a point kNoDepthColour. A cell whose point lies within `tolerance_mm` of detection d's model
/// points (`model_clouds_mm[d.model_index]` moved by d.T_scene_model) is tinted `colours[d]`
/// (cycling when there are fewer colours), keeping some of its shade; the nearest detection wins.
/// Reports progress and stops (Cancelled) when asked. Throws Error for an unorganized scan, a
/// detection naming a missing model, no colour, or `tolerance_mm` <= 0.
DepthOverlay renderDepthOverlay(const PointCloud& scan_mm,
                                const std::vector<const PointCloud*>& model_clouds_mm,
                                const std::vector<Detection>& detections,
                                const std::vector<Rgb8>& colours, double tolerance_mm,
                                const ProgressFn& progress = {});

} // namespace scanpick::core
