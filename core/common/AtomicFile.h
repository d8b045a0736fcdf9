#pragma once
/// @file AtomicFile.h
/// Atomic file writes: data go to a temporary file in the destination folder, which is renamed
/// over the destination only when complete, so readers never see a partial file.

#include "core/common/Progress.h"

#include <filesystem>
#include <functional>
#include <string_view>

namespace scanpick::core {

/// Writes `contents` to `path` atomically. Throws Error (with the path and the OS reason) on
/// failure; the destination is then untouched and no temporary file is left.
void writeFileAtomic(const std::filesystem::path& path, std::string_view contents);

/// Calls `write(tmp_path)` to produce the file at a temporary path next to `path`, then renames it
/// into place. If `write` throws, the temporary file is removed and the exception propagates.
void writeFileAtomicWith(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp_path)>& write);

/// Checks, before any work is done, that `path` can be written: its folder exists and is writable
/// and `path` is not a folder. Throws Error saying which.
void checkWritable(const std::filesystem::path& path);

/// Reads a whole file, reporting the share of its bytes read to `progress` (1 MB at a time; it
/// may cancel); throws Error if it is missing or unreadable.
std::string readFile(const std::filesystem::path& path, const ProgressFn& progress = {});

} // namespace scanpick::core
