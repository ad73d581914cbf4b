#include "util/HugePages.h"

#include <cstdint>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace prism {

void preferHugePages(const void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Below two huge pages the aligned span inside may be empty; not worth the system call.
  if (data == nullptr || bytes < 2 * kHugePageBytes) return;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(data);
  const uintptr_t first = (begin + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const uintptr_t last = (begin + bytes) & ~(kHugePageBytes - 1);
  if (last <= first) return;
  // Advice only: an error (no THP in this kernel, a range not from mmap) changes nothing.
  madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

void* allocateHugePageBlock(size_t bytes) {
  void* block = ::operator new (bytes, std::align_val_t{kHugePageBytes});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const size_t whole = bytes & ~(kHugePageBytes - 1);
  if (whole > 0) madvise(block, whole, MADV_HUGEPAGE);  // advice only: an error changes nothing
#endif
  return block;
}

void releaseHugePageBlock(void* block) noexcept {
  ::operator delete (block, std::align_val_t{kHugePageBytes});
}

}  // namespace prism
