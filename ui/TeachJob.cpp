#include "ui/TeachJob.h"

#include "ui/panels/ParameterPanel.h"

namespace scanpick::ui {

TeachOutcome teachPart(const core::PointCloud& part_mm, const core::TeachOptions& options,
                       const core::RecognitionParams& panel,
                       const std::set<std::string>& hand_edits, bool derive,
                       const core::ProgressFn& progress) {
  TeachOutcome outcome;
  if (!derive) {
    outcome.model =
        std::make_shared<const core::TaughtModel>(core::teach(part_mm, options, panel, progress));
    return outcome;
  }
  // The core's defaults as the base, as `scanpick-cli teach` with no preset derives.
  outcome.derived = core::autoTeachParams(part_mm, options, core::RecognitionParams{},
                                          core::subProgress(progress, 0.0, 0.3));
  const core::RecognitionParams params = withHandEdits(outcome.derived->params, panel, hand_edits);
  core::TaughtModel model =
      core::teach(part_mm, options, params, core::subProgress(progress, 0.3, 1.0));
  for (const core::DerivedValue& v : outcome.derived->values)
    if (hand_edits.count(v.key) == 0)
      model.param_reasons[v.key] = v.reason;
  outcome.model = std::make_shared<const core::TaughtModel>(std::move(model));
  return outcome;
}

} // namespace scanpick::ui
