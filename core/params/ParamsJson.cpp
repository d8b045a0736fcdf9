#include "core/params/ParamsJson.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/JsonText.h"
#include "core/params/ParameterTable.h"

#include <algorithm>
#include <cmath>

namespace scanpick::core {

namespace {
constexpr int kPresetVersion = 2;
/// How deep presets may build on one another (a loop of bases stops here).
constexpr int kMaxBaseDepth = 8;
} // namespace

nlohmann::json paramsToJson(const RecognitionParams& params) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& info : parameterTable()) {
    const double v = info.get(params);
    switch (info.type) {
    case ParamType::Bool:
      out[info.key] = v != 0.0;
      break;
    case ParamType::Int:
      out[info.key] = static_cast<long long>(std::llround(v));
      break;
    case ParamType::Enum:
      out[info.key] = info.choices.at(static_cast<std::size_t>(v));
      break;
    case ParamType::Double:
      out[info.key] = v;
      break;
    }
  }
  return out;
}

RecognitionParams paramsFromJson(const nlohmann::json& object, RecognitionParams params) {
  if (!object.is_object())
    throw Error("parameters must be a JSON object of {\"key\": value}");
  for (const auto& [key, value] : object.items()) {
    const ParamInfo* info = findParameter(key);
    if (!info)
      throw Error("unknown parameter '" + key + "' (see docs/parameters.md for the keys)");
    double v = 0.0;
    if (info->type == ParamType::Enum && value.is_string()) {
      const auto it =
          std::find(info->choices.begin(), info->choices.end(), value.get<std::string>());
      if (it == info->choices.end())
        throw Error("parameter '" + key + "': unknown choice '" + value.get<std::string>() + "'");
      v = static_cast<double>(it - info->choices.begin());
    } else if (value.is_boolean()) {
      v = value.get<bool>() ? 1.0 : 0.0;
    } else if (value.is_number()) {
      v = value.get<double>();
    } else {
      throw Error("parameter '" + key + "': expected a number, got " + jsonExcerpt(value));
    }
    checkParamValue(*info, v);
    info->set(params, v);
  }
  return params;
}

namespace {
Preset loadPresetAt(const std::filesystem::path& path, int depth) {
  const std::string text = readFile(path);
  const nlohmann::json doc = parseJsonText(text, "preset '" + path.string() + "'", "");
  if (!doc.is_object() || doc.value("format", "") != "scanpick-preset")
    throw Error("'" + path.string() +
                "' is not a scanpick preset (missing \"format\": "
                "\"scanpick-preset\")");
  const int version = doc.value("version", 0);
  if (version > kPresetVersion)
    throw Error("preset '" + path.string() + "' has version " + std::to_string(version) +
                "; this scanpick reads up to version " + std::to_string(kPresetVersion) +
                ": update scanpick");
  Preset preset;
  preset.name = doc.value("name", path.stem().string());
  preset.description = doc.value("description", "");
  // Version 2: a preset may name the preset it builds on (a file next to it); its own params
  // then change only what differs.
  RecognitionParams base;
  if (doc.contains("base")) {
    if (!doc["base"].is_string() || doc["base"].get<std::string>().empty())
      throw Error("preset '" + path.string() + "': \"base\" must name a preset file next to it");
    if (depth >= kMaxBaseDepth)
      throw Error("preset '" + path.string() + "': its bases go deeper than " +
                  std::to_string(kMaxBaseDepth) + " presets (do two presets name each other?)");
    const auto base_path = path.parent_path() / (doc["base"].get<std::string>() + ".json");
    base = loadPresetAt(base_path, depth + 1).params;
  }
  try {
    preset.params = paramsFromJson(doc.value("params", nlohmann::json::object()), base);
  } catch (const Error& e) {
    throw Error("preset '" + path.string() + "': " + e.what());
  }
  return preset;
}
} // namespace

Preset loadPreset(const std::filesystem::path& path) {
  return loadPresetAt(path, 0);
}

void savePreset(const std::filesystem::path& path, const Preset& preset) {
  nlohmann::json doc{{"format", "scanpick-preset"},
                     {"version", kPresetVersion},
                     {"name", preset.name},
                     {"description", preset.description},
                     {"params", paramsToJson(preset.params)}};
  writeFileAtomic(path, dumpJsonText(doc, 2) + "\n");
}

} // namespace scanpick::core
