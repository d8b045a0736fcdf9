// libFuzzer target: taught model files (.spmodel). Only core::Error may come out.
#include "core/common/Error.h"
#include "core/model/ModelFile.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    scanpick::core::decodeModel(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const scanpick::core::Error&) {
  }
  return 0;
}
