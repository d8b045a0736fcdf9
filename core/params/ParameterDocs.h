#pragma once
/// @file ParameterDocs.h
/// The parameter table as text: the Markdown of docs/parameters.md and a plain-text listing,
/// both generated from parameterTable() so the documentation cannot drift from the code.

#include "core/params/ParameterTable.h"

#include <optional>
#include <string>

namespace scanpick::core {

/// A parameter's value as written in documentation: numbers with up to 10 significant digits,
/// "on"/"off" for booleans, the choice name for enums.
std::string formatParamValue(const ParamInfo& info, double value);

/// The allowed range as written in documentation ("0.1 – 100", "on/off", "a | b | c").
std::string formatParamRange(const ParamInfo& info);

/// The Markdown of docs/parameters.md: one section per stage with a table (key, label, unit,
/// default, range, description). With `preset`, a "value" column shows its values next to the
/// defaults and the heading names it.
std::string parametersMarkdown(const std::optional<RecognitionParams>& preset = std::nullopt,
                               const std::string& preset_name = {});

/// A plain-text listing for terminals: one line per parameter (key, label, unit, default or
/// preset value, range, stage) followed by its indented description.
std::string parametersText(const std::optional<RecognitionParams>& preset = std::nullopt);

} // namespace scanpick::core
