#pragma once
/// @file RecipeOptions.h
/// Options shared by teach and recognize: parameters (--preset / --params), units and sensor.

#include "core/cloud/CloudIo.h"
#include "core/cloud/Sensor.h"
#include "core/common/Error.h"
#include "core/params/ParamsJson.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

namespace scanpick::cli {

struct RecipeOptions {
  std::string preset; ///< preset name (resources/presets/<name>.json) or file
  std::string params; ///< preset file with parameters
  std::string units = "mm";
  std::string sensor;                 ///< sensor preset name; empty = default
  std::vector<std::string> overrides; ///< KEY=VALUE, applied after the preset or file

  void add(CLI::App* sub) {
    sub->add_option("--preset", preset, "Parameter preset: a name in resources/presets or a file");
    sub->add_option("--params", params, "Parameter file (scanpick-preset JSON)");
    sub->add_option("--units", units, "Units of the input clouds: mm or m")->capture_default_str();
    sub->add_option("--sensor", sensor,
                    "Sensor preset (phoxi-m-1032, phoxi-m-2064, kinect-v1); default phoxi-m-1032");
    sub->add_option("--set", overrides,
                    "Override one parameter, KEY=VALUE (e.g. matching.min_coverage=0.6; keys: "
                    "scanpick-cli params); repeatable, applied after --preset/--params");
  }
};

/// Finds a preset by file path or by name under resources/presets (current folder, then the
/// source tree next to the executable).
inline std::filesystem::path findPreset(const std::string& name) {
  namespace fs = std::filesystem;
  if (fs::exists(name))
    return name;
  std::vector<fs::path> roots{fs::current_path()};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  for (fs::path dir = exe.parent_path(); !ec && !dir.empty() && dir != dir.root_path();
       dir = dir.parent_path())
    roots.push_back(dir);
  for (const auto& root : roots) {
    const fs::path candidate = root / "resources" / "presets" / (name + ".json");
    if (fs::exists(candidate))
      return candidate;
  }
  throw core::Error("unknown preset '" + name +
                    "': give a preset file or a name from resources/presets");
}

/// KEY=VALUE of --set or --view-set as a one-key JSON object: numbers and booleans as JSON,
/// anything else (an enum name) as a string.
inline nlohmann::json parseSetting(const std::string& kv, const std::string& option) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
    throw core::Error(option + " '" + kv + "': expected KEY=VALUE, e.g. matching.min_coverage=0.6");
  const std::string value = kv.substr(eq + 1);
  nlohmann::json parsed = nlohmann::json::parse(value, nullptr, false);
  if (parsed.is_discarded() || parsed.is_object() || parsed.is_array())
    parsed = value;
  return {{kv.substr(0, eq), parsed}};
}

/// The parameters chosen on the command line (defaults when neither option is given).
inline core::RecognitionParams resolveParams(const RecipeOptions& o,
                                             const core::RecognitionParams& fallback = {}) {
  if (!o.preset.empty() && !o.params.empty())
    throw core::Error("give either --preset or --params, not both");
  core::RecognitionParams params = fallback;
  if (!o.params.empty())
    params = core::loadPreset(o.params).params;
  else if (!o.preset.empty())
    params = core::loadPreset(findPreset(o.preset)).params;
  for (const auto& kv : o.overrides)
    params = core::paramsFromJson(parseSetting(kv, "--set"), params);
  return params;
}

/// Loads a cloud in the given units, warning on stderr when its extent suggests other units.
inline core::PointCloud loadWithUnitsCheck(const std::string& path, const std::string& units) {
  core::LoadedCloud loaded = core::loadCloud(path, core::parseLengthUnit(units));
  if (!loaded.units_warning.empty())
    std::cerr << "warning: " << path << ": " << loaded.units_warning << "\n";
  return std::move(loaded.cloud);
}

} // namespace scanpick::cli
