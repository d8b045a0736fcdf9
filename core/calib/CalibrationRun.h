#pragma once
/// @file CalibrationRun.h
/// A hand-eye calibration run from a poses file, as `scanpick-cli calibrate` and the GUI's
/// calibration dialog both run it (docs/calibration.md): one sequence of steps, so both give the
/// same result and the same messages. Reports per scan, also on failure; cancellable.

#include "core/calib/CalibJson.h"
#include "core/calib/HandEye.h"
#include "core/cloud/Units.h"
#include "core/common/Progress.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::calib {

/// What the operator chose: the CLI's --mode, --poses, --target, --units and --pose-units.
struct CalibrationRequest {
  HandEyeMode mode = HandEyeMode::EyeToHand;
  std::filesystem::path poses_file;
  std::filesystem::path target_file; ///< empty: defaultTarget()
  LengthUnit scan_units = LengthUnit::Millimetres;
  LengthUnit pose_units = LengthUnit::Millimetres;
  HandEyeParams params;
};

/// The target found in one scan.
struct ScanReport {
  int spheres_found = 0;
  double fit_rms_mm = 0;     ///< TargetObservation::fit_rms_mm
  std::string units_warning; ///< LoadedCloud::units_warning, empty when none
};

/// The outcome of a run: a result, or the error that stopped it (then nothing is to be saved).
struct CalibrationOutcome {
  std::vector<PoseEntry> entries; ///< the poses file as read (empty if unreadable)
  TargetLayout target;
  std::vector<ScanReport> scans;       ///< the scans searched so far, in the poses file's order
  std::optional<HandEyeResult> result; ///< set on success
  std::string error;    ///< the core's message on failure (as the CLI prints it), else empty
  int failed_scan = -1; ///< 0-based index of the scan the error is about, -1 for none
};

/// The poses file read as the CLI reads it (loadPoseList, positions in `pose_units`).
/// Throws Error.
std::vector<PoseEntry> readPoses(const std::filesystem::path& poses_file, LengthUnit pose_units);

/// Runs the calibration: target file, poses file, checkPoses (before any scan is read), then per
/// scan loadCloud + detectTarget, then calibrateHandEye. Errors end up in the outcome (a scan's
/// error starts "scan N (PATH): " as in the CLI). `progress` moves with the scans read; when it
/// returns false the run stops with core::Cancelled.
CalibrationOutcome runCalibration(const CalibrationRequest& request, const ProgressFn& progress);

} // namespace scanpick::core::calib
