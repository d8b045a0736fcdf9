#pragma once
// The message of the core::Error a call throws, for tests that check what an error says.
#include "core/common/Error.h"

#include <functional>
#include <string>

namespace scanpick::test {

/// What `f` throws as core::Error, or "no error" when it returns.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "no error";
}

} // namespace scanpick::test
