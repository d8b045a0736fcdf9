#pragma once
/// @file Error.h
/// The one exception type the core throws for bad input: its message says what went wrong and
/// what to do about it, so command-line tools and the GUI can show it as it is.

#include <stdexcept>
#include <string>

namespace scanpick::core {

/// Bad input or an operation that cannot be carried out (missing file, empty cloud, wrong units,
/// future file version, ...). `what()` is a complete sentence meant for the operator.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Thrown when a progress callback asked to stop.
class Cancelled : public std::runtime_error {
public:
  Cancelled() : std::runtime_error("cancelled") {}
};

} // namespace scanpick::core
