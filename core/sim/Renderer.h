#pragma once
/// @file Renderer.h
/// The virtual structured-light scanner: exact ray casting (Embree) of a scene from the camera,
/// keeping a point only where the projector also lights the surface.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/common/Progress.h"
#include "core/sim/Scene.h"
#include "core/sim/SensorNoise.h"

#include <cstdint>
#include <vector>

namespace scanpick::core {

/// Pixel labels of RenderResult::labels.
inline constexpr std::int32_t kLabelEnvironment = -1; ///< floor, table or bin wall
inline constexpr std::int32_t kLabelNothing = -2;     ///< the ray hit nothing

/// A simulated scan and what each pixel saw.
struct RenderResult {
  PointCloud cloud; ///< organized (sensor width × height), scene = camera frame, mm; NaN = no point
  /// Per pixel: the instance id the camera ray hit first, kLabelEnvironment or kLabelNothing
  /// (kept also where the point is missing, e.g. in projector shadow).
  std::vector<std::int32_t> labels;
  /// Per instance (by id): valid points of the final cloud whose ray hit it.
  std::vector<std::size_t> visible_points;
  /// Per instance: pixels where it is seen and lit (in range, not in projector shadow, not
  /// grazing), before random dropouts and flying pixels.
  std::vector<std::size_t> lit_pixels;
  /// Per instance: the same count with the instance alone in front of the sensor.
  std::vector<std::size_t> lit_pixels_alone;
  /// lit_pixels / lit_pixels_alone (0 when the instance is out of view).
  std::vector<double> visible_fraction;
};

/// Renders `scene` with `sensor`. For every pixel, a ray from the camera centre finds the first
/// surface; the point is kept only if it lies in the sensor's working range and a shadow ray from
/// it to the projector centre is unobstructed (the undercuts and shadows of structured light).
/// Then `noise` is applied with random draws keyed by (seed, pixel), so the result is identical
/// for identical inputs whatever the thread scheduling. Runs in parallel (TBB).
/// Throws Error if the sensor has no pixels.
RenderResult renderScene(const Scene& scene, const SensorModel& sensor, const SensorNoise& noise,
                         std::uint64_t seed, const ProgressFn& progress = {});

} // namespace scanpick::core
