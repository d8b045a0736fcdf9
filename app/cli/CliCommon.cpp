#include "app/cli/CliCommon.h"

#include "core/common/Error.h"

#include <iostream>

namespace scanpick::cli {

int runGuarded(const std::string& command, const std::function<int()>& body) {
  try {
    return body();
  } catch (const core::Cancelled&) {
    std::cerr << "scanpick-cli " << command << ": cancelled\n";
    return kCancelled;
  } catch (const core::Error& e) {
    std::cerr << "scanpick-cli " << command << ": error: " << e.what() << "\n";
    return kFailure;
  } catch (const std::exception& e) {
    std::cerr << "scanpick-cli " << command << ": internal error: " << e.what()
              << " (please report this with the input that caused it)\n";
    return kFailure;
  }
}

CLI::App* addCommand(CLI::App& app, const std::string& name, const std::string& description,
                     std::function<int()> run) {
  CLI::App* sub = app.add_subcommand(name, description);
  sub->callback([name, run = std::move(run)] {
    const int code = runGuarded(name, run);
    if (code != kOk)
      throw CLI::RuntimeError(code);
  });
  return sub;
}

} // namespace scanpick::cli
