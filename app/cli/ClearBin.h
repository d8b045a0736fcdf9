#pragma once
/// @file ClearBin.h
/// The virtual bin-clearing run of `scanpick-cli clear-bin` (docs/bin-clearing.md): a simulated
/// bin is scanned, the part recognized, the grasps planned, the best pick judged against the
/// ground truth and, when it succeeds, its instance taken out and the pile settled; then again.

#include "core/grasp/GraspPlanner.h"
#include "core/grasp/PickJudge.h"
#include "core/model/TaughtModel.h"
#include "core/params/Parameters.h"
#include "core/sim/Part.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::cli {

/// What to clear and how.
struct ClearBinSetup {
  core::Part part;
  int count = 20;                                               ///< instances dropped into the bin
  std::uint64_t seed = 0;                                       ///< the bin's (physics and noise)
  std::string sensor = "phoxi-m-1032";                          ///< sensor preset
  std::vector<std::shared_ptr<const core::TaughtModel>> models; ///< views of the part (joined)
  core::RecognitionParams params;
  std::vector<core::grasp::GraspSpec> grasps; ///< empty: each grip point along the model's +z
  core::grasp::Gripper gripper;
  core::grasp::GraspPlanParams planning;
  std::optional<core::grasp::BinEstimateParams> bin; ///< estimate the bin from each scan
  core::grasp::PickJudgeParams judge;
  int max_cycles = 0;        ///< 0: 2 × count + 5
  std::filesystem::path out; ///< overlay pictures cycle-NNN.png go here
};

/// One pick tried in a cycle and the judge's verdict on it.
struct PickAttempt {
  int detection = -1;
  std::string grip;
  Eigen::Isometry3d T_scene_tool = Eigen::Isometry3d::Identity();
  core::grasp::PickVerdict verdict;
  int instance = -1; ///< the instance it landed on, as numbered in the first scan; -1: none
};

/// One cycle: scan, recognize, plan, pick.
struct ClearCycle {
  int instances = 0;  ///< in the bin when scanned
  int detections = 0; ///< found by the recognizer
  int feasible = 0;   ///< grasps in the pick list
  double vision_ms = 0, planning_ms = 0;
  std::vector<PickAttempt> attempts; ///< in pick-list order, until one succeeded
  /// Why the other grasps were not listed: rejection kind ("tilt", "bin-collision", ...) → how
  /// many grasps it rejected (a grasp counts once for each of its reasons' kinds).
  std::map<std::string, int> rejections;
  int picked = -1; ///< instance taken out (first scan's numbering); -1: none
};

/// The run.
struct ClearBinReport {
  std::vector<ClearCycle> cycles;
  int count = 0, picks = 0, wrong_picks = 0, collisions = 0, left = 0;
  std::string stop_reason; ///< "bin empty", "no pickable grasp", "every grasp failed", ...
};

/// Teaches the part's four table views (sides 0-3, core::teachSideTurn) from simulated PhoXi teach
/// scans of seed `teach_seed`, each cropped with its ground truth's box, its floor removed, its
/// grip points and pose from the truth, and its parameters derived (core::autoTeachParams), as
/// `teach --crop-from-truth --remove-floor` without a preset does. A side that cannot be taught
/// (too few points or features) is left out with a warning on stderr; throws core::Error when none
/// can be. Views are joined.
std::vector<std::shared_ptr<const core::TaughtModel>>
autoTeachViews(const std::string& part_name, std::uint64_t teach_seed, const std::string& sensor);

/// Runs the cycles until the bin is empty, nothing can be picked or max_cycles. A failed pick
/// (wrong or colliding) takes nothing out: the cell tries the next grasp of the same pick list.
/// Writes the overlay picture of each cycle to setup.out. Deterministic for a given setup (but
/// the timings).
ClearBinReport clearBin(const ClearBinSetup& setup);

} // namespace scanpick::cli
