#pragma once
/// @file Units.h
/// Length units of input files. Everything inside scanpick is in millimetres.

#include "core/cloud/PointCloud.h"

#include <optional>
#include <string>
#include <string_view>

namespace scanpick::core {

/// Length unit of coordinates in a file.
enum class LengthUnit { Millimetres, Metres };

/// Parses "mm" / "m" (also "millimetres", "metres", "meters"); throws Error otherwise.
LengthUnit parseLengthUnit(std::string_view text);
/// "mm" or "m".
std::string toString(LengthUnit unit);
/// Millimetres per unit: 1 or 1000.
float millimetresPer(LengthUnit unit);

/// A guess of the unit from the extent of the valid points: scenes and parts scanned for bin
/// picking span roughly 20 mm to 3 m. A diagonal below 5 (units) suggests metres. Returns nullopt
/// when the cloud has no valid point.
std::optional<LengthUnit> guessLengthUnit(const PointCloud& cloud_in_file_units);

/// A warning sentence when `declared` disagrees with the guess from the extent (e.g. "--units mm
/// but the cloud spans 0.9 mm: is it in metres? pass --units m"), or an empty string.
std::string unitsSanityWarning(const PointCloud& cloud_in_file_units, LengthUnit declared);

} // namespace scanpick::core
