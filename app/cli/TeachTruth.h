#pragma once
/// @file TeachTruth.h
/// Teaching from a simulated teach scene: what its ground truth says about the part.

#include "core/model/TaughtModel.h"

#include <filesystem>

namespace scanpick::cli {

/// Sets what the ground truth of a teach scene (`scanpick-cli synth`, `<scene>.gt.json`) gives:
/// the crop box (oriented, centred on its own origin), the part's grip points unless `options`
/// has some, and, for a scene of one part, the part's pose (TeachOptions::T_scan_part, so that
/// views of the part are joined when searched together). Throws core::Error for a file that is
/// not valid ground truth (core::eval::loadGroundTruth: a pose that is not rigid, for one) or has
/// no crop box.
void teachOptionsFromTruth(const std::filesystem::path& truth_path, core::TeachOptions& options);

} // namespace scanpick::cli
