// Large arrays on 2 MiB pages. Linux leaves transparent huge pages to madvise on many machines
// (Debian's default), and there a fresh array's first touch takes one page fault per 4 KiB: on
// a virtual machine, where a fault is dear, the faults of a 1 M-triangle scene build cost more
// than its SAH binning. Advising a range before it is first written lets each fault map 2 MiB.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace prism {

// Asks the kernel to back [data, data + bytes) with huge pages where it can. Only whole, aligned
// 2 MiB spans inside the range qualify; ranges under 4 MiB are left alone (they may hold no such
// span), as is everything on systems without transparent huge pages. Never fails.
void preferHugePages(const void* data, size_t bytes);

// v.reserve(n), with the reserved storage on huge pages before anything is written to it.
template <class T, class Allocator>
void reserveOnHugePages(std::vector<T, Allocator>& v, size_t n) {
  v.reserve(n);
  preferHugePages(v.data(), v.capacity() * sizeof(T));
}

constexpr size_t kHugePageBytes = size_t{2} << 20;

// `bytes` (at least kHugePageBytes) starting on a 2 MiB boundary, every whole huge page in it
// advised before first touch: where reserveOnHugePages' storage starts wherever malloc put it
// and loses the pages at both ends, this loses only the last partial one. Free with
// releaseHugePageBlock. Throws std::bad_alloc.
void* allocateHugePageBlock(size_t bytes);
void releaseHugePageBlock(void* block) noexcept;

// For large arrays written once and read often (the caustic map's texels): blocks of a huge page
// or more come from allocateHugePageBlock, smaller ones from operator new as usual. A map built
// in 4 KiB pages spent a third of its time in page faults on a virtual machine.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (n * sizeof(T) < kHugePageBytes) return std::allocator<T>().allocate(n);
    return static_cast<T*>(allocateHugePageBlock(n * sizeof(T)));
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) < kHugePageBytes) {
      std::allocator<T>().deallocate(p, n);
    } else {
      releaseHugePageBlock(p);
    }
  }
  friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace prism
