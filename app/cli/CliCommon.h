#pragma once
/// @file CliCommon.h
/// Shared pieces of scanpick-cli's subcommands.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace scanpick::core {
struct ViewCoverage;
} // namespace scanpick::core

namespace scanpick::cli {

/// Exit codes of scanpick-cli.
enum ExitCode : int {
  kOk = 0,
  kFailure = 1,     ///< the operation failed (message on stderr says why and what to do)
  kUsage = 2,       ///< wrong command-line usage
  kCancelled = 130, ///< interrupted
};

/// Runs `body`, turning scanpick::core::Error and other exceptions into a one-line message on
/// stderr ("scanpick-cli <command>: error: ...") and a non-zero exit code.
int runGuarded(const std::string& command, const std::function<int()>& body);

/// Prints on one line the taught views' coverage of the directions the part may be seen from in a
/// bin, and which views to teach next (teach and recognize).
void printViewCoverage(const core::ViewCoverage& coverage);

/// Registers a subcommand; `run` is called when it is chosen and its return value is the exit code.
CLI::App* addCommand(CLI::App& app, const std::string& name, const std::string& description,
                     std::function<int()> run);

} // namespace scanpick::cli
