#pragma once
/// @file Log.h
/// The core's logger. Front ends add sinks (the GUI's log dock, the CLI's stderr) to it.

#include <memory>
#include <spdlog/logger.h>

namespace scanpick::core {

/// The shared "scanpick" logger (created on first use, stderr sink, level info or the one named
/// by the environment variable SCANPICK_LOG_LEVEL: trace, debug, info, warn, error, off). Creating
/// it also silences PCL's own console output below debug level.
std::shared_ptr<spdlog::logger> logger();

} // namespace scanpick::core
