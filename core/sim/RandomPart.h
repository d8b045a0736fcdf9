#pragma once
/// @file RandomPart.h
/// Industrial-like parts generated from a seed, for a benchmark that no one can tune to: plates
/// with holes and ribs, L/T/U brackets, n-sided prisms with bores and shafts, stepped bushings,
/// bolted flanges with hubs and extrusions of random profiles, 20-300 mm across. Each is a union
/// of closed primitive solids, and its symmetries are known by construction.

#include "core/sim/Part.h"

#include <cstdint>
#include <optional>
#include <string>

namespace scanpick::core {

/// The families randomPart() draws from.
enum class RandomPartFamily {
  Plate,
  LBracket,
  TBracket,
  UChannel,
  Prism,
  Bushing,
  Flange,
  Extrusion
};
inline constexpr int kRandomPartFamilies = 8;

/// The part of `seed`: its family, proportions and size (its bounding box's longest side 20-300 mm,
/// log-uniform) all follow from the seed, the same on every machine. Named "random-<seed>", resting
/// as built on z = 0 (its natural pose on a table), with a grip point on its top and its exact
/// symmetries (discrete rotations, or a continuous axis for a surface of revolution).
Part randomPart(std::uint64_t seed);

/// The family of randomPart(seed).
RandomPartFamily randomPartFamily(std::uint64_t seed);

/// Readable name of a family ("plate", "l-bracket", ...).
std::string toString(RandomPartFamily family);

/// The seed of a part name "random-<seed>", or nothing for another name.
std::optional<std::uint64_t> randomPartSeed(const std::string& name);

} // namespace scanpick::core
