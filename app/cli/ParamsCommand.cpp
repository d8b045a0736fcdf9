// scanpick-cli params: the parameter table (key, label, unit, default, range, stage,
// description), as text or as the Markdown of docs/parameters.md, optionally with a preset's
// values.
#include "app/cli/CliCommon.h"
#include "app/cli/Commands.h"
#include "app/cli/RecipeOptions.h"
#include "core/params/ParameterDocs.h"
#include "core/params/ParamsJson.h"

#include <iostream>
#include <memory>
#include <optional>

namespace scanpick::cli {

void registerParamsCommand(CLI::App& app) {
  struct Options {
    bool markdown = false;
    std::string preset;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = addCommand(
      app, "params",
      "Print the recognition parameters (key, label, unit, default, range, stage, description).\n"
      "docs/parameters.md is the output of `scanpick-cli params --markdown`.",
      [options] {
        std::optional<core::RecognitionParams> values;
        std::string name;
        if (!options->preset.empty()) {
          const core::Preset preset = core::loadPreset(findPreset(options->preset));
          values = preset.params;
          name = preset.name;
        }
        std::cout << (options->markdown ? core::parametersMarkdown(values, name)
                                        : core::parametersText(values));
        return kOk;
      });
  sub->add_flag("--markdown", options->markdown, "Markdown tables (as in docs/parameters.md)");
  sub->add_option("--preset", options->preset,
                  "Also show this preset's values: a name in resources/presets or a file");
}

} // namespace scanpick::cli
