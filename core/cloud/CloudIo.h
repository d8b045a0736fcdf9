#pragma once
/// @file CloudIo.h
/// Reading and writing point clouds (PCD and PLY), converting units to millimetres.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Units.h"
#include "core/common/Progress.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace scanpick::core {

/// What loadCloud found besides the points.
struct LoadedCloud {
  PointCloud cloud;          ///< in millimetres, organization kept
  std::string units_warning; ///< unitsSanityWarning() text, empty when the extent looks right
};

/// Loads a .pcd or .ply file whose coordinates are in `units`, converting to millimetres.
/// Reads XYZ and, when present, normals (normal_x/y/z) and colour (rgb/rgba), in the file's
/// `units`, or with no `units` in metres when the extent says so (guessLengthUnit; logged) and
/// millimetres otherwise. `progress` moves with the bytes read (to 0.6), then after decoding
/// (0.9) and at the end; it may cancel.
/// Throws Error for a missing, unreadable, truncated or empty file, an unknown extension, or a
/// cloud with no valid point.
LoadedCloud loadCloud(const std::filesystem::path& path, std::optional<LengthUnit> units,
                      const ProgressFn& progress = {});

/// Decodes the bytes of a .pcd or .ply file (`extension` ".pcd" or ".ply") in the file's own
/// units. Non-finite or implausible coordinates (core/cloud/PcdFile.h) become invalid points,
/// counted in `implausible`. Throws Error naming `source` for anything malformed.
PointCloud decodeCloud(std::string_view bytes, const std::string& extension,
                       const std::string& source, std::size_t& implausible);

/// Writes a binary PCD in millimetres, keeping the organization (width x height) and NaNs.
/// Writes normals and colours when present. Atomic: the destination is replaced only when
/// complete. Throws Error on failure.
void saveCloudPcd(const std::filesystem::path& path, const PointCloud& cloud_mm);

/// Writes a binary little-endian PLY (vertices, normals and colours when present), atomically.
void saveCloudPly(const std::filesystem::path& path, const PointCloud& cloud_mm);

/// Saves by extension (.pcd or .ply).
void saveCloud(const std::filesystem::path& path, const PointCloud& cloud_mm);

} // namespace scanpick::core
