#include "core/params/ViewParams.h"

#include "core/common/Error.h"
#include "core/params/ParameterTable.h"

namespace scanpick::core {

void checkViewParam(const std::string& key, double value) {
  const ParamInfo* info = findParameter(key);
  if (!info)
    throw Error("unknown parameter '" + key + "' (keys: scanpick-cli params)");
  if (info->stage != Stage::Matching)
    throw Error("'" + key + "' cannot differ per view: only matching parameters can (the " +
                stageName(info->stage) + " stage runs once for all views)");
  checkParamValue(*info, value);
}

RecognitionParams withViewParams(RecognitionParams params, const ViewParams& view) {
  for (const auto& [key, value] : view) {
    checkViewParam(key, value);
    findParameter(key)->set(params, value);
  }
  return params;
}

void foldViewParams(RecognitionParams& params, ViewParams& view) {
  params = withViewParams(params, view);
  view.clear();
}

} // namespace scanpick::core
