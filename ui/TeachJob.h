#pragma once
/// @file TeachJob.h
/// What the Teach action runs on its worker thread: with the parameters derived from the part and
/// the scan (the Parameters panel's default choice) or with the panel's parameters as they are.

#include "core/model/TaughtModel.h"

#include <memory>
#include <optional>
#include <set>
#include <string>

namespace scanpick::ui {

/// What the teach job hands back to the GUI thread.
struct TeachOutcome {
  std::shared_ptr<const core::TaughtModel> model;
  /// The derivation (measures, values, reasons) when the parameters were derived; empty when
  /// they were the panel's.
  std::optional<core::AutoParams> derived;
};

/// Teaches a model from `part_mm` (the working cloud, scan frame) cut as `options` say. With
/// `derive`: core::autoTeachParams over the core's defaults (progress 0–0.3), then the values of
/// `hand_edits` (ParameterPanel::handEdits) taken from `panel` over the derived ones, as --set
/// does on the CLI, then core::teach with them; each derived value not set by hand keeps its
/// reason in TaughtModel::param_reasons. Without: core::teach with `panel` as it is. Throws what
/// they throw (core::Error, core::Cancelled when `progress` asks to stop).
TeachOutcome teachPart(const core::PointCloud& part_mm, const core::TeachOptions& options,
                       const core::RecognitionParams& panel,
                       const std::set<std::string>& hand_edits, bool derive,
                       const core::ProgressFn& progress);

} // namespace scanpick::ui
