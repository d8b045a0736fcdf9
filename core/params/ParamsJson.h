#pragma once
/// @file ParamsJson.h
/// Presets: RecognitionParams as JSON keyed by the metadata table's keys.
///
/// Format (version 2): `{"format": "scanpick-preset", "version": 2, "name": "...",
/// "description": "...", "base": "phoxi-bin", "params": {"keypoints.position_range_mm": 0.6,
/// ...}}`. Enum values may be given by name ("ransac") or index. Missing keys keep the base
/// preset's values (`base`, optional: a preset file of that name next to this one), or the
/// defaults. Version 1 (no base) is read as before.

#include "core/params/Parameters.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace scanpick::core {

/// Flat object {key: value} of all parameters (enums by name).
nlohmann::json paramsToJson(const RecognitionParams& params);

/// Applies {key: value} onto `base`. Throws Error naming an unknown key, a wrong type or a value
/// out of range.
RecognitionParams paramsFromJson(const nlohmann::json& object, RecognitionParams base = {});

/// A preset file's content.
struct Preset {
  std::string name;
  std::string description;
  RecognitionParams params;
};

/// Reads a preset and the presets it builds on; throws Error for a missing or malformed file
/// (its own or a base's), a future version, or bases that name each other.
Preset loadPreset(const std::filesystem::path& path);
/// Writes a preset atomically.
void savePreset(const std::filesystem::path& path, const Preset& preset);

} // namespace scanpick::core
