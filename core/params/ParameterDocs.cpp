#include "core/params/ParameterDocs.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace scanpick::core {
namespace {

std::string number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

/// Markdown table cells must not contain a bare '|'.
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|')
      out += "\\|";
    else
      out += c;
  }
  return out.empty() ? "–" : out;
}

std::string pad(const std::string& text, std::size_t width) {
  // Width in code points, so labels with Greek letters line up.
  std::size_t length = 0;
  for (const char c : text)
    length += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  return length >= width ? text + " " : text + std::string(width - length, ' ');
}

} // namespace

std::string formatParamValue(const ParamInfo& info, double value) {
  switch (info.type) {
  case ParamType::Bool:
    return value != 0.0 ? "on" : "off";
  case ParamType::Enum: {
    const auto index = static_cast<std::size_t>(std::lround(value));
    return index < info.choices.size() ? info.choices[index] : number(value);
  }
  case ParamType::Int:
    return number(std::round(value));
  case ParamType::Double:
    return number(value);
  }
  return number(value);
}

std::string formatParamRange(const ParamInfo& info) {
  switch (info.type) {
  case ParamType::Bool:
    return "on/off";
  case ParamType::Enum: {
    std::string out;
    for (std::size_t i = 0; i < info.choices.size(); ++i)
      out += (i ? " | " : "") + info.choices[i];
    return out;
  }
  case ParamType::Int:
  case ParamType::Double:
    return number(info.min_value) + " – " + number(info.max_value);
  }
  return {};
}

std::string parametersMarkdown(const std::optional<RecognitionParams>& preset,
                               const std::string& preset_name) {
  const RecognitionParams defaults;
  std::ostringstream out;
  out << "# Recognition parameters\n\n"
      << "Generated with `scanpick-cli params --markdown > docs/parameters.md` from the parameter "
         "table in `core/params/ParameterTable.cpp`; do not edit by hand (a unit test fails when "
         "the two disagree).\n\n"
      << "Presets (`resources/presets/*.json`, format in [file-formats.md](file-formats.md)) "
         "and the GUI's editors use these keys; lengths are millimetres, angles radians unless "
         "the unit says otherwise. Changing a parameter recomputes its stage and the later "
         "ones only.\n";
  if (preset)
    out << "\nValues of preset **" << preset_name << "** are in the *value* column.\n";
  out << "\n## Tuned for a cell\n\n"
      << "Teach derives the others from the part and the scan; these are the ones an engineer "
         "sets for a cell (the GUI shows them first, the rest under *Show advanced "
         "parameters*):\n\n";
  for (const std::string_view key : kTunedParameters)
    if (const ParamInfo* info = findParameter(key))
      out << "- `" << info->key << "` (" << info->label << ")\n";
  // Grouped by stage in pipeline order (the seed is listed last in the table but belongs to
  // clustering).
  std::set<Stage> stages;
  for (const auto& info : parameterTable())
    stages.insert(info.stage);
  for (const Stage stage : stages) {
    out << "\n## " << stageName(stage) << "\n\n"
        << "| key | label | unit | default |" << (preset ? " value |" : "")
        << " range | description |\n"
        << "|---|---|---|---|" << (preset ? "---|" : "") << "---|---|\n";
    for (const auto& info : parameterTable()) {
      if (info.stage != stage)
        continue;
      out << "| `" << info.key << "` | " << cell(info.label) << " | " << cell(info.unit) << " | "
          << cell(formatParamValue(info, info.get(defaults))) << " | ";
      if (preset)
        out << cell(formatParamValue(info, info.get(*preset))) << " | ";
      out << cell(formatParamRange(info)) << " | " << cell(info.description) << " |\n";
    }
  }
  return out.str();
}

std::string parametersText(const std::optional<RecognitionParams>& preset) {
  const RecognitionParams values = preset.value_or(RecognitionParams{});
  std::ostringstream out;
  out << pad("key", 38) << pad("label", 28) << pad("unit", 7)
      << pad(preset ? "value" : "default", 16) << pad("range", 40) << "stage\n";
  for (const auto& info : parameterTable()) {
    out << pad(info.key, 38) << pad(info.label, 28) << pad(info.unit, 7)
        << pad(formatParamValue(info, info.get(values)), 16) << pad(formatParamRange(info), 40)
        << stageName(info.stage) << "\n"
        << "    " << info.description << "\n";
  }
  return out.str();
}

} // namespace scanpick::core
