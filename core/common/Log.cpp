#include "core/common/Log.h"

#include "core/common/Error.h"
#include "core/common/Progress.h"

#include <algorithm>
#include <cstdlib>
#include <pcl/console/print.h>
#include <spdlog/sinks/stdout_color_sinks.h>

namespace scanpick::core {

std::shared_ptr<spdlog::logger> logger() {
  static const std::shared_ptr<spdlog::logger> instance = [] {
    auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
    auto log = std::make_shared<spdlog::logger>("scanpick", sink);
    // SCANPICK_LOG_LEVEL=debug (trace, info, warn, error, off) shows more or less.
    const char* level = std::getenv("SCANPICK_LOG_LEVEL");
    log->set_level(level ? spdlog::level::from_str(level) : spdlog::level::info);
    log->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    // PCL prints to the terminal itself (every degenerate RANSAC sample, every field a conversion
    // does not find): silent unless scanpick's own log asks for debug output.
    pcl::console::setVerbosityLevel(log->level() <= spdlog::level::debug ? pcl::console::L_DEBUG
                                                                         : pcl::console::L_ALWAYS);
    return log;
  }();
  return instance;
}

void reportProgress(const ProgressFn& progress, double fraction) {
  if (progress && !progress(std::clamp(fraction, 0.0, 1.0)))
    throw Cancelled();
}

ProgressFn subProgress(const ProgressFn& parent, double begin, double end) {
  if (!parent)
    return {};
  return [parent, begin, end](double f) { return parent(begin + (end - begin) * f); };
}

} // namespace scanpick::core
