#pragma once
/// @file ParameterTable.h
/// The one metadata table of recognition parameters: key, type, default, range, step, unit and a
/// description in the thesis's terms. The GUI builds its editors from it; presets use its keys.

#include "core/params/Parameters.h"

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace scanpick::core {

/// Pipeline stages, in execution order. Changing a parameter invalidates its stage and later ones.
enum class Stage { Preprocess, Clustering, Keypoints, Features, Matching, Refine };

/// Type of a parameter's value (all are exchanged as double; Bool is 0/1, Enum is the index).
enum class ParamType { Double, Int, Bool, Enum };

/// Metadata of one parameter.
struct ParamInfo {
  std::string key;         ///< dotted key, e.g. "keypoints.position_range_mm"
  std::string label;       ///< short name as in the thesis, e.g. "Neig. position range Δp"
  std::string unit;        ///< "mm", "rad", "deg", "points", "" ...
  std::string description; ///< what it does, for tooltips and docs
  /// One of the few an engineer tunes for a cell (kTunedParameters; the GUI shows them first).
  /// The others are advanced: teach derives them from the part and the scan.
  bool tuned = false;
  Stage stage;
  ParamType type;
  double min_value;
  double max_value;
  double step;
  std::vector<std::string> choices; ///< Enum only: names by index
  std::function<double(const RecognitionParams&)> get;
  std::function<void(RecognitionParams&, double)> set; ///< clamps to [min, max]
};

/// The keys of the parameters an engineer tunes for a cell, in the order the GUI shows them: the
/// floor, the split into objects, how much of the part a detection must show and within what
/// tolerance, how many detections, and ICP. The rest is derived at teach (or set by a preset).
inline constexpr std::string_view kTunedParameters[] = {"floor.enabled",
                                                        "floor.distance_mm",
                                                        "floor.max_planes",
                                                        "clustering.enabled",
                                                        "matching.verify_tolerance_mm",
                                                        "matching.min_coverage",
                                                        "matching.max_detections",
                                                        "refine.enabled"};

/// All parameters, grouped by stage in pipeline order.
std::span<const ParamInfo> parameterTable();

/// The entry for `key`, or nullptr.
const ParamInfo* findParameter(std::string_view key);

/// Throws Error unless `value` is a valid value of `info`: finite, within [min, max], and a whole
/// number unless the parameter is a Double ("'KEY' = V is outside its range MIN – MAX").
void checkParamValue(const ParamInfo& info, double value);

/// Human-readable stage name ("First-level keypoints", ...).
std::string stageName(Stage stage);

/// The earliest stage whose parameters differ between `a` and `b`, or nullopt when all are equal.
/// A changed seed counts from Stage::Preprocess (floor removal is the first stage that samples).
std::optional<Stage> firstChangedStage(const RecognitionParams& a, const RecognitionParams& b);

} // namespace scanpick::core
