#pragma once
/// @file DetectionColours.h
/// The colours that tell detections apart wherever they are drawn: the GUI's 3D view, depth view
/// and results table, and the result picture.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace scanpick::core {

/// An 8-bit sRGB colour (red, green, blue).
using Rgb8 = std::array<std::uint8_t, 3>;

/// The colour of detection `index` (0-based, the order of RecognitionResult::detections, shown as
/// ID index + 1): saturation 0.85, value 1, hue 0.08 + index × the golden ratio's fraction (mod 1),
/// so that neighbouring indices lie far apart on the colour wheel.
Rgb8 detectionColour(std::size_t index);

/// The colours of detections 0 … count - 1 (detectionColour).
std::vector<Rgb8> detectionColours(std::size_t count);

} // namespace scanpick::core
