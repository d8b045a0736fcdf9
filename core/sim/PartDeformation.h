#pragma once
/// @file PartDeformation.h
/// Shape variation between instances of one part, as between pears of one kind or bent sheet-metal
/// parts (the thesis's §5.4 recognizes pears with a model taught from another pear): each
/// instance's mesh is stretched, sheared and bent a little, about the part's centre, so that its
/// pose (the part frame) stays that of the part as designed.

#include "core/sim/Part.h"

#include <cstdint>

namespace scanpick::core {

/// Largest deformation fraction deformedPart accepts (the error messages say 0.3).
inline constexpr double kMaxDeformation = 0.3;

/// `part` with its components deformed by up to `fraction` (0 .. kMaxDeformation), drawn from
/// `seed`: each axis stretched or squeezed by a factor in [1 − f, 1 + f], each pair of axes sheared
/// by up to f / 2, and the part bent along its longest axis so that its ends move by up to f times
/// half its length across it. The map keeps the bounding-box centre; grip points and symmetries
/// stay those of the part as designed. fraction 0 returns `part` unchanged. Throws Error for a
/// fraction outside [0, kMaxDeformation].
Part deformedPart(const Part& part, double fraction, std::uint64_t seed);

} // namespace scanpick::core
