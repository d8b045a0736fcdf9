// libFuzzer target: the JSON files scanpick reads (parameters and presets, ground truth, results).
// The first byte chooses the reader; the rest is the file. Only core::Error may come out.
#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/eval/GroundTruth.h"
#include "core/eval/ResultsFile.h"
#include "core/params/ParamsJson.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0)
    return 0;
  namespace core = scanpick::core;
  try {
    const auto doc = core::parseJsonText(
        std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1), "fuzz", "");
    switch (data[0] % 3) {
    case 0:
      core::paramsFromJson(doc);
      break;
    case 1:
      core::eval::parseGroundTruth(doc, "fuzz");
      break;
    default:
      core::eval::parseResults(doc, "fuzz");
    }
  } catch (const core::Error&) {
  }
  return 0;
}
