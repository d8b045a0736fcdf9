#pragma once
/// @file Settle.h
/// Letting a pile settle again after parts are taken out of it (a robot's pick), with the same
/// Bullet physics that built it (SceneBuilder.cpp, where settleScene is defined).

#include "core/sim/Scene.h"

#include <vector>

namespace scanpick::core {

/// The scene without the instances whose ids are in `removed_ids`, after the rest have settled:
/// Bullet restarts from the instances' current poses (world frame, at rest, no velocity) in the
/// scene's environment (bin or table, as buildScene makes it) and steps until every part rests or
/// `max_seconds` of simulated time have passed. The kept instances keep their order and part and
/// are renumbered 0..m-1 (the renderer and the ground truth index instances by id): instance k of
/// the result is the k-th instance of `scene` that was kept. An id that names no instance is
/// ignored. Deterministic for a given scene and list. Camera, bin and parts are unchanged.
Scene settleScene(const Scene& scene, const std::vector<int>& removed_ids,
                  double max_seconds = 3.0);

} // namespace scanpick::core
