#pragma once
/// @file ModelFile.h
/// The `.spmodel` file: one JSON header line followed by a binary point block with its byte count
/// and CRC-32 (format in docs/model-format.md).

#include "core/model/TaughtModel.h"

#include <filesystem>
#include <string>

namespace scanpick::core {

/// Highest `.spmodel` version this build reads and the one it writes.
inline constexpr int kModelFormatVersion = 3;

/// Serializes a model (header line + binary block) into a byte string.
std::string encodeModel(const TaughtModel& model);

/// Parses bytes produced by encodeModel. `source` names the file in messages. Throws Error for a
/// file that is not a scanpick model, a future version, a truncated or oversized point block, a
/// checksum mismatch, or malformed or missing header fields (missing parameters take defaults).
TaughtModel decodeModel(const std::string& bytes, const std::string& source = "model");

/// Writes `model` to `path` atomically.
void saveModel(const std::filesystem::path& path, const TaughtModel& model);

/// Reads a `.spmodel` file (see decodeModel); throws Error for a missing file too.
TaughtModel loadModel(const std::filesystem::path& path);

} // namespace scanpick::core
