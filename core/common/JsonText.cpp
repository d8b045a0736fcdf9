#include "core/common/JsonText.h"

#include "core/common/Error.h"

namespace scanpick::core {
namespace {

/// The deepest nesting of `text`, counting brackets outside strings; stops past `limit`.
int nestingDepth(std::string_view text, int limit) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit)
        return deepest;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

} // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& source,
                             const std::string& hint) {
  if (nestingDepth(text, kMaxJsonDepth) > kMaxJsonDepth)
    throw Error(source + " is not valid JSON (nested deeper than " + std::to_string(kMaxJsonDepth) +
                " levels)" + hint);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(source + " is not valid JSON (" + e.what() + ")" + hint);
  }
}

std::string dumpJsonText(const nlohmann::json& doc, int indent) {
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

Error jsonFieldError(const std::string& source, const nlohmann::json::exception& e) {
  return Error(source + ": a field is missing or of the wrong type (" + e.what() +
               "): regenerate the file or fix it");
}

std::string jsonExcerpt(const nlohmann::json& value) {
  const std::string text = dumpJsonText(value);
  return text.size() <= 60 ? text : text.substr(0, 57) + "...";
}

} // namespace scanpick::core
