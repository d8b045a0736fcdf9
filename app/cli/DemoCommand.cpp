// scanpick-cli demo: writes the demo scenes (a PhoXi bin of supports and the support's teach scan).
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"

#include "core/common/Error.h"
#include "core/sim/Suite.h"

#include <iostream>
#include <memory>

namespace scanpick::cli {

void registerDemoCommand(CLI::App& app) {
  auto out = std::make_shared<std::string>();
  CLI::App* demo = addCommand(app, "demo",
                              "Generate the demo: a simulated PhoXi scan of 8 supports in a bin and the "
                              "support's teach scan, with ground truth.",
                              [out] {
                                if (out->empty())
                                  throw core::Error("--out DIR is required");
                                for (const auto& f : core::writeDemoScenes(*out))
                                  std::cout << "wrote " << f.string() << "\n";
                                return kOk;
                              });
  demo->add_option("--out", *out, "output folder");
}

} // namespace scanpick::cli
