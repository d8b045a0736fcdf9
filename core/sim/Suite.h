#pragma once
/// @file Suite.h
/// Fixed, seeded sets of simulated scenes for evaluation, and the demo scenes.

#include "core/common/Progress.h"
#include "core/sim/Synth.h"

#include <filesystem>
#include <string>
#include <vector>

namespace scanpick::core {

/// One scene of a suite: where it goes (relative to the output folder, without extension) and
/// what it holds.
struct SuiteScene {
  std::filesystem::path relative_prefix;  ///< e.g. "phoxi-bin/scene-000"
  SynthRequest request;
};

/// The suites: "phoxi-bin" (20 one-part bins, 5 per built-in part, 6-15 instances, plus 4 mixed
/// bins), "kinect-bin" (12 one-part bins, 6-12 instances), "teach" (each part alone on a table,
/// for each sensor preset: teach/<sensor>/<part>, and the other sides it can rest on,
/// teach/<sensor>/<part>-side1..3, for models taught from several views).
std::vector<std::string> suiteNames();

/// The scenes of suite `name` for `seed` (kDefaultSuiteSeed unless testing). Throws Error for an
/// unknown suite.
std::vector<SuiteScene> suiteScenes(const std::string& name, std::uint64_t seed);

/// The seed `scanpick-cli synth-suite` uses, so everyone gets the same files.
inline constexpr std::uint64_t kDefaultSuiteSeed = 20160401;

/// Generates `scenes` under `out_dir` (each scene written as by writeSynthScene) and returns the
/// files written. `on_scene` (may be empty) is called after each scene with its prefix.
std::vector<std::filesystem::path> writeSuite(
    const std::filesystem::path& out_dir, const std::vector<SuiteScene>& scenes,
    const ProgressFn& progress = {},
    const std::function<void(const std::filesystem::path&)>& on_scene = {});

/// Writes the demo scenes into `dir`: `demo-bin` (PhoXi M 1032, 8 supports in a bin, seed 7) and
/// `support-teach` (one support on a table, same sensor) and `support-teach-side1` (the same
/// turned over, resting on both legs as most do in the bin). Returns the files written.
std::vector<std::filesystem::path> writeDemoScenes(const std::filesystem::path& dir,
                                                   const ProgressFn& progress = {});

} // namespace scanpick::core
