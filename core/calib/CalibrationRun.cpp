#include "core/calib/CalibrationRun.h"

#include "core/calib/TargetDetection.h"
#include "core/cloud/CloudIo.h"
#include "core/common/Error.h"

namespace scanpick::core::calib {
namespace {

/// `message` with "scan N (PATH): " before it, as `scanpick-cli calibrate` words it.
std::string scanError(std::size_t index, const std::filesystem::path& scan,
                      const std::string& message) {
  return "scan " + std::to_string(index + 1) + " (" + scan.string() + "): " + message;
}

/// Stops the run when the operator cancelled.
void report(const ProgressFn& progress, double fraction) {
  if (progress && !progress(fraction))
    throw Cancelled();
}

/// Finds the target in every scan of `out.entries`, filling out.scans; returns the samples.
std::vector<HandEyeSample> detectAll(const CalibrationRequest& request, CalibrationOutcome& out,
                                     const ProgressFn& progress) {
  const TargetDetectParams detect;
  std::vector<HandEyeSample> samples;
  const std::size_t n = out.entries.size();
  for (std::size_t i = 0; i < n; ++i) {
    report(progress, double(i) / double(n + 1));
    const PoseEntry& entry = out.entries[i];
    HandEyeSample sample;
    sample.T_base_flange = entry.T_base_flange;
    ScanReport scan;
    try {
      LoadedCloud loaded = loadCloud(entry.scan, request.scan_units);
      scan.units_warning = loaded.units_warning;
      sample.observation = detectTarget(loaded.cloud, out.target, detect);
    } catch (const std::exception& e) {
      // Unreadable scans, the target not found: the message names the scan.
      out.failed_scan = int(i);
      throw Error(scanError(i, entry.scan, e.what()));
    }
    scan.spheres_found = sample.observation.found();
    scan.fit_rms_mm = sample.observation.fit_rms_mm;
    out.scans.push_back(scan);
    samples.push_back(std::move(sample));
  }
  return samples;
}

} // namespace

std::vector<PoseEntry> readPoses(const std::filesystem::path& poses_file, LengthUnit pose_units) {
  return loadPoseList(poses_file, double(millimetresPer(pose_units)));
}

CalibrationOutcome runCalibration(const CalibrationRequest& request, const ProgressFn& progress) {
  CalibrationOutcome out;
  try {
    const TargetDetectParams detect;
    out.target = request.target_file.empty()
                     ? defaultTarget()
                     : loadTarget(request.target_file, 2 * detect.match_tolerance_mm);
    out.entries = readPoses(request.poses_file, request.pose_units);
    // Pose count and motion first: a bad pose set fails before any scan is read.
    std::vector<Eigen::Isometry3d> flanges;
    for (const auto& e : out.entries)
      flanges.push_back(e.T_base_flange);
    checkPoses(flanges, request.params);
    const std::vector<HandEyeSample> samples = detectAll(request, out, progress);
    report(progress, double(samples.size()) / double(samples.size() + 1));
    out.result = calibrateHandEye(request.mode, samples, out.target, request.params);
  } catch (const Cancelled&) {
    throw;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

} // namespace scanpick::core::calib
