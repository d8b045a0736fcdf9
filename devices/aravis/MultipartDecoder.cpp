#include "devices/aravis/MultipartDecoder.h"

#include "devices/Camera.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace scanpick::devices {
namespace {

/// Bytes per pixel of the formats we decode, 0 for others.
std::size_t bytesPerPixel(std::uint32_t format) {
  switch (format) {
  case pfnc::kMono8:
  case pfnc::kConfidence8:
    return 1;
  case pfnc::kMono10:
  case pfnc::kMono12:
  case pfnc::kMono16:
  case pfnc::kConfidence16:
    return 2;
  case pfnc::kRgb8:
    return 3;
  case pfnc::kCoord3dA32f:
  case pfnc::kCoord3dB32f:
  case pfnc::kCoord3dC32f:
  case pfnc::kConfidence32f:
    return 4;
  case pfnc::kCoord3dAbc32f:
    return 12;
  default:
    return 0;
  }
}

std::string hex(std::uint32_t v) {
  std::ostringstream s;
  s << "0x" << std::hex << std::uppercase << v;
  return s.str();
}

DeviceError protocol(const std::string& what) {
  return DeviceError(
      DeviceErrorKind::Protocol,
      "the scanner sent " + what +
          ": check that the firmware is 1.13 or newer and that Range is Coord3D_ABC32f or "
          "Coord3D_C32f");
}

template <typename T> T readLe(const std::byte* p) {
  T v;
  std::memcpy(&v, p, sizeof v); // x86-64 and ARM64 are little-endian like GigE Vision payloads here
  return v;
}

float floatAt(const BufferPart& part, std::size_t i, std::size_t component = 0) {
  return readLe<float>(part.data.data() + i * bytesPerPixel(part.pixel_format) + component * 4);
}

} // namespace

PartKind guessPartKind(std::uint32_t pixel_format, bool range_seen) {
  switch (pixel_format) {
  case pfnc::kCoord3dAbc32f:
    return range_seen ? PartKind::Normal : PartKind::Range;
  case pfnc::kCoord3dC32f:
    return range_seen ? PartKind::Unknown : PartKind::Range;
  case pfnc::kCoord3dA32f:
    return PartKind::CoordinateMapA;
  case pfnc::kCoord3dB32f:
    return PartKind::CoordinateMapB;
  case pfnc::kConfidence8:
  case pfnc::kConfidence16:
  case pfnc::kConfidence32f:
    return PartKind::Confidence;
  case pfnc::kMono8:
  case pfnc::kMono10:
  case pfnc::kMono12:
  case pfnc::kMono16:
  case pfnc::kRgb8:
    return PartKind::Intensity;
  default:
    return PartKind::Unknown;
  }
}

core::PointCloud decodeParts(std::span<const BufferPart> parts,
                             const std::optional<ProjectedCParams>& projected) {
  const auto range_it = std::find_if(parts.begin(), parts.end(),
                                     [](const BufferPart& p) { return p.kind == PartKind::Range; });
  if (range_it == parts.end())
    throw protocol("no Range part (enable ComponentSelector=Range, ComponentEnable=true)");
  const BufferPart& range = *range_it;
  const std::size_t n = static_cast<std::size_t>(range.width) * range.height;
  if (n == 0)
    throw protocol("an empty Range part");
  const BufferPart* map_a = nullptr;
  const BufferPart* map_b = nullptr;
  for (const BufferPart& part : parts) {
    if (part.kind == PartKind::Unknown)
      continue;
    const std::size_t bpp = bytesPerPixel(part.pixel_format);
    if (bpp == 0)
      throw protocol("pixel format " + hex(part.pixel_format) + " which scanpick cannot decode");
    if (part.width != range.width || part.height != range.height)
      throw protocol("parts of different sizes (" + std::to_string(part.width) + "x" +
                     std::to_string(part.height) + " vs Range " + std::to_string(range.width) +
                     "x" + std::to_string(range.height) + ")");
    if (part.data.size() < n * bpp)
      throw protocol("a truncated part (" + std::to_string(part.data.size()) + " bytes, " +
                     std::to_string(n * bpp) + " expected)");
    if (part.kind == PartKind::CoordinateMapA)
      map_a = &part;
    if (part.kind == PartKind::CoordinateMapB)
      map_b = &part;
  }

  core::PointCloud cloud;
  cloud.width = range.width;
  cloud.height = range.height;
  cloud.points_mm.resize(n);
  if (range.pixel_format == pfnc::kCoord3dAbc32f) {
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3f p(floatAt(range, i, 0), floatAt(range, i, 1), floatAt(range, i, 2));
      // PhoXi marks "no measurement" as (0,0,0).
      cloud.points_mm[i] = (p.allFinite() && !p.isZero()) ? p : core::invalidPoint();
    }
  } else if (range.pixel_format == pfnc::kCoord3dC32f) {
    if (!projected || projected->focal_length_px <= 0 || projected->aspect_ratio <= 0)
      throw protocol("a Coord3D_C32f range without Scan3dFocalLength/Scan3dAspectRatio");
    for (std::size_t i = 0; i < n; ++i) {
      const float z = floatAt(range, i);
      if (!std::isfinite(z) || z <= 0.0f) {
        cloud.points_mm[i] = core::invalidPoint();
        continue;
      }
      const double a = map_a ? floatAt(*map_a, i) : static_cast<double>(i % range.width);
      const double b = map_b ? floatAt(*map_b, i) : static_cast<double>(i / range.width);
      cloud.points_mm[i] = {
          static_cast<float>(z * (a - projected->principal_u_px) / projected->focal_length_px),
          static_cast<float>(z * (b - projected->principal_v_px) /
                             (projected->focal_length_px * projected->aspect_ratio)),
          z};
    }
  } else {
    throw protocol("a Range part in " + hex(range.pixel_format) + " format");
  }

  for (const BufferPart& part : parts) {
    const std::byte* d = part.data.data();
    switch (part.kind) {
    case PartKind::Normal:
      if (part.pixel_format != pfnc::kCoord3dAbc32f)
        throw protocol("a Normal part in " + hex(part.pixel_format) +
                       " format (Coord3D_ABC32f expected)");
      cloud.normals.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        cloud.normals[i] = {floatAt(part, i, 0), floatAt(part, i, 1), floatAt(part, i, 2)};
      break;
    case PartKind::Confidence:
      cloud.confidence.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        double c = part.pixel_format == pfnc::kConfidence8
                       ? static_cast<double>(readLe<std::uint8_t>(d + i))
                   : part.pixel_format == pfnc::kConfidence16  ? readLe<std::uint16_t>(d + 2 * i)
                   : part.pixel_format == pfnc::kConfidence32f ? readLe<float>(d + 4 * i)
                                                               : -1.0;
        if (c < 0.0)
          throw protocol("a Confidence part in " + hex(part.pixel_format) + " format");
        cloud.confidence[i] =
            static_cast<std::uint8_t>(std::clamp(std::isfinite(c) ? c : 0.0, 0.0, 255.0));
      }
      break;
    case PartKind::Intensity:
      if (part.pixel_format == pfnc::kRgb8) {
        cloud.colors.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          cloud.colors[i] = {readLe<std::uint8_t>(d + 3 * i), readLe<std::uint8_t>(d + 3 * i + 1),
                             readLe<std::uint8_t>(d + 3 * i + 2)};
      } else if (bytesPerPixel(part.pixel_format) <= 2 && part.pixel_format != pfnc::kConfidence8 &&
                 part.pixel_format != pfnc::kConfidence16) {
        cloud.intensity.resize(n);
        const bool wide = bytesPerPixel(part.pixel_format) == 2;
        for (std::size_t i = 0; i < n; ++i)
          cloud.intensity[i] =
              wide ? readLe<std::uint16_t>(d + 2 * i) : readLe<std::uint8_t>(d + i);
      } else {
        throw protocol("an Intensity part in " + hex(part.pixel_format) + " format");
      }
      break;
    default:
      break;
    }
  }
  return cloud;
}

} // namespace scanpick::devices
