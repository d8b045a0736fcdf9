// scanpick-cli eval: scores recognition results against the virtual scanner's ground truth
// (docs/evaluation.md). Single mode compares one results file with one ground truth; suite mode
// compares RESULTS_DIR/scene-XXX.json with every DIR/scene-XXX.gt.json.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "core/common/Error.h"
#include "core/eval/Evaluator.h"
#include "core/eval/RenderCheck.h"
#include "core/eval/ReportFormat.h"

#include <iostream>
#include <memory>

namespace scanpick::cli {
namespace {

struct EvalOptions {
  std::string truth, suite, results, json;
  std::vector<std::string> teach_truths;
  core::eval::Tolerances tolerances;
  bool details = false;
  double render_check_mm = 0.0;
};

int runEval(const EvalOptions& o) {
  if (o.truth.empty() == o.suite.empty())
    throw core::Error("give either --truth scene.gt.json (one scene) or --suite DIR (a suite)");
  if (o.results.empty())
    throw core::Error("--results is required (a results file, or a folder with --suite)");
  const std::vector<std::filesystem::path> teach_paths(o.teach_truths.begin(),
                                                       o.teach_truths.end());
  const auto teach = core::eval::loadTeachTruths(teach_paths, o.suite);

  core::eval::EvalReport report =
      o.suite.empty() ? core::eval::evaluateFiles(o.truth, o.results, teach, o.tolerances)
                      : core::eval::evaluateSuite(o.suite, o.results, teach, o.tolerances);
  if (o.render_check_mm > 0)
    report = core::eval::withRenderCheck(std::move(report), o.render_check_mm);
  std::cout << core::eval::reportToTable(report, o.details);
  if (!o.json.empty()) {
    core::eval::saveReportJson(o.json, report);
    std::cout << "\nwrote " << o.json << "\n";
  }
  return kOk;
}

} // namespace

void registerEvalCommand(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = addCommand(
      app, "eval",
      "Score recognition results against ground truth: precision, recall (instances >= 50 % "
      "visible), recall at 99 % precision, symmetry-aware pose errors at the origin and the grip "
      "points, time per scene.\n"
      "  one scene: eval --truth scene.gt.json --results result.json --teach-truth teach.gt.json\n"
      "  a suite:   eval --suite DIR --results RESULTS_DIR [--teach-truth T.gt.json] [--json out]",
      [o] { return runEval(*o); });
  sub->add_option("--truth", o->truth, "Ground truth of one scene (scene.gt.json)");
  sub->add_option("--suite", o->suite, "Suite folder with scene-XXX.gt.json files");
  sub->add_option("--results", o->results,
                  "Results file (one scene) or folder with scene-XXX.json (suite)");
  sub->add_option("--teach-truth", o->teach_truths,
                  "Ground truth of the teach scene, or a folder of them (repeatable; with several "
                  "parts, each results file is matched by its model name). Suite mode without it "
                  "looks in DIR, then DIR/../teach/<sensor>");
  sub->add_option("--json", o->json, "Also write the report as JSON to this file");
  sub->add_option("--translation-tolerance", o->tolerances.translation_fraction,
                  "True positive: origin error at most this fraction of the part diameter")
      ->default_val(0.1)
      ->check(CLI::PositiveNumber);
  sub->add_option("--rotation-tolerance-deg", o->tolerances.rotation_deg,
                  "True positive: rotation error at most this many degrees")
      ->default_val(10.0)
      ->check(CLI::Range(0.0, 180.0));
  sub->add_option("--min-visible", o->tolerances.min_visible_fraction,
                  "Recall counts instances at least this visible")
      ->default_val(0.5)
      ->check(CLI::Range(0.0, 1.0));
  sub->add_flag("--accept-free-turns", o->tolerances.accept_free_turns,
                "Score a detection that reports a free_turn_axis (its view does not show the "
                "part's turn about that axis) up to a turn about it, and one that reports "
                "alternative_poses (turns its scan cannot tell apart) by the best of them; "
                "default: strictly");
  sub->add_option("--render-check", o->render_check_mm,
                  "Also render each scene's ground truth again (noise-free) with each detection's "
                  "part at its pose instead of the nearest instance's, and report the share of "
                  "that instance's pixels whose depth then differs by more than this many mm: "
                  "near 0 when the scan cannot tell the pose from the truth (built-in parts only)")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--details", o->details,
                "Also list each detection (one scene) or each scene (suite)");
}

} // namespace scanpick::cli
