#pragma once
/// @file Evaluator.h
/// Scores recognition results against ground truth: one-to-one greedy matching by score,
/// symmetry-aware pose errors, precision, recall, recall at 99 % precision, error statistics and
/// time per scene; for one scene or a whole suite (aggregated and per part).

#include "core/common/Progress.h"
#include "core/eval/GroundTruth.h"
#include "core/eval/PoseError.h"
#include "core/eval/ResultsFile.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::eval {

/// What became of one detection.
struct DetectionOutcome {
  int detection_id = 0;
  double score = 0.0;
  bool true_positive = false;
  int instance_id = -1;           ///< matched instance (true positives only), else -1
  bool counts_for_recall = false; ///< the matched instance is visible enough for recall
  /// Error to the nearest instance of the part (matched or not), for diagnosis; absent when the
  /// scene holds no instance of the part.
  std::optional<PoseError> error;
  int nearest_instance_id = -1;
  /// The detection's own part pose (scene frame, mm): T_scene_model · T_model_part.
  Eigen::Isometry3d T_scene_part = Eigen::Isometry3d::Identity();
  /// The render check (RenderCheck.h), when it was run: the share of the pixels of the instance
  /// the detection lies on that a scan would see differently with the part at T_scene_part.
  std::optional<double> render_difference;
  /// The detection's reported alternative poses as part poses (scene frame, mm).
  std::vector<Eigen::Isometry3d> alternatives_scene_part;
  /// The render check of a true positive that reports alternative poses: the largest share of
  /// pixels a scan would see differently from the truth at any pose it offers (its own and its
  /// alternatives). Small when what it reports is an ambiguity no scan can tell; large when the
  /// scan could have told which pose is right.
  std::optional<double> ambiguity_render_difference;
};

/// One scene's evaluation.
struct SceneEvaluation {
  std::string name;          ///< scene name (ground-truth file stem)
  std::string part;          ///< part that was searched (from the teach ground truth)
  int instances = 0;         ///< instances of that part in the scene
  int visible_instances = 0; ///< of those, at least Tolerances::min_visible_fraction visible
  std::vector<DetectionOutcome> outcomes; ///< in matching order (score descending)
  std::optional<double> total_ms;         ///< results' timings_ms.total
  /// The ground truth the scene was evaluated against (kept for the render check; not part of
  /// the report's JSON).
  std::shared_ptr<const GroundTruth> truth;
};

/// Median, 95th percentile (linear interpolation between order statistics) and maximum.
struct Stats {
  std::size_t count = 0;
  double mean = 0.0, median = 0.0, p95 = 0.0, max = 0.0;
};

/// Statistics of `values` (all zero when empty).
Stats computeStats(std::vector<double> values);

/// Metrics over a set of scenes.
struct Summary {
  std::string label; ///< "all" or a part name
  int scenes = 0, detections = 0, true_positives = 0, instances = 0, visible_instances = 0;
  int recalled_visible = 0;        ///< visible instances matched by a true positive
  std::optional<double> precision; ///< true positives / detections (none without detections)
  std::optional<double> recall;    ///< recalled_visible / visible_instances
  /// Highest recall reached by a score threshold whose precision is ≥ 0.99 (0 when none) and
  /// that threshold (the lowest kept score).
  double recall_at_99_precision = 0.0;
  std::optional<double> threshold_at_99_precision;
  double average_precision = 0.0; ///< area under the interpolated precision-recall curve
  Stats translation_mm, rotation_deg, grip_mm; ///< over true positives
  Stats time_ms;                               ///< per scene with timings
  /// The render check's differing shares of true and of false positives (empty when not run).
  Stats render_difference_tp, render_difference_fp;
  /// The ambiguity_render_difference of the true positives that report alternative poses.
  Stats render_difference_ambiguous;
};

/// Metrics over `scenes` (label names the group).
Summary summarize(const std::vector<SceneEvaluation>& scenes, const std::string& label);

/// The evaluation of one or more scenes.
struct EvalReport {
  Tolerances tolerances;
  std::vector<SceneEvaluation> scenes;
  Summary overall;
  std::vector<Summary> per_part; ///< one per searched part, by name
};

/// Evaluates one scene. The searched part and T_teach_part are the single instance of `teach`
/// (a ground truth of kind "teach"). Detections become part poses with
/// T_scene_part = T_scene_model · T_teach_model⁻¹ · T_teach_part, then are matched greedily by
/// descending score, each to the nearest unmatched instance within tolerance.
/// Throws Error when `teach` does not hold exactly one instance.
/// With several models (views of one part taught from different scans), `view_teach[m]` is
/// the teach ground truth of results.models[m] (see selectViewTeachTruths); empty = `teach` for
/// every model. Throws Error when the views are of different parts. `truth` is kept in the
/// result (SceneEvaluation::truth): a caller done with it moves it in.
SceneEvaluation evaluateScene(GroundTruth truth, const ResultsFile& results,
                              const GroundTruth& teach, const Tolerances& tolerances,
                              const std::string& name,
                              const std::vector<const GroundTruth*>& view_teach = {});

/// The teach ground truth of each of the results' models, found by the model's teach scan file
/// name; empty when the results hold one model or a model names no teach scan. Throws Error
/// when a model's teach scan has no ground truth among `teach_truths`.
std::vector<const GroundTruth*> selectViewTeachTruths(const std::vector<GroundTruth>& teach_truths,
                                                      const ResultsFile& results);

/// Picks the teach ground truth for `results` on scene `truth`: the only one given; else the one
/// whose part is named like the results' model; else, when the scene holds one part type, that
/// part's. Throws Error when none fits.
const GroundTruth& selectTeachTruth(const std::vector<GroundTruth>& teach_truths,
                                    const ResultsFile& results, const GroundTruth& truth);

/// Builds the report (overall and per part) from evaluated scenes.
EvalReport makeReport(std::vector<SceneEvaluation> scenes, const Tolerances& tolerances);

/// Single mode: one ground truth, one results file.
EvalReport evaluateFiles(const std::filesystem::path& truth_path,
                         const std::filesystem::path& results_path,
                         const std::vector<GroundTruth>& teach_truths,
                         const Tolerances& tolerances);

/// Suite mode: every `scene-*.gt.json` in `suite_dir` (teach scenes excluded) against
/// `results_dir/scene-*.json`. Throws Error when the folder holds no scene or a results file is
/// missing (naming it).
EvalReport evaluateSuite(const std::filesystem::path& suite_dir,
                         const std::filesystem::path& results_dir,
                         const std::vector<GroundTruth>& teach_truths, const Tolerances& tolerances,
                         const ProgressFn& progress = {});

/// Teach ground truths in a folder (`*.gt.json` whose scene kind is "teach"), sorted by name.
std::vector<GroundTruth> findTeachTruths(const std::filesystem::path& dir);

/// Teach ground truths from `--teach-truth` arguments (files, or folders searched with
/// findTeachTruths). When `paths` is empty and `suite_dir` is set, looks in the suite folder,
/// then in `<suite_dir>/../teach/<sensor preset of its first scene>` (the layout synth-suite
/// writes). Throws Error when nothing is found, saying what to pass.
std::vector<GroundTruth> loadTeachTruths(const std::vector<std::filesystem::path>& paths,
                                         const std::filesystem::path& suite_dir = {});

} // namespace scanpick::core::eval
