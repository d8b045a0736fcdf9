#include "core/eval/Evaluator.h"

#include "core/common/Error.h"
#include "core/eval/JsonFields.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

namespace scanpick::core::eval {
namespace {

/// Translation plus rotation converted to the displacement of a point at the part's radius:
/// one number to compare candidate instances by.
double poseCost(const PoseError& e, double diameter_mm) {
  return e.translation_mm + e.rotation_deg * std::numbers::pi / 180.0 * diameter_mm / 2.0;
}

/// "scene-003.gt.json" -> "scene-003".
std::string sceneNameOf(const std::filesystem::path& truth_path) {
  std::string name = truth_path.filename().string();
  for (const std::string suffix : {".gt.json", ".json"})
    if (name.size() > suffix.size() && name.ends_with(suffix))
      return name.substr(0, name.size() - suffix.size());
  return name;
}

} // namespace

Stats computeStats(std::vector<double> values) {
  Stats s;
  s.count = values.size();
  if (values.empty())
    return s;
  std::sort(values.begin(), values.end());
  const auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(values.size() - 1);
    const auto lo = static_cast<std::size_t>(pos);
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (pos - static_cast<double>(lo)) * (values[hi] - values[lo]);
  };
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  s.median = quantile(0.5);
  s.p95 = quantile(0.95);
  s.max = values.back();
  return s;
}

namespace {

/// The one instance of a teach scene's ground truth; throws Error when it holds more or none.
const TruthInstance& taughtInstance(const GroundTruth& t) {
  if (t.instances.size() != 1)
    throw Error(
        "teach ground truth " + t.source + " holds " + std::to_string(t.instances.size()) +
        " instances; a teach scene must hold exactly one (pass the teach scene's .gt.json)");
  return t.instances.front();
}

/// Each model's frame relative to the part (T_model_part), from the scan that model was taught
/// from: its own teach truth in `view_teach`, else the first model's `taught` instance.
std::vector<Eigen::Isometry3d> modelFramesInPart(const ResultsFile& results,
                                                 const std::vector<const GroundTruth*>& view_teach,
                                                 const TruthInstance& taught) {
  std::vector<Eigen::Isometry3d> T_model_part;
  for (std::size_t m = 0; m < std::max<std::size_t>(1, results.models.size()); ++m) {
    const bool own = m < view_teach.size();
    const TruthInstance& view = own ? taughtInstance(*view_teach[m]) : taught;
    if (view.part != taught.part)
      throw Error(results.source + ": its models are views of different parts (" + taught.part +
                  ", " + view.part + "): evaluate one part at a time");
    const Eigen::Isometry3d T_teach_model =
        m < results.models.size() ? results.models[m].T_teach_model : results.T_teach_model;
    T_model_part.push_back(T_teach_model.inverse() * view.T_scene_part);
  }
  return T_model_part;
}

/// A pose estimate and the part as scored for it: a reported free turn is scored as a symmetry
/// of that pose alone.
struct Estimate {
  Eigen::Isometry3d T_scene_part;
  PartInfo scored;
};

/// The detection's pose and, when free turns are accepted, its reported alternative poses, each
/// as a pose of the part (T_model_part: the detection's model frame in the part).
std::vector<Estimate> estimatesOf(const ResultDetection& detection,
                                  const Eigen::Isometry3d& T_model_part, const PartInfo& part,
                                  const Tolerances& tolerances) {
  const auto estimate = [&](const Eigen::Isometry3d& T_scene_model,
                            const std::optional<ContinuousAxis>& free_turn_axis) {
    Estimate e{T_scene_model * T_model_part, part};
    if (tolerances.accept_free_turns && free_turn_axis && !part.symmetry.continuous_axis) {
      const Eigen::Isometry3d T_part_scene = e.T_scene_part.inverse();
      e.scored.symmetry.continuous_axis =
          ContinuousAxis{T_part_scene * free_turn_axis->point_mm,
                         T_part_scene.linear() * free_turn_axis->direction};
    }
    return e;
  };
  std::vector<Estimate> estimates{estimate(detection.T_scene_model, detection.free_turn_axis)};
  if (tolerances.accept_free_turns)
    for (std::size_t k = 0; k < detection.alternative_poses.size(); ++k)
      estimates.push_back(
          estimate(detection.alternative_poses[k], k < detection.alternative_free_turn_axes.size()
                                                       ? detection.alternative_free_turn_axes[k]
                                                       : std::nullopt));
  return estimates;
}

/// What the detections of one scene are judged against.
struct SceneTargets {
  const GroundTruth& truth;
  const PartInfo& part;
  const std::vector<Eigen::Isometry3d>& group; ///< the part's symmetries (symmetryGroup)
  const std::vector<std::size_t>& targets;     ///< indices of the truth's instances of the part
  const Tolerances& tolerances;
};

/// Judges one detection against the scene's instances: it matches the nearest instance within
/// tolerance that no better-scored detection has claimed (marked in `matched`), else it is a
/// false positive carrying its error to the nearest instance.
DetectionOutcome judgeDetection(const ResultDetection& detection,
                                const Eigen::Isometry3d& T_model_part, const SceneTargets& scene,
                                std::vector<bool>& matched) {
  const GroundTruth& truth = scene.truth;
  DetectionOutcome outcome;
  outcome.detection_id = detection.id;
  outcome.score = detection.score;
  outcome.T_scene_part = detection.T_scene_model * T_model_part;
  for (const auto& T_alternative : detection.alternative_poses)
    outcome.alternatives_scene_part.push_back(T_alternative * T_model_part);
  // Reported alternative poses are scored as poses of this detection too (the best one counts).
  const std::vector<Estimate> estimates =
      estimatesOf(detection, T_model_part, scene.part, scene.tolerances);
  double nearest_cost = 0.0, match_cost = 0.0;
  std::optional<PoseError> match_error;
  for (const std::size_t i : scene.targets) {
    PoseError e;
    double cost = std::numeric_limits<double>::infinity();
    for (const auto& est : estimates) {
      PoseError candidate = symmetricPoseError(est.T_scene_part, truth.instances[i].T_scene_part,
                                               est.scored, scene.group, scene.tolerances);
      const double candidate_cost = poseCost(candidate, scene.part.diameter_mm);
      if (candidate_cost < cost) {
        cost = candidate_cost;
        e = std::move(candidate);
      }
    }
    if (!outcome.error || cost < nearest_cost) {
      nearest_cost = cost;
      outcome.error = e;
      outcome.nearest_instance_id = truth.instances[i].id;
    }
    if (e.within_tolerance && !matched[i] && (!match_error || cost < match_cost)) {
      match_cost = cost;
      match_error = std::move(e);
      outcome.instance_id = static_cast<int>(i); // index for now, id below
    }
  }
  if (match_error) {
    const auto index = static_cast<std::size_t>(outcome.instance_id);
    matched[index] = true;
    outcome.true_positive = true;
    outcome.instance_id = truth.instances[index].id;
    outcome.counts_for_recall =
        truth.instances[index].visible_fraction >= scene.tolerances.min_visible_fraction;
    outcome.error = std::move(match_error);
    outcome.nearest_instance_id = outcome.instance_id;
  }
  return outcome;
}

} // namespace

SceneEvaluation evaluateScene(GroundTruth scene_truth, const ResultsFile& results,
                              const GroundTruth& teach, const Tolerances& tolerances,
                              const std::string& name,
                              const std::vector<const GroundTruth*>& view_teach) {
  const auto kept = std::make_shared<const GroundTruth>(std::move(scene_truth));
  const GroundTruth& truth = *kept;
  const TruthInstance& taught = taughtInstance(view_teach.empty() ? teach : *view_teach.front());
  const auto part_it = truth.parts.contains(taught.part) ? truth.parts.find(taught.part)
                                                         : teach.parts.find(taught.part);
  const PartInfo& part = part_it->second;
  const auto group = symmetryGroup(part.symmetry, part.diameter_mm);
  const std::vector<Eigen::Isometry3d> T_model_part =
      modelFramesInPart(results, view_teach, taught);

  SceneEvaluation scene;
  scene.name = name;
  scene.part = taught.part;
  scene.total_ms = results.total_ms;
  scene.truth = kept;
  std::vector<std::size_t> targets;
  for (std::size_t i = 0; i < truth.instances.size(); ++i) {
    if (truth.instances[i].part != taught.part)
      continue;
    targets.push_back(i);
    ++scene.instances;
    if (truth.instances[i].visible_fraction >= tolerances.min_visible_fraction)
      ++scene.visible_instances;
  }

  // Greedy by score: the best-scored detection claims its instance first, so a duplicate of an
  // already found instance is a false positive, and any score threshold keeps a prefix.
  std::vector<std::size_t> order(results.detections.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return results.detections[a].score > results.detections[b].score;
  });
  const SceneTargets judged{truth, part, group, targets, tolerances};
  std::vector<bool> matched(truth.instances.size(), false);
  for (const std::size_t d : order) {
    const ResultDetection& detection = results.detections[d];
    if (detection.model >= T_model_part.size())
      throw Error(results.source + ": detection " + std::to_string(detection.id) +
                  " names a model the file does not list");
    scene.outcomes.push_back(
        judgeDetection(detection, T_model_part[detection.model], judged, matched));
  }
  return scene;
}

Summary summarize(const std::vector<SceneEvaluation>& scenes, const std::string& label) {
  Summary s;
  s.label = label;
  struct Pooled {
    double score;
    bool tp, recall;
  };
  std::vector<Pooled> pooled;
  std::vector<double> translation, rotation, grip, time, render_tp, render_fp, render_ambiguous;
  for (const auto& scene : scenes) {
    ++s.scenes;
    s.instances += scene.instances;
    s.visible_instances += scene.visible_instances;
    if (scene.total_ms)
      time.push_back(*scene.total_ms);
    for (const auto& o : scene.outcomes) {
      ++s.detections;
      pooled.push_back({o.score, o.true_positive, o.counts_for_recall});
      if (o.render_difference)
        (o.true_positive ? render_tp : render_fp).push_back(*o.render_difference);
      if (o.ambiguity_render_difference)
        render_ambiguous.push_back(*o.ambiguity_render_difference);
      if (!o.true_positive)
        continue;
      ++s.true_positives;
      s.recalled_visible += o.counts_for_recall ? 1 : 0;
      translation.push_back(o.error->translation_mm);
      rotation.push_back(o.error->rotation_deg);
      grip.insert(grip.end(), o.error->grip_mm.begin(), o.error->grip_mm.end());
    }
  }
  if (s.detections > 0)
    s.precision = static_cast<double>(s.true_positives) / s.detections;
  if (s.visible_instances > 0)
    s.recall = static_cast<double>(s.recalled_visible) / s.visible_instances;

  // Sweep the score threshold: greedy matching per scene makes every threshold's matching the
  // prefix of the score order, so pooled prefixes give each threshold's precision and recall.
  std::stable_sort(pooled.begin(), pooled.end(),
                   [](const Pooled& a, const Pooled& b) { return a.score > b.score; });
  std::vector<std::pair<double, double>> curve; // (recall, precision) per threshold
  int tp = 0, recalled = 0;
  for (std::size_t k = 0; k < pooled.size(); ++k) {
    tp += pooled[k].tp ? 1 : 0;
    recalled += pooled[k].recall ? 1 : 0;
    if (k + 1 < pooled.size() && pooled[k + 1].score == pooled[k].score)
      continue; // a threshold keeps all detections of equal score
    const double precision = static_cast<double>(tp) / static_cast<double>(k + 1);
    const double recall =
        s.visible_instances > 0 ? static_cast<double>(recalled) / s.visible_instances : 0.0;
    curve.emplace_back(recall, precision);
    if (precision >= 0.99 && recall >= s.recall_at_99_precision) {
      s.recall_at_99_precision = recall;
      s.threshold_at_99_precision = pooled[k].score;
    }
  }
  // Interpolated precision: the best precision at this recall or beyond.
  double previous_recall = 0.0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    double best_precision = 0.0;
    for (std::size_t j = i; j < curve.size(); ++j)
      best_precision = std::max(best_precision, curve[j].second);
    s.average_precision += (curve[i].first - previous_recall) * best_precision;
    previous_recall = curve[i].first;
  }

  s.translation_mm = computeStats(std::move(translation));
  s.rotation_deg = computeStats(std::move(rotation));
  s.grip_mm = computeStats(std::move(grip));
  s.time_ms = computeStats(std::move(time));
  s.render_difference_tp = computeStats(std::move(render_tp));
  s.render_difference_fp = computeStats(std::move(render_fp));
  s.render_difference_ambiguous = computeStats(std::move(render_ambiguous));
  return s;
}

const GroundTruth& selectTeachTruth(const std::vector<GroundTruth>& teach_truths,
                                    const ResultsFile& results, const GroundTruth& truth) {
  if (teach_truths.empty())
    throw Error("no teach ground truth: pass --teach-truth with the teach scene's .gt.json");
  if (teach_truths.size() == 1)
    return teach_truths.front();
  const auto cloudName = [](const std::string& path) {
    return std::filesystem::path(path).filename().string();
  };
  // The model's own teach scan first, when the results name it.
  if (!results.models.empty() && !results.models.front().teach_scan.empty())
    for (const auto& teach : teach_truths)
      if (cloudName(teach.cloud) == cloudName(results.models.front().teach_scan))
        return teach;
  // A part's usual teach scene (<part>.pcd) before its other sides (<part>-side1.pcd, ...).
  const auto teachOf = [&](const std::string& part) -> const GroundTruth* {
    const GroundTruth* any = nullptr;
    for (const auto& teach : teach_truths)
      if (teach.instances.size() == 1 && teach.instances.front().part == part) {
        if (cloudName(teach.cloud) == part + ".pcd")
          return &teach;
        if (!any)
          any = &teach;
      }
    return any;
  };
  if (const GroundTruth* teach = teachOf(results.model_name))
    return *teach;
  // A model named by the operator ("bracket-v2") on a one-part scene: that part's teach scene.
  if (truth.parts.size() == 1)
    if (const GroundTruth* teach = teachOf(truth.parts.begin()->first))
      return *teach;
  throw Error(results.source + ": its model '" + results.model_name +
              "' matches none of the teach ground truths' parts: pass only the teach scene of "
              "the part this model was taught from");
}

std::vector<const GroundTruth*> selectViewTeachTruths(const std::vector<GroundTruth>& teach_truths,
                                                      const ResultsFile& results) {
  std::vector<const GroundTruth*> views;
  if (results.models.size() < 2)
    return views;
  for (const auto& model : results.models) {
    if (model.teach_scan.empty())
      return {};
    const std::string scan = std::filesystem::path(model.teach_scan).filename().string();
    const auto it =
        std::find_if(teach_truths.begin(), teach_truths.end(), [&](const GroundTruth& t) {
          return std::filesystem::path(t.cloud).filename().string() == scan;
        });
    if (it == teach_truths.end())
      throw Error(results.source + ": no teach ground truth for model '" + model.name +
                  "' taught from " + scan + ": pass its .gt.json with --teach-truth (or a folder)");
    views.push_back(&*it);
  }
  return views;
}

EvalReport makeReport(std::vector<SceneEvaluation> scenes, const Tolerances& tolerances) {
  EvalReport report;
  report.tolerances = tolerances;
  report.scenes = std::move(scenes);
  report.overall = summarize(report.scenes, "all");
  std::map<std::string, std::vector<SceneEvaluation>> by_part;
  for (const auto& scene : report.scenes)
    by_part[scene.part].push_back(scene);
  for (const auto& [part, group] : by_part)
    report.per_part.push_back(summarize(group, part));
  return report;
}

EvalReport evaluateFiles(const std::filesystem::path& truth_path,
                         const std::filesystem::path& results_path,
                         const std::vector<GroundTruth>& teach_truths,
                         const Tolerances& tolerances) {
  GroundTruth truth = loadGroundTruth(truth_path);
  const ResultsFile results = loadResults(results_path);
  const GroundTruth& teach = selectTeachTruth(teach_truths, results, truth);
  std::vector<SceneEvaluation> scenes;
  scenes.push_back(evaluateScene(std::move(truth), results, teach, tolerances,
                                 sceneNameOf(truth_path),
                                 selectViewTeachTruths(teach_truths, results)));
  return makeReport(std::move(scenes), tolerances);
}

std::vector<GroundTruth> findTeachTruths(const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir))
    throw Error("folder " + quoted(dir) + " does not exist");
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().ends_with(".gt.json"))
      paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  std::vector<GroundTruth> teach;
  for (const auto& path : paths) {
    GroundTruth truth = loadGroundTruth(path);
    if (truth.kind == "teach")
      teach.push_back(std::move(truth));
  }
  return teach;
}

std::vector<GroundTruth> loadTeachTruths(const std::vector<std::filesystem::path>& paths,
                                         const std::filesystem::path& suite_dir) {
  std::vector<GroundTruth> teach;
  for (const auto& path : paths) {
    if (std::filesystem::is_directory(path)) {
      auto found = findTeachTruths(path);
      if (found.empty())
        throw Error("folder " + quoted(path) +
                    " holds no teach ground truth (*.gt.json of kind "
                    "\"teach\")");
      std::move(found.begin(), found.end(), std::back_inserter(teach));
    } else {
      teach.push_back(loadGroundTruth(path));
    }
  }
  if (teach.empty() && !suite_dir.empty() && std::filesystem::is_directory(suite_dir)) {
    teach = findTeachTruths(suite_dir);
    if (teach.empty()) {
      // synth-suite writes <out>/phoxi-bin/scene-XXX and <out>/teach/<sensor>/<part>.
      std::vector<std::filesystem::path> scenes;
      for (const auto& entry : std::filesystem::directory_iterator(suite_dir))
        if (entry.path().filename().string().ends_with(".gt.json"))
          scenes.push_back(entry.path());
      std::sort(scenes.begin(), scenes.end());
      if (!scenes.empty()) {
        const std::string sensor = loadGroundTruth(scenes.front()).sensor_preset;
        auto suite = std::filesystem::absolute(suite_dir).lexically_normal();
        if (!suite.has_filename()) // "out/phoxi-bin/" names the same folder as "out/phoxi-bin"
          suite = suite.parent_path();
        const auto dir = suite.parent_path() / "teach" / sensor;
        if (!sensor.empty() && std::filesystem::is_directory(dir))
          teach = findTeachTruths(dir);
      }
    }
  }
  if (teach.empty())
    throw Error("no teach ground truth: pass --teach-truth teach.gt.json (the ground truth of the "
                "scan the model was taught from) or a folder of them");
  for (const auto& t : teach)
    if (t.instances.size() != 1)
      throw Error("teach ground truth " + t.source + " holds " +
                  std::to_string(t.instances.size()) + " instances; a teach scene holds one");
  return teach;
}

EvalReport evaluateSuite(const std::filesystem::path& suite_dir,
                         const std::filesystem::path& results_dir,
                         const std::vector<GroundTruth>& teach_truths, const Tolerances& tolerances,
                         const ProgressFn& progress) {
  if (!std::filesystem::is_directory(suite_dir))
    throw Error("suite folder '" + suite_dir.string() +
                "' does not exist (create it with "
                "scanpick-cli synth-suite)");
  if (!std::filesystem::is_directory(results_dir))
    throw Error("results folder '" + results_dir.string() +
                "' does not exist (write it with "
                "scanpick-cli recognize)");
  std::vector<std::filesystem::path> truth_paths;
  for (const auto& entry : std::filesystem::directory_iterator(suite_dir)) {
    const std::string file = entry.path().filename().string();
    if (file.starts_with("scene-") && file.ends_with(".gt.json"))
      truth_paths.push_back(entry.path());
  }
  std::sort(truth_paths.begin(), truth_paths.end());
  if (truth_paths.empty())
    throw Error("suite folder '" + suite_dir.string() + "' holds no scene-*.gt.json files");

  std::vector<SceneEvaluation> scenes;
  for (std::size_t i = 0; i < truth_paths.size(); ++i) {
    reportProgress(progress, static_cast<double>(i) / static_cast<double>(truth_paths.size()));
    const std::string name = sceneNameOf(truth_paths[i]);
    GroundTruth truth = loadGroundTruth(truth_paths[i]);
    if (truth.kind == "teach")
      continue;
    const std::filesystem::path results_path = results_dir / (name + ".json");
    if (!std::filesystem::exists(results_path))
      throw Error("no results for " + name + ": expected '" + results_path.string() +
                  "' (run scanpick-cli recognize on every scene of the suite)");
    const ResultsFile results = loadResults(results_path);
    const GroundTruth& teach = selectTeachTruth(teach_truths, results, truth);
    scenes.push_back(evaluateScene(std::move(truth), results, teach, tolerances, name,
                                   selectViewTeachTruths(teach_truths, results)));
  }
  reportProgress(progress, 1.0);
  return makeReport(std::move(scenes), tolerances);
}

} // namespace scanpick::core::eval
