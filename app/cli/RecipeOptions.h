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
#include <string>
#include <unistd.h>

namespace scanpick::cli {

struct RecipeOptions {
  std::string preset;  ///< preset name (resources/presets/<name>.json) or file
  std::string params;  ///< preset file with parameters
  std::string units = "mm";
  std::string sensor;  ///< sensor preset name; empty = default

  void add(CLI::App* sub) {
    sub->add_option("--preset", preset, "Parameter preset: a name in resources/presets or a file");
    sub->add_option("--params", params, "Parameter file (scanpick-preset JSON)");
    sub->add_option("--units", units, "Units of the input clouds: mm or m")->capture_default_str();
    sub->add_option("--sensor", sensor,
                    "Sensor preset (phoxi-m-1032, phoxi-m-2064, kinect-v1); default phoxi-m-1032");
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

/// The parameters chosen on the command line (defaults when neither option is given).
inline core::RecognitionParams resolveParams(const RecipeOptions& o,
                                             const core::RecognitionParams& fallback = {}) {
  if (!o.preset.empty() && !o.params.empty())
    throw core::Error("give either --preset or --params, not both");
  if (!o.params.empty())
    return core::loadPreset(o.params).params;
  if (!o.preset.empty())
    return core::loadPreset(findPreset(o.preset)).params;
  return fallback;
}

/// Loads a cloud in the given units, warning on stderr when its extent suggests other units.
inline core::PointCloud loadWithUnitsCheck(const std::string& path, const std::string& units) {
  core::LoadedCloud loaded = core::loadCloud(path, core::parseLengthUnit(units));
  if (!loaded.units_warning.empty())
    std::cerr << "warning: " << path << ": " << loaded.units_warning << "\n";
  return std::move(loaded.cloud);
}

} // namespace scanpick::cli
