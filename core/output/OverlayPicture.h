#pragma once
/// @file OverlayPicture.h
/// The result picture (the command-line tool's `--picture`): the scan's depth image with each
/// detection's explained pixels tinted in its colour (renderDepthOverlay, the rendering the GUI's
/// depth view shows), each detection's ID at its label pixel and its grip points as round markers,
/// in the detection colours (detectionColour).

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Detection.h"
#include "core/output/DepthOverlay.h"

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <vector>

namespace scanpick::core {

/// How an unorganized scene's points map to the pixels of its picture. Pixel coordinates are
/// (column, row) of a cell; rows grow with the scene's y, columns with its x.
struct PictureProjection {
  int width = 0, height = 0; ///< the picture's size, pixels
  /// True: the sensor's pinhole camera (SensorModel::pixelOf). False: an orthographic view along
  /// +z, pixel = round(((x, y) − origin_mm) × px_per_mm) + border_px.
  bool pinhole = false;
  SensorModel sensor;                                  ///< the camera, when pinhole
  Eigen::Vector2d origin_mm = Eigen::Vector2d::Zero(); ///< orthographic: scene (x, y) at the border
  double px_per_mm = 1.0;                              ///< orthographic: scale
  int border_px = 0;                                   ///< orthographic: empty margin, pixels
  /// The pixel where scene point `p_mm` (scene frame, mm) appears, or none when it lies behind
  /// the pinhole camera or outside the picture.
  [[nodiscard]] std::optional<Eigen::Vector2i> pixelOf(const Eigen::Vector3d& p_mm) const;
};

/// A scene made ready for renderDepthOverlay: an organized cloud and, when it had to be projected,
/// how its points were mapped to cells.
struct PictureScan {
  PointCloud scan_mm; ///< organized (height > 1), scene frame, mm
  /// Set when the scene was unorganized: the projection that made `scan_mm`'s grid.
  std::optional<PictureProjection> projection;
};

/// An organized `scene_mm` is returned as it is. An unorganized one (height == 1, a PLY or a
/// filtered cloud) is projected into a grid: through `sensor`'s pinhole camera when its
/// intrinsics are set (fx, fy, width and height > 0) and some point lands in its image, otherwise
/// orthographically along +z, fitted to the valid points' x-y extent at `fallback_width_px`
/// (at least 16) pixels wide and at most four times as high. Each cell keeps the nearest point
/// (smallest z) that falls in it. Where the points are sparser than the cells (the filled cells'
/// mean spacing in their bounding rectangle is 1.5 pixels or more), each point covers the cells
/// within half the diagonal of that spacing (at most 4 pixels), again the nearest winning, so that
/// the picture shows surfaces rather than dots. Cells left empty are NaN.
/// Throws Error when an unorganized scene has no valid point.
PictureScan organizeForPicture(const PointCloud& scene_mm, const SensorModel& sensor,
                               int fallback_width_px = 1024);

/// The picture as an image: renderDepthOverlay of organizeForPicture(scene_mm) with
/// detectionColours and `tolerance_mm` (depthOverlayTolerance_mm gives the GUI's), then, for each
/// detection k (ID k + 1, the order of `detections`), its grip points as filled circles in its
/// colour with a white ring and a dark outline, and its ID in its colour on a dark box framed in
/// its colour, centred at its label pixel and moved inside the picture where it would cross the
/// edge. Sizes scale with the picture (IDs about 1/30 of its smaller side high, at least 12
/// pixels). For a projected scene the returned marks' grip pixels, and the label pixel of a
/// detection without tinted pixels, are the projections of the grip points and of
/// Detection::centre_mm; (-1, -1) where there is none. Detection d draws
/// `model_clouds_mm[d.model_index]`. Throws Error as organizeForPicture and renderDepthOverlay do.
DepthOverlay renderOverlayPicture(const PointCloud& scene_mm,
                                  const std::vector<const PointCloud*>& model_clouds_mm,
                                  const std::vector<Detection>& detections,
                                  const SensorModel& sensor, double tolerance_mm,
                                  int fallback_width_px = 1024);

/// Writes renderOverlayPicture(...) as an 8-bit RGB PNG at `path`, atomically: on any failure
/// (the folder missing or not writable, encoding) it throws Error, leaves no file behind and keeps
/// a file already at `path` unchanged. The folder is checked before the picture is rendered.
void writeOverlayPng(const std::filesystem::path& path, const PointCloud& scene_mm,
                     const std::vector<const PointCloud*>& model_clouds_mm,
                     const std::vector<Detection>& detections, const SensorModel& sensor,
                     double tolerance_mm, int fallback_width_px = 1024);

} // namespace scanpick::core
