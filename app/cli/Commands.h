#pragma once
/// @file Commands.h
/// Registration functions of scanpick-cli's subcommands, one per source file.

#include <CLI/CLI.hpp>

namespace scanpick::cli {
void registerSynthCommands(CLI::App& app);    ///< synth, synth-suite (SynthCommand.cpp)
void registerEvalCommand(CLI::App& app);      ///< eval (EvalCommand.cpp)
void registerTeachCommand(CLI::App& app);     ///< teach (TeachCommand.cpp)
void registerRecognizeCommand(CLI::App& app); ///< recognize (RecognizeCommand.cpp)
void registerDeviceCommands(CLI::App& app);   ///< devices, capture (DeviceCommands.cpp)
void registerDemoCommand(CLI::App& app);      ///< demo: the README's main job (DemoCommand.cpp)
void registerParamsCommand(CLI::App& app);    ///< params: the parameter table (ParamsCommand.cpp)
void registerBenchCommand(CLI::App& app);     ///< bench: recognition timings (BenchCommand.cpp)
void registerServeCommand(CLI::App& app);     ///< serve: the robot link (ServeCommand.cpp)
void registerCalibrateCommand(CLI::App& app); ///< calibrate: hand-eye (CalibrateCommand.cpp)
void registerClearBinCommand(
    CLI::App& app); ///< clear-bin: virtual bin clearing (ClearBinCommand.cpp)
void registerRestingSidesCommand(
    CLI::App& app); ///< resting-sides: which sides to teach (RestingSidesCommand.cpp)
} // namespace scanpick::cli
