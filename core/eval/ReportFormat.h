#pragma once
/// @file ReportFormat.h
/// An evaluation report as JSON ("scanpick-eval", version 1; see docs/evaluation.md) and as a
/// plain-text table for terminals.

#include "core/eval/Evaluator.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace scanpick::core::eval {

/// The report as JSON: tolerances, "overall", "per_part" and "scenes" (with each detection's
/// outcome). Undefined ratios (no detections, no visible instances) are null.
nlohmann::ordered_json reportToJson(const EvalReport& report);

/// The report as a readable table. `details` adds a line per detection (single scenes) or per
/// scene (suites).
std::string reportToTable(const EvalReport& report, bool details);

/// Writes reportToJson atomically; throws Error when the file cannot be written.
void saveReportJson(const std::filesystem::path& path, const EvalReport& report);

} // namespace scanpick::core::eval
