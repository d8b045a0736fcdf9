#pragma once
/// @file ViewParams.h
/// Parameters one view of a part sets for itself (beyond the thesis): a part taught on several
/// sides is searched with one parameter set, but a view may need its own matching settings (a
/// thin plate seen edge-on verifies poorly even in its own scan; a flat view casts few votes per
/// reference point). Only matching parameters can differ per view: the scene stages before
/// matching run once for all views.

#include "core/params/Parameters.h"

#include <map>
#include <string>

namespace scanpick::core {

/// Parameter key (as in the metadata table, e.g. "matching.min_coverage") → value, exchanged as
/// the table does (a number; booleans 0/1, enums by index).
using ViewParams = std::map<std::string, double>;

/// Throws Error unless `key` names a matching parameter and `value` lies in its range (and is a
/// whole number for an integer, boolean or enum parameter).
void checkViewParam(const std::string& key, double value);

/// `params` with the view's own values in place (each checked as by checkViewParam).
RecognitionParams withViewParams(RecognitionParams params, const ViewParams& view);

/// Moves the view's own values into `params` and empties `view`: for an editor that shows one
/// view's parameters and tunes them (the GUI's parameter panel).
void foldViewParams(RecognitionParams& params, ViewParams& view);

} // namespace scanpick::core
