#include "core/common/Memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace scanpick::core {

void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  // By default glibc gives memory back once about twice the largest block freed so far lies free
  // at the heap's top, so each scene mapped its buffers afresh. It accepts at most half its
  // 64 MiB heap size as the mapping threshold.
  constexpr int kMib = 1024 * 1024;
  mallopt(M_MMAP_THRESHOLD, 32 * kMib);
  mallopt(M_TRIM_THRESHOLD, 512 * kMib);
#endif
}

} // namespace scanpick::core
