// scanpick-cli: the headless front end for integrators and robot controllers.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "core/common/Memory.h"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  using namespace scanpick::cli;
  scanpick::core::keepFreedMemoryForReuse(); // a suite or a bench recognizes scene after scene
  CLI::App app{"scanpick-cli: 3D object recognition for bin picking, taught from a scan.\n"
               "Units are millimetres unless a command says otherwise."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("scanpick ") + SCANPICK_VERSION);
  scanpick::cli::registerSynthCommands(app);
  scanpick::cli::registerEvalCommand(app);
  scanpick::cli::registerTeachCommand(app);
  scanpick::cli::registerRecognizeCommand(app);
  scanpick::cli::registerDeviceCommands(app);
  scanpick::cli::registerDemoCommand(app);
  scanpick::cli::registerParamsCommand(app);
  scanpick::cli::registerBenchCommand(app);
  scanpick::cli::registerServeCommand(app);
  scanpick::cli::registerCalibrateCommand(app);
  scanpick::cli::registerClearBinCommand(app);
  scanpick::cli::registerRestingSidesCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every other parse error is a usage error (exit 2), whatever
    // CLI11's own code for it.
    const int code = app.exit(e);
    return code == 0 ? kOk : kUsage;
  }
  return 0;
}
