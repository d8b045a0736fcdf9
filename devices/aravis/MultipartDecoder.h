#pragma once
/// @file MultipartDecoder.h
/// Turns the parts of a PhoXi GigE Vision buffer (Range, Intensity, Confidence, Normal ...) into
/// an organized cloud. A pure function on bytes: no Aravis types, so it is tested on buffers
/// built in the test, independent of how a particular camera lays out its multipart payload.

#include "core/cloud/PointCloud.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace scanpick::devices {

/// GenICam PFNC pixel formats the decoder understands (values from the PFNC standard; Aravis
/// 0.8 has no constants for the Coord3D and Confidence families).
namespace pfnc {
inline constexpr std::uint32_t kMono8 = 0x01080001;
inline constexpr std::uint32_t kMono10 = 0x01100003;
inline constexpr std::uint32_t kMono12 = 0x01100005;
inline constexpr std::uint32_t kMono16 = 0x01100007;
inline constexpr std::uint32_t kRgb8 = 0x02180014;
inline constexpr std::uint32_t kCoord3dAbc32f = 0x026000C0;
inline constexpr std::uint32_t kCoord3dA32f = 0x012000BD;
inline constexpr std::uint32_t kCoord3dB32f = 0x012000BE;
inline constexpr std::uint32_t kCoord3dC32f = 0x012000BF;
inline constexpr std::uint32_t kConfidence8 = 0x010800C6;
inline constexpr std::uint32_t kConfidence16 = 0x011000C7;
inline constexpr std::uint32_t kConfidence32f = 0x012000C8;
} // namespace pfnc

/// What a part carries (GenICam ComponentSelector names).
enum class PartKind {
  Unknown,
  Range,
  Intensity,
  Confidence,
  Normal,
  CoordinateMapA,
  CoordinateMapB
};

/// One part of a buffer. `data` is row-major, tightly packed, little-endian.
struct BufferPart {
  PartKind kind = PartKind::Unknown;
  std::uint32_t pixel_format = 0;
  std::uint32_t width = 0, height = 0;
  std::span<const std::byte> data;
};

/// Projection of a `Coord3D_C32f` (Z only, "ProjectedC") range:
/// x = z (A - principal_u) / focal, y = z (B - principal_v) / (focal aspect), where A/B are the
/// CoordinateMapA/B parts, or the column/row index when those parts are absent.
struct ProjectedCParams {
  double focal_length_px = 0; ///< Scan3dFocalLength
  double aspect_ratio = 1;    ///< Scan3dAspectRatio
  double principal_u_px = 0;  ///< Scan3dPrincipalPointU
  double principal_v_px = 0;  ///< Scan3dPrincipalPointV
};

/// Kind of a part whose component id is unknown, guessed from its pixel format and order:
/// the first Coord3D_ABC32f/C32f is Range, a second ABC32f is Normal, Confidence* is
/// Confidence, Mono/RGB is Intensity, A32f/B32f are coordinate maps.
PartKind guessPartKind(std::uint32_t pixel_format, bool range_seen);

/// Decodes the parts into an organized cloud (mm; invalid (0,0,0) or non-finite points become
/// NaN): Range -> points_mm; Normal -> normals; Confidence -> confidence (0 = invalid);
/// Intensity Mono* -> intensity, RGB8 -> colors. Unknown kinds are ignored.
/// Throws DeviceError Protocol when there is no Range part, a part's size does not match its
/// width x height x pixel size, parts disagree on the grid, a pixel format is unsupported, or a
/// C32f range comes without `projected` parameters.
core::PointCloud decodeParts(std::span<const BufferPart> parts,
                             const std::optional<ProjectedCParams>& projected = std::nullopt);

} // namespace scanpick::devices
