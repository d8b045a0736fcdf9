#pragma once
/// @file JsonText.h
/// JSON text read and written the same way by every scanpick file: parsing refuses nesting deeper
/// than kMaxJsonDepth before the parser sees the text (a file nested 60,000 levels deep would
/// otherwise exhaust the stack), and writing replaces bytes that are not UTF-8 (a file name in
/// another encoding) instead of failing after the work is done.

#include "core/common/Error.h"

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace scanpick::core {

/// The deepest nesting of arrays and objects a scanpick JSON file may have (its own go to 6).
inline constexpr int kMaxJsonDepth = 64;

/// Parses `text`; throws Error "`source` is not valid JSON (...)" with `hint` appended, also for
/// nesting deeper than kMaxJsonDepth.
nlohmann::json parseJsonText(std::string_view text, const std::string& source,
                             const std::string& hint);

/// `doc.dump(indent)` with invalid UTF-8 replaced by U+FFFD.
std::string dumpJsonText(const nlohmann::json& doc, int indent = -1);

/// The Error withJsonErrors throws.
Error jsonFieldError(const std::string& source, const nlohmann::json::exception& e);

/// Calls `read` (a reader of a parsed JSON document), turning nlohmann's exceptions (a field of
/// the wrong type, a missing key read with at()) into an Error that names `source`.
template <typename Read> auto withJsonErrors(const std::string& source, Read&& read) {
  try {
    return read();
  } catch (const nlohmann::json::exception& e) {
    throw jsonFieldError(source, e);
  }
}

/// `value` as JSON text cut to at most 60 characters, for error messages.
std::string jsonExcerpt(const nlohmann::json& value);

} // namespace scanpick::core
