// Large arrays on 2 MiB pages. Linux leaves transparent huge pages to madvise on many machines
// (Debian's default), and there a fresh array's first touch takes one page fault per 4 KiB: on
// a virtual machine, where a fault is dear, the faults of a 1 M-triangle scene build cost more
// than its SAH binning. Advising a range before it is first written lets each fault map 2 MiB.
#pragma once

#include <cstddef>
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

}  // namespace prism
