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
  std::filesystem::path relative_prefix; ///< e.g. "phoxi-bin/scene-000"
  SynthRequest request;
  /// When not empty: a bin scan turned into a teach scan by isolateNovelView (written as kind
  /// "teach"), avoiding the views of these teach scenes of the suite (written before it).
  std::vector<std::filesystem::path> novel_against;
};

/// The direction from the camera towards an instance's centre, in the part frame (unit).
Eigen::Vector3d viewDirectionInPart(const Scene& scene, const PartInstance& instance);

/// A teach scan cut from a bin scan, for the view of a part as it lies in a bin that the table
/// scans do not show (a support face-down on one leg, the other leg hanging below it). Of the
/// instances at least 90 % visible (else the most visible one), it keeps the one whose viewing
/// direction (viewDirectionInPart), up to the part's symmetries, is farthest from every one of
/// `taught_views_part`; the scan keeps that instance's points and the bin's (as an operator's
/// lasso around it leaves them), the others become NaN, and the scene holds that instance only,
/// with its bounding box as the crop box. Throws Error when the bin has no instance in view.
SynthScene isolateNovelView(SynthScene bin, const std::vector<Eigen::Vector3d>& taught_views_part);

/// The seed `scanpick-cli synth-suite` uses, so everyone gets the same files.
inline constexpr std::uint64_t kDefaultSuiteSeed = 20160401;
/// Parts of the random-parts suite unless told otherwise.
inline constexpr int kDefaultRandomParts = 50;

/// The suites: "phoxi-bin" (20 one-part bins, 5 per built-in part, 6-15 instances, plus 4 mixed
/// bins), "kinect-bin" (12 one-part bins, 6-12 instances), "teach" (each part alone on a table,
/// for each sensor preset: teach/<sensor>/<part>, and the other sides it can rest on,
/// teach/<sensor>/<part>-side1..3, for models taught from several views, plus
/// teach/<sensor>/<part>-bin, one part cut from a bin of ten by isolateNovelView).
std::vector<std::string> suiteNames();

/// The scenes of suite `name` for `seed` (kDefaultSuiteSeed unless testing). Besides
/// suiteNames(), "random-parts": `random_parts` parts generated from the seed (randomPart,
/// core/sim/RandomPart.h), each in random-parts/part-KKK/ with its table scans on each side it
/// can rest on (teach, teach-side1..3) and three PhoXi M bins of ten, fewer of a large part
/// (scene-000..002). Throws Error for an unknown suite.
std::vector<SuiteScene> suiteScenes(const std::string& name, std::uint64_t seed,
                                    int random_parts = kDefaultRandomParts);

/// Generates `scenes` under `out_dir` (each scene written as by writeSynthScene) and returns the
/// files written. `on_scene` (may be empty) is called after each scene with its prefix.
std::vector<std::filesystem::path>
writeSuite(const std::filesystem::path& out_dir, const std::vector<SuiteScene>& scenes,
           const ProgressFn& progress = {},
           const std::function<void(const std::filesystem::path&)>& on_scene = {});

/// Writes the demo scenes into `dir`: `demo-bin` (PhoXi M 1032, 8 supports in a bin, seed 7) and
/// `support-teach` (one support on a table, same sensor) and `support-teach-side1` (the same
/// turned over, resting on both legs as most do in the bin). Returns the files written.
std::vector<std::filesystem::path> writeDemoScenes(const std::filesystem::path& dir,
                                                   const ProgressFn& progress = {});

} // namespace scanpick::core
