// libFuzzer target: point cloud files (PCD in every encoding, PLY). The first byte chooses the
// format; the rest is the file. Only core::Error may come out.
#include "core/cloud/CloudIo.h"
#include "core/common/Error.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::size_t implausible = 0;
  try {
    scanpick::core::decodeCloud(bytes, data[0] % 2 ? ".ply" : ".pcd", "fuzz", implausible);
  } catch (const scanpick::core::Error&) {
  }
  return 0;
}
