#pragma once
/// @file PcdFile.h
/// PCD (Point Cloud Data, versions 0.5 to 0.7) decoded and encoded in memory. The header is
/// validated before anything is allocated or indexed: every keyword, size, type and count, the
/// point count against the grid and against the bytes the file holds; the data is read by field
/// type (float and double coordinates alike), so that a damaged or foreign file gets a clear
/// error instead of a crash, a hang or points read as zeros.

#include "core/cloud/PointCloud.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace scanpick::core {

/// One FIELDS entry of a PCD header.
struct PcdField {
  std::string name;
  char type = 'F';         ///< 'F' floating point, 'I' signed, 'U' unsigned integer
  std::uint32_t size = 4;  ///< bytes per element: 1, 2, 4 or 8
  std::uint32_t count = 1; ///< elements per point
  std::size_t offset = 0;  ///< bytes from the start of a point record
};

/// A validated PCD header.
struct PcdHeader {
  std::vector<PcdField> fields;
  std::uint32_t width = 0;     ///< columns, or points of an unorganized cloud
  std::uint32_t height = 1;    ///< rows; 1 for an unorganized cloud
  std::string data;            ///< "ascii", "binary" or "binary_compressed"
  std::size_t point_step = 0;  ///< bytes per point record
  std::size_t data_offset = 0; ///< where the data starts in the file

  [[nodiscard]] std::size_t points() const { return static_cast<std::size_t>(width) * height; }
};

/// The most points a PCD may declare (2^31 - 1, the grid's index range).
inline constexpr std::uint64_t kMaxPcdPoints = 0x7FFFFFFF;
/// Coordinates farther than this from the origin, in the file's units, are not measurements
/// (a flipped bit in a float gives 1e20): they are read as invalid points.
inline constexpr double kMaxPcdCoordinate = 1e7;

/// `n` as a float normal, or NaN when it is not one (not finite, or longer than 2: a corrupt value
/// that a float cannot even hold must not reach a cast).
Eigen::Vector3f normalOrNaN(const Eigen::Vector3d& n);

/// Parses and validates the header of `bytes`. Throws Error naming `source` and what is wrong.
PcdHeader parsePcdHeader(std::string_view bytes, const std::string& source);

/// Decodes a whole PCD file (in the file's units): x, y, z as float or double (required), normals
/// (normal_x/y/z, float or double) and colour (rgb or rgba, packed) when present. Non-finite or
/// implausible coordinates (beyond kMaxPcdCoordinate) become invalid (NaN) points, counted in
/// `implausible` when given. Throws Error for anything else that is wrong.
PointCloud decodePcd(std::string_view bytes, const std::string& source,
                     std::size_t* implausible = nullptr);

/// Appends `cloud`'s points as little-endian binary records, one per point: x, y, z (float), the
/// normal (3 floats) when the cloud has normals, the colour when it has colours (one packed uint32
/// 0x00RRGGBB with `packed_rgb`, as PCD stores it, else three bytes, as PLY does).
void appendPointRecords(std::string& out, const PointCloud& cloud, bool packed_rgb);

/// Encodes `cloud` as a binary PCD 0.7 (x, y, z float; normals and rgb when present).
std::string encodePcdBinary(const PointCloud& cloud);

} // namespace scanpick::core
