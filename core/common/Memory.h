#pragma once
/// @file Memory.h
/// How the process's allocator treats the large buffers each scene needs.

namespace scanpick::core {

/// Keeps the memory the process frees for its next scene instead of handing it back to the
/// system: blocks up to 32 MiB come from the heap (not from their own mappings), and the heap is
/// trimmed only when more than 512 MiB of it are free. A scene's buffers (a PhoXi scan of 9.6 MB,
/// pixel grids of 3.2 MB each) are then reused from the second scene on instead of being mapped
/// afresh, page by page, for every scene (docs/design-notes-speed.md, "Memory"). For
/// processes that recognize scene after scene (the CLI, the application); the peak memory stays
/// in use while they run. Does nothing where the C library is not glibc. Call it once, early in
/// main().
void keepFreedMemoryForReuse();

} // namespace scanpick::core
