// scanpick-cli calibrate: hand-eye calibration from robot poses and scans of the sphere target
// (docs/calibration.md). Runs core::calib::runCalibration (as the GUI's dialog does), prints the
// target found in every scan, the residual of every pose and the rejected ones, and writes the
// calibration atomically; on any error it writes nothing.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "core/calib/CalibJson.h"
#include "core/calib/CalibrationRun.h"
#include "core/cloud/Units.h"
#include "core/common/AtomicFile.h"
#include "core/common/Error.h"

#include <cstdio>
#include <iostream>
#include <memory>

namespace scanpick::cli {
namespace {

struct CalibrateOptions {
  std::string mode, poses, target, out;
  std::string units = "mm";
  std::string pose_units; ///< empty = units
  core::calib::HandEyeParams params;
};

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

void printPose(const std::string& name, const Eigen::Isometry3d& T) {
  Eigen::Quaterniond q(T.linear());
  if (q.w() < 0)
    q.coeffs() = -q.coeffs();
  const Eigen::Vector3d t = T.translation();
  std::cout << "  " << name << ": position " << fixed(t.x(), 3) << ", " << fixed(t.y(), 3) << ", "
            << fixed(t.z(), 3) << " mm, quaternion (w x y z) " << fixed(q.w(), 6) << " "
            << fixed(q.x(), 6) << " " << fixed(q.y(), 6) << " " << fixed(q.z(), 6) << "\n";
  for (int r = 0; r < 4; ++r) {
    std::cout << "   ";
    for (int c = 0; c < 4; ++c)
      std::cout << " " << fixed(T.matrix()(r, c), c == 3 ? 3 : 6);
    std::cout << "\n";
  }
}

int runCalibrate(const CalibrateOptions& o) {
  using namespace core::calib;
  core::checkWritable(o.out);
  CalibrationRequest request;
  request.mode = modeFromName(o.mode);
  request.poses_file = o.poses;
  request.target_file = o.target;
  request.scan_units = core::parseLengthUnit(o.units);
  request.pose_units = core::parseLengthUnit(o.pose_units.empty() ? o.units : o.pose_units);
  request.params = o.params;
  const CalibrationOutcome run = runCalibration(request, {});
  for (std::size_t i = 0; i < run.scans.size(); ++i) {
    const ScanReport& scan = run.scans[i];
    if (!scan.units_warning.empty())
      std::cerr << "warning: scan " << i + 1 << ": " << scan.units_warning << "\n";
    std::cout << "scan " << i + 1 << " " << run.entries[i].scan.filename().string() << ": "
              << scan.spheres_found << " of " << run.target.sphere_centres_mm.size()
              << " spheres, fit to the target " << fixed(scan.fit_rms_mm, 3) << " mm RMS\n";
  }
  if (!run.result)
    throw core::Error(run.error);
  const HandEyeMode mode = request.mode;
  const std::vector<PoseEntry>& entries = run.entries;
  const TargetLayout& target = run.target;
  const HandEyeResult& result = *run.result;
  std::cout << "\npose  rms mm  max mm  rot deg\n";
  for (const auto& r : result.residuals) {
    char line[96];
    std::snprintf(line, sizeof line, "%4d  %6.3f  %6.3f  %7.4f", r.index + 1, r.rms_mm, r.max_mm,
                  r.rot_deg);
    std::cout << line << (r.rejected ? "  rejected" : "") << "\n";
  }
  int rejected = 0;
  for (const auto& r : result.residuals)
    if (r.rejected) {
      std::cout << "rejected pose " << r.index + 1 << " ("
                << entries[std::size_t(r.index)].scan.string() << "): " << r.reason << "\n";
      ++rejected;
    }
  if (rejected == 0)
    std::cout << "no pose rejected\n";
  std::cout << "\n"
            << modeName(mode) << " calibration from " << result.poses_used << " of "
            << entries.size() << " poses, residuals " << fixed(result.rms_mm, 3) << " mm / "
            << fixed(result.rms_deg, 4) << " deg RMS:\n";
  printPose(result.cameraName(), result.T_camera);
  printPose(result.targetName(), result.T_target);
  saveCalibration(o.out, result, target);
  std::cout << "wrote " << o.out << "\n";
  return kOk;
}

} // namespace

void registerCalibrateCommand(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* sub = addCommand(
      app, "calibrate",
      "Hand-eye calibration from robot poses and scans of the sphere target "
      "(docs/calibration.md):\n"
      "  calibrate --mode eye-to-hand --poses poses.json --out calibration.json\n"
      "eye-to-hand: fixed camera, target on the flange (gives T_base_camera, T_flange_target);\n"
      "eye-in-hand: camera on the flange, fixed target (gives T_flange_camera, T_base_target).",
      [o] { return runCalibrate(*o); });
  sub->add_option("--mode", o->mode, "eye-to-hand or eye-in-hand")
      ->required()
      ->check(CLI::IsMember({"eye-to-hand", "eye-in-hand"}));
  sub->add_option("--poses", o->poses,
                  "Poses file: [{\"scan\": PATH, \"T_base_flange\": 4x4 or {x, y, z, qw, qx, qy, "
                  "qz}}, ...]; scan paths relative to the file")
      ->required();
  sub->add_option("--target", o->target,
                  "Target file (sphere radius and centres); default: the built-in 4-sphere target");
  sub->add_option("--units", o->units, "Units of the scans and the robot positions: mm or m")
      ->capture_default_str()
      ->check(CLI::IsMember({"mm", "m"}));
  sub->add_option("--pose-units", o->pose_units,
                  "Units of the robot positions when they differ from the scans': mm or m")
      ->check(CLI::IsMember({"mm", "m"}));
  sub->add_option("--out", o->out, "Calibration file to write (JSON)")->required();
  sub->add_option("--max-rms-mm", o->params.max_rms_mm,
                  "Fail when the poses kept still disagree by more than this RMS (mm)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  sub->add_option("--outlier-floor-mm", o->params.outlier_floor_mm,
                  "Never reject a pose whose sphere residual is below this (mm)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

} // namespace scanpick::cli
