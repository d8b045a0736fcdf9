// libFuzzer target: the parts of a PhoXi GigE Vision multipart buffer (devices/aravis). The input
// is cut into up to four parts, each led by a 6-byte header (kind, pixel format choice, width and
// height of 1..64); the rest of the input is shared out as their data. Only core::Error (a
// DeviceError) may come out.
#include "core/common/Error.h"
#include "devices/aravis/MultipartDecoder.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dev = scanpick::devices;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static constexpr std::array<std::uint32_t, 13> kFormats = {dev::pfnc::kMono8,
                                                             dev::pfnc::kMono10,
                                                             dev::pfnc::kMono12,
                                                             dev::pfnc::kMono16,
                                                             dev::pfnc::kRgb8,
                                                             dev::pfnc::kCoord3dAbc32f,
                                                             dev::pfnc::kCoord3dA32f,
                                                             dev::pfnc::kCoord3dB32f,
                                                             dev::pfnc::kCoord3dC32f,
                                                             dev::pfnc::kConfidence8,
                                                             dev::pfnc::kConfidence16,
                                                             dev::pfnc::kConfidence32f,
                                                             0x12345678u};
  if (size < 2)
    return 0;
  const std::size_t count = 1 + data[0] % 4;
  const bool projected = data[1] & 1;
  std::size_t pos = 2;
  std::vector<dev::BufferPart> parts;
  for (std::size_t i = 0; i < count && pos + 6 <= size; ++i, pos += 6) {
    dev::BufferPart part;
    part.kind = static_cast<dev::PartKind>(data[pos] % 8);
    part.pixel_format = kFormats[data[pos + 1] % kFormats.size()];
    part.width = 1 + data[pos + 2] % 64 + 64u * (data[pos + 3] % 2);
    part.height = 1 + data[pos + 4] % 64 + 64u * (data[pos + 5] % 2);
    parts.push_back(part);
  }
  if (parts.empty())
    return 0;
  const std::size_t share = (size - pos) / parts.size();
  for (auto& part : parts) {
    part.data = {reinterpret_cast<const std::byte*>(data + pos), share};
    pos += share;
  }
  try {
    dev::decodeParts(parts, projected ? std::optional<dev::ProjectedCParams>(
                                            dev::ProjectedCParams{1000.0, 1.0, 32.0, 32.0})
                                      : std::nullopt);
  } catch (const scanpick::core::Error&) {
  }
  return 0;
}
