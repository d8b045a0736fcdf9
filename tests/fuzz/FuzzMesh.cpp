// libFuzzer target: triangle mesh files (PLY, STL, OBJ, legacy VTK). The first byte chooses the
// format; the rest is the file. Only core::Error may come out.
#include "core/common/Error.h"
#include "core/sim/MeshIo.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  static const char* const kExtensions[] = {".ply", ".stl", ".obj", ".vtk"};
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    scanpick::core::decodeMesh(bytes, kExtensions[data[0] % 4], "fuzz");
  } catch (const scanpick::core::Error&) {
  }
  return 0;
}
