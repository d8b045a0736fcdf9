#pragma once
/// @file OverlayPicture.h
/// The thesis's result pictures (Figures 5.2-5.12): the scene in light grey and each detected
/// model, moved by its pose, in red, seen from the sensor.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/pipeline/Detection.h"

#include <filesystem>
#include <vector>

namespace scanpick::core {

/// Renders scene points (light grey) and each detection's model cloud (red) into a PNG, nearest
/// point wins (z-buffer), points drawn as 2×2 pixels. The view is the sensor's pinhole camera when
/// its intrinsics are set (fx > 0), otherwise an orthographic view along +z fitted to the points
/// (`fallback_width_px` wide). Writes atomically; throws Error on failure.
void writeOverlayPng(const std::filesystem::path& path, const PointCloud& scene_mm,
                     const PointCloud& model_cloud_mm, const std::vector<Detection>& detections,
                     const SensorModel& sensor, int fallback_width_px = 1024);

/// As above for detections of several models (views): detection d draws
/// `model_clouds_mm[d.model_index]`. Throws Error when a detection names a missing model.
void writeOverlayPng(const std::filesystem::path& path, const PointCloud& scene_mm,
                     const std::vector<const PointCloud*>& model_clouds_mm,
                     const std::vector<Detection>& detections, const SensorModel& sensor,
                     int fallback_width_px = 1024);

} // namespace scanpick::core
