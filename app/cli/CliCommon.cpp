#include "app/cli/CliCommon.h"

#include "core/common/Error.h"
#include "core/model/ViewCoverage.h"

#include <cstdio>
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

void printViewCoverage(const core::ViewCoverage& coverage) {
  const core::ViewCoverageOptions defaults;
  std::printf("view coverage: %.0f %% of the directions a part can be seen from lie within %.0f "
              "deg of a taught view",
              100.0 * coverage.covered, defaults.tolerance_deg);
  if (coverage.unplaced > 0)
    std::printf(" (%zu view(s) left out: they do not know their place in the part)",
                coverage.unplaced);
  if (!coverage.missing_part.empty()) {
    std::printf("; to cover more, teach the part seen from");
    for (std::size_t i = 0; i < coverage.missing_part.size(); ++i) {
      const Eigen::Vector3d& d = coverage.missing_part[i];
      std::printf("%s (%.2f, %.2f, %.2f)", i == 0 ? "" : ",", d.x(), d.y(), d.z());
    }
    std::printf(" (part frame, from the part towards the camera)");
  }
  std::printf("\n");
}

} // namespace scanpick::cli
