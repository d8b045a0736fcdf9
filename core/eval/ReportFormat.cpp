#include "core/eval/ReportFormat.h"

#include "core/common/AtomicFile.h"
#include "core/common/JsonText.h"

#include <cstdio>
#include <sstream>

namespace scanpick::core::eval {
namespace {

/// Insertion-ordered, so the file reads top-down: format, tolerances, overall, scenes.
using Json = nlohmann::ordered_json;

Json optionalToJson(const std::optional<double>& value) {
  return value ? Json(*value) : Json(nullptr);
}

Json statsToJson(const Stats& s) {
  return {
      {"count", s.count}, {"mean", s.mean}, {"median", s.median}, {"p95", s.p95}, {"max", s.max}};
}

Json summaryToJson(const Summary& s) {
  Json out{{"label", s.label},
           {"scenes", s.scenes},
           {"detections", s.detections},
           {"true_positives", s.true_positives},
           {"false_positives", s.detections - s.true_positives},
           {"instances", s.instances},
           {"visible_instances", s.visible_instances},
           {"recalled_visible_instances", s.recalled_visible},
           {"precision", optionalToJson(s.precision)},
           {"recall", optionalToJson(s.recall)},
           {"recall_at_99_precision", s.recall_at_99_precision},
           {"threshold_at_99_precision", optionalToJson(s.threshold_at_99_precision)},
           {"average_precision", s.average_precision},
           {"translation_error_mm", statsToJson(s.translation_mm)},
           {"rotation_error_deg", statsToJson(s.rotation_deg)},
           {"grip_error_mm", statsToJson(s.grip_mm)},
           {"time_per_scene_ms", statsToJson(s.time_ms)}};
  if (s.render_difference_tp.count + s.render_difference_fp.count > 0) {
    out["render_difference_true_positives"] = statsToJson(s.render_difference_tp);
    out["render_difference_false_positives"] = statsToJson(s.render_difference_fp);
    out["render_difference_ambiguous"] = statsToJson(s.render_difference_ambiguous);
  }
  return out;
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string ratio(const std::optional<double>& value) {
  return value ? format("%.3f", *value) : std::string("n/a");
}

std::string pad(const std::string& text, std::size_t width, bool left = false) {
  if (text.size() >= width)
    return text;
  const std::string fill(width - text.size(), ' ');
  return left ? text + fill : fill + text;
}

void writeStatsRow(std::ostringstream& out, const std::string& what, const Stats& s) {
  out << "  " << pad(what, 28, true);
  if (s.count == 0) {
    out << pad("-", 10) << pad("-", 10) << pad("-", 10) << pad("0", 7) << "\n";
    return;
  }
  out << pad(format("%.3f", s.median), 10) << pad(format("%.3f", s.p95), 10)
      << pad(format("%.3f", s.max), 10) << pad(std::to_string(s.count), 7) << "\n";
}

} // namespace

nlohmann::ordered_json reportToJson(const EvalReport& report) {
  Json doc{{"format", "scanpick-eval"},
           {"version", 1},
           {"units", "mm"},
           {"tolerances",
            {{"translation_fraction_of_diameter", report.tolerances.translation_fraction},
             {"rotation_deg", report.tolerances.rotation_deg},
             {"min_visible_fraction", report.tolerances.min_visible_fraction},
             {"accept_free_turns", report.tolerances.accept_free_turns}}},
           {"overall", summaryToJson(report.overall)}};
  doc["per_part"] = Json::array();
  for (const auto& s : report.per_part)
    doc["per_part"].push_back(summaryToJson(s));
  doc["scenes"] = Json::array();
  for (const auto& scene : report.scenes) {
    Json detections = Json::array();
    for (const auto& o : scene.outcomes) {
      Json d{{"id", o.detection_id},
             {"score", o.score},
             {"true_positive", o.true_positive},
             {"instance", o.true_positive ? Json(o.instance_id) : nullptr},
             {"nearest_instance", o.error ? Json(o.nearest_instance_id) : Json(nullptr)}};
      if (o.error) {
        d["translation_error_mm"] = o.error->translation_mm;
        d["rotation_error_deg"] = o.error->rotation_deg;
        d["grip_error_mm"] = o.error->grip_mm;
      }
      if (o.render_difference)
        d["render_difference"] = *o.render_difference;
      if (o.ambiguity_render_difference)
        d["ambiguity_render_difference"] = *o.ambiguity_render_difference;
      detections.push_back(std::move(d));
    }
    doc["scenes"].push_back({{"name", scene.name},
                             {"part", scene.part},
                             {"instances", scene.instances},
                             {"visible_instances", scene.visible_instances},
                             {"total_ms", optionalToJson(scene.total_ms)},
                             {"detections", std::move(detections)}});
  }
  return doc;
}

std::string reportToTable(const EvalReport& report, bool details) {
  std::ostringstream out;
  const auto& t = report.tolerances;
  out << "true positive: origin within " << format("%g", t.translation_fraction)
      << " x diameter and rotation within " << format("%g", t.rotation_deg)
      << " deg (symmetry-aware" << (t.accept_free_turns ? ", and up to reported free turns" : "")
      << "); recall over instances at least " << format("%g", t.min_visible_fraction * 100.0)
      << " % visible\n\n";

  out << pad("part", 18, true) << pad("scenes", 7) << pad("det", 6) << pad("TP", 6) << pad("FP", 6)
      << pad("visible", 9) << pad("precision", 11) << pad("recall", 8) << pad("R@P99", 8)
      << pad("AP", 7) << "\n";
  std::vector<const Summary*> rows{&report.overall};
  if (report.per_part.size() > 1)
    for (const auto& s : report.per_part)
      rows.push_back(&s);
  for (const Summary* s : rows)
    out << pad(s->label, 18, true) << pad(std::to_string(s->scenes), 7)
        << pad(std::to_string(s->detections), 6) << pad(std::to_string(s->true_positives), 6)
        << pad(std::to_string(s->detections - s->true_positives), 6)
        << pad(std::to_string(s->visible_instances), 9) << pad(ratio(s->precision), 11)
        << pad(ratio(s->recall), 8) << pad(format("%.3f", s->recall_at_99_precision), 8)
        << pad(format("%.3f", s->average_precision), 7) << "\n";

  for (const Summary* s : rows) {
    out << "\nerrors of true positives (" << s->label << ")" << pad("median", 10) << pad("p95", 10)
        << pad("max", 10) << pad("n", 7) << "\n";
    writeStatsRow(out, "translation at origin (mm)", s->translation_mm);
    writeStatsRow(out, "rotation (deg)", s->rotation_deg);
    writeStatsRow(out, "at grip points (mm)", s->grip_mm);
    writeStatsRow(out, "time per scene (ms)", s->time_ms);
    if (s->render_difference_tp.count + s->render_difference_fp.count > 0) {
      out << "render check (" << s->label << "): share of pixels seen differently\n";
      writeStatsRow(out, "true positives", s->render_difference_tp);
      writeStatsRow(out, "false positives", s->render_difference_fp);
      writeStatsRow(out, "reported ambiguities", s->render_difference_ambiguous);
    }
  }

  if (details) {
    out << "\n";
    if (report.scenes.size() == 1) {
      out << pad("detection", 10) << pad("score", 8) << pad("result", 8) << pad("instance", 10)
          << pad("t err mm", 10) << pad("r err deg", 11) << pad("render", 8) << "\n";
      for (const auto& o : report.scenes.front().outcomes)
        out << pad(std::to_string(o.detection_id), 10) << pad(format("%.3f", o.score), 8)
            << pad(o.true_positive ? "TP" : "FP", 8)
            << pad(o.error ? std::to_string(o.nearest_instance_id) : "-", 10)
            << pad(o.error ? format("%.3f", o.error->translation_mm) : "-", 10)
            << pad(o.error ? format("%.2f", o.error->rotation_deg) : "-", 11)
            << pad(o.render_difference ? format("%.3f", *o.render_difference) : "-", 8) << "\n";
    } else {
      out << pad("scene", 18, true) << pad("part", 18, true) << pad("det", 5) << pad("TP", 5)
          << pad("visible", 9) << pad("ms", 10) << "\n";
      for (const auto& scene : report.scenes) {
        int tp = 0;
        for (const auto& o : scene.outcomes)
          tp += o.true_positive ? 1 : 0;
        out << pad(scene.name, 18, true) << pad(scene.part, 18, true)
            << pad(std::to_string(scene.outcomes.size()), 5) << pad(std::to_string(tp), 5)
            << pad(std::to_string(scene.visible_instances), 9)
            << pad(scene.total_ms ? format("%.1f", *scene.total_ms) : "-", 10) << "\n";
      }
    }
  }
  return out.str();
}

void saveReportJson(const std::filesystem::path& path, const EvalReport& report) {
  writeFileAtomic(path, dumpJsonText(reportToJson(report), 2) + "\n");
}

} // namespace scanpick::core::eval
