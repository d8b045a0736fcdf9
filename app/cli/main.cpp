// scanpick-cli: the headless front end for integrators and robot controllers.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "core/common/Memory.h"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  scanpick::core::keepFreedMemoryForReuse(); // a suite or a bench recognizes scene after scene
  CLI::App app{"scanpick-cli: 3D object recognition for bin picking, taught from a scan.\n"
               "Units are millimetres unless a command says otherwise."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("scanpick ") + SCANPICK_VERSION);
#ifdef SCANPICK_HAS_SYNTHCOMMAND
  scanpick::cli::registerSynthCommands(app);
#endif
#ifdef SCANPICK_HAS_EVALCOMMAND
  scanpick::cli::registerEvalCommand(app);
#endif
#ifdef SCANPICK_HAS_TEACHCOMMAND
  scanpick::cli::registerTeachCommand(app);
#endif
#ifdef SCANPICK_HAS_RECOGNIZECOMMAND
  scanpick::cli::registerRecognizeCommand(app);
#endif
#ifdef SCANPICK_HAS_DEVICECOMMANDS
  scanpick::cli::registerDeviceCommands(app);
#endif
#ifdef SCANPICK_HAS_DEMOCOMMAND
  scanpick::cli::registerDemoCommand(app);
#endif
#ifdef SCANPICK_HAS_PARAMSCOMMAND
  scanpick::cli::registerParamsCommand(app);
#endif
#ifdef SCANPICK_HAS_BENCHCOMMAND
  scanpick::cli::registerBenchCommand(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return 0;
}
